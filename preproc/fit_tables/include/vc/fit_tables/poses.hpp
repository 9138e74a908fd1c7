// The poses a table set is fitted and judged on: nominal joints and a tool length.
//   - the grid: every linear joint at `levels` equally spaced positions over its travel, every
//     rotary joint at the positions asked for (default: `levels` over its travel; a full turn
//     without its repeated end when its tables are read modulo 360), at each tool length: the
//     whole volume, deterministic;
//   - fresh poses: each joint uniform over its travel (vc::machine::TravelSamples, a fixed
//     seed), drawn after one another so that two sets never share a pose.
#pragma once

#include <map>
#include <vector>

#include "vc/machine/model.hpp"
#include "vc/machine/travel_samples.hpp"

namespace vc::fit_tables {

struct Pose {
  machine::Joints q;      // nominal joints, mm and deg
  double tool_length_mm;  // L: gauge point to tool tip
};

struct GridSpec {
  int levels = 7;                              // positions per linear joint (and rotary by default)
  std::map<char, std::vector<double>> rotary;  // letter -> positions (deg), replacing the default
  std::vector<double> tool_lengths_mm;
  bool full_turn_once = false;  // a 360 deg rotary travel: leave out its end (= its start)
};

// Throws std::invalid_argument for levels < 2, no tool length, rotary positions of an axis the
// machine lacks or that is not rotary, or outside its travel.
std::vector<Pose> grid_poses(const machine::Model& model, const GridSpec& spec);

class FreshPoses {
 public:
  explicit FreshPoses(const machine::Model& model) : samples_(model) {}
  // `count` poses at each of the tool lengths (the same joints at each).
  std::vector<Pose> next(int count, const std::vector<double>& tool_lengths_mm);

 private:
  machine::TravelSamples samples_;
};

}  // namespace vc::fit_tables
