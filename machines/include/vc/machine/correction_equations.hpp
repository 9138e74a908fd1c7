// The equations machine::correct() solves (model.md, Correction), for whoever solves them
// another way (the pre-distorter's one-step Newton, preproc/predistort/one_step_correction.hpp):
//     pos P(q) - pos P'(q_n) = 0                       (3 rows, mm)
//     b_m . (k'(q_n) x k(q)) = 0, m < rotary joints    (rad; b_m _|_ k', or the one axis line)
// Real-time: no allocation.
#pragma once

#include <array>

#include "vc/machine/forward.hpp"

namespace vc::machine {

// Weighs direction residuals (rad) against position ones (mm) in a residual norm.
inline constexpr double kDirectionLeverMm = 1000.0;

using SquareMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxAxes, kMaxAxes>;

// What the real machine must reach: the ideal tool tip, and the components of the direction
// error k' x k that must vanish (along each basis vector).
struct CorrectionTarget {
  Eigen::Vector3d tip_mm;
  Eigen::Vector3d direction;
  std::array<Eigen::Vector3d, 2> basis;
  int direction_equations = 0;
};

// Position only (the linear joints' equations), from the ideal pose at q_n.
CorrectionTarget position_target(const ToolPose& ideal) noexcept;
// Position and tool direction (the full correction), from the ideal pose at q_n and its
// derivatives there (which give the rotary axis lines).
CorrectionTarget full_target(const Model& model, const ToolPose& ideal, const PoseDerivatives& d) noexcept;

// Residual: tip position (mm), then direction components (rad); `equations` rows.
Joints correction_residual(const CorrectionTarget& target, const ToolPose& pose, int equations) noexcept;

// Sum of squares of a residual's direction rows (rad^2): the rows after the first three. A
// loop over at most three rows (Eigen's tail() here vectorizes into loads GCC cannot bound).
inline double direction_squared_norm(const Joints& residual) noexcept {
  double sum = 0.0;
  for (Eigen::Index i = 3; i < residual.size(); ++i) sum += residual[i] * residual[i];
  return sum;
}

// d residual / d q of the joints index[0..unknowns), from pose derivatives.
SquareMatrix correction_jacobian(const CorrectionTarget& target, const PoseDerivatives& d,
                                 const std::array<int, kMaxAxes>& index, int unknowns) noexcept;

// phi: the smallest angle between the ideal tool direction and a rotary axis line (pi/2
// without rotary joints).
double pole_angle_at(const Model& model, const ToolPose& ideal, const PoseDerivatives& d) noexcept;

}  // namespace vc::machine
