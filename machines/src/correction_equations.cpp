#include "vc/machine/correction_equations.hpp"

#include <algorithm>
#include <cmath>

namespace vc::machine {
namespace {

using Eigen::Vector3d;

// Two unit vectors perpendicular to k (and to each other).
std::array<Vector3d, 2> perpendicular_basis(const Vector3d& k) {
  Eigen::Index smallest;
  k.cwiseAbs().minCoeff(&smallest);
  const Vector3d b1 = k.cross(Vector3d::Unit(smallest)).normalized();
  return {b1, k.cross(b1)};
}

}  // namespace

CorrectionTarget position_target(const ToolPose& ideal) noexcept { return {ideal.tip_mm, ideal.direction, {}, 0}; }

CorrectionTarget full_target(const Model& model, const ToolPose& ideal, const PoseDerivatives& d) noexcept {
  CorrectionTarget target = position_target(ideal);
  const int rotary = model.rotary_count();
  target.direction_equations = rotary;
  if (rotary == 2) {
    target.basis = perpendicular_basis(ideal.direction);
  } else {
    for (int j = 0; j < model.joint_count(); ++j)
      if (model.axes[j].type == AxisType::Rotary) target.basis[0] = d.axis_line.col(j).normalized();
  }
  return target;
}

Joints correction_residual(const CorrectionTarget& target, const ToolPose& pose, int equations) noexcept {
  Joints r(equations);
  r.head(3) = pose.tip_mm - target.tip_mm;
  const Vector3d dir_error = target.direction.cross(pose.direction);
  for (int m = 0; m < target.direction_equations; ++m) r[3 + m] = target.basis[m].dot(dir_error);
  return r;
}

SquareMatrix correction_jacobian(const CorrectionTarget& target, const PoseDerivatives& d,
                                 const std::array<int, kMaxAxes>& index, int unknowns) noexcept {
  SquareMatrix jacobian(unknowns, unknowns);
  for (int c = 0; c < unknowns; ++c) {
    const int j = index[c];
    jacobian.block(0, c, 3, 1) = d.tip.col(j);
    const Vector3d ddir = target.direction.cross(d.direction.col(j));
    for (int m = 0; m < target.direction_equations; ++m) jacobian(3 + m, c) = target.basis[m].dot(ddir);
  }
  return jacobian;
}

// Each rotary axis line l makes atan2(|l x k|, |l . k|) with the tool direction k, whatever
// l's length; the smallest is found by comparing the pairs (a1 b2 < a2 b1), so one atan2 is
// taken for all axes.
double pole_angle_at(const Model& model, const ToolPose& ideal, const PoseDerivatives& d) noexcept {
  double across = 1.0, along = 0.0;  // pi / 2: no rotary axis
  for (int j = 0; j < model.joint_count(); ++j) {
    if (model.axes[j].type != AxisType::Rotary) continue;
    const Vector3d line = d.axis_line.col(j);
    const double a = line.cross(ideal.direction).norm(), b = std::abs(line.dot(ideal.direction));
    if (a * along < across * b) {
      across = a;
      along = b;
    }
  }
  return std::atan2(across, along);
}

}  // namespace vc::machine
