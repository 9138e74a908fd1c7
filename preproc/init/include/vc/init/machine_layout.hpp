// Which joint is which axis, and each axis's travel, as a LinuxCNC configuration sets them:
// the kinematics module's coordinates, [KINS]JOINTS, [TRAJ]COORDINATES, [TRAJ]LINEAR_UNITS
// and ANGULAR_UNITS, [JOINT_n] TYPE, MIN_LIMIT and MAX_LIMIT, checked against each other and
// against what the model takes (exactly three linear axes X Y Z, at most two rotary ones,
// mm or inch, deg). 5axiskins' W is no axis of the model but its tool-axis coordinate (the X, Y, Z
// joints move the tool along its own axis; machines/README.md, tool_axis_coordinate).
#pragma once

#include <string>
#include <vector>

#include "vc/init/kinematics_line.hpp"
#include "vc/init/linuxcnc_units.hpp"

namespace vc::init {

struct LayoutAxis {
  char letter = 'X';  // upper case
  int joint = 0;      // the first joint of this letter (the one the travel is read from)
  bool rotary = false;
  bool continuous = false;                    // a rotary joint without limits: travel one turn, 0 .. 360 deg
  double travel_min = 0.0, travel_max = 0.0;  // mm or deg (converted from an inch configuration's)
  std::string type_from;                      // where its TYPE is written, or that it is not
  std::string travel_from;
};

struct MachineLayout {
  std::string coordinates;       // one letter per joint, as the module maps them (duplicates kept)
  std::string coordinates_from;  // where that comes from
  std::vector<LayoutAxis> axes;  // one per letter, in XYZABC order (not the tool-axis coordinate)
  char tool_axis = 0;            // 5axiskins: 'W', the tool-axis coordinate; else 0
  int tool_axis_joint = -1;      // its first joint
  LinearUnits units;             // LinuxCNC's length unit: the travel above is converted to mm

  const LayoutAxis* axis(char letter) const;
};

// Throws vc::LoadError (file:line) with what is inconsistent or what the model cannot take.
MachineLayout read_layout(const LinuxcncIni& ini, const KinematicsLine& kinematics);

}  // namespace vc::init
