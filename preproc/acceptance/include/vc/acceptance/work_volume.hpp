// The work volume an acceptance test spans: a box in the X, Y, Z joints (mm), by default the
// machine file's travel shrunk by 10 % of each axis's travel at each end (so the overruns
// before the reversals stay inside the travel), or given as "x0:x1,y0:y1,z0:z1".
#pragma once

#include <Eigen/Core>
#include <string>

#include "vc/machine/model.hpp"

namespace vc::acceptance {

struct WorkVolume {
  Eigen::Vector3d low_mm, high_mm;  // X, Y, Z
  Eigen::Vector3d centre() const { return (low_mm + high_mm) / 2; }
};

// The joints of X, Y, Z in `model` (throws std::runtime_error naming the missing or rotary one).
struct LinearJoints {
  int x = -1, y = -1, z = -1;
  int operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
};
LinearJoints linear_joints(const machine::Model& model);

WorkVolume default_volume(const machine::Model& model, double shrink = 0.1);

// "x0:x1,y0:y1,z0:z1" in mm, each low < high and inside the model's travel; throws
// std::runtime_error saying which part is wrong.
WorkVolume parse_volume(const machine::Model& model, const std::string& text);

}  // namespace vc::acceptance
