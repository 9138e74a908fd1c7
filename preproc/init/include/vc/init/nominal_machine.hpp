// The machine file init writes: the nominal geometry of the stock kinematics in the project's
// model (machines/README.md), zero errors, every value with where it came from.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "vc/init/linuxcnc_units.hpp"

namespace vc::init {

using Vector3 = std::array<double, 3>;

struct NominalAxis {
  char letter = 'X';
  bool rotary = false;
  Vector3 direction{}, pole_mm{};
  double travel_min = 0.0, travel_max = 0.0;
  // Comments: lines above the entry (what the axis is), then after or above each value.
  std::vector<std::string> about;
  std::string type_from, direction_from, travel_from;
  std::vector<std::string> pole_from;
};

struct NominalMachine {
  std::string name, name_from;
  std::string module;                                    // the stock kinematics module
  std::vector<std::string> remarks;                      // for the header: what the user must know or do
  std::vector<NominalAxis> tool_chain, workpiece_chain;  // bed outward
  Vector3 gauge_point_mm{};
  std::string gauge_point_from;
  double tool_length_mm = 0.0;
  std::string tool_length_from;
  double tool_length_reference_mm = 0.0;
  std::string tool_length_reference_from;
  char tool_axis_coordinate = 0;  // 5axiskins: 'W' (machines/README.md); 0: none
  std::string tool_axis_from;
  Vector3 fixture_origin_mm{};
  std::vector<std::string> fixture_from;

  // What volkins' KINEMATICS line takes over from the stock one.
  std::string coordinates;      // the joints' letters, as LinuxCNC maps them (duplicates kept)
  LinearUnits units;            // LinuxCNC's length unit (units=inch: volkins converts)
  std::string world;            // "tcp", or "" (volkins' default: the world is the axes)
  bool identity_first = false;  // sparm=identityfirst: kinematics type 0 is the identity
  // The stock module's HAL pins (without the "module." prefix), and the one that takes
  // LinuxCNC's tool length offset ("" if none).
  std::vector<std::string> pins;
  std::string tool_offset_pin;
};

}  // namespace vc::init
