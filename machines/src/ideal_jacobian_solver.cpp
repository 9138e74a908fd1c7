#include "vc/machine/ideal_jacobian_solver.hpp"

#include <cmath>

namespace vc::machine {

IdealJacobianSolver::IdealJacobianSolver(const Model& model, int direction_equations) noexcept
    : joints_(model.joint_count()), rotary_count_(direction_equations) {
  int linear = 0, rotary = 0;
  for (int j = 0; j < joints_; ++j) {
    if (model.axes[j].type == AxisType::Linear) {
      if (linear == 3) return;  // not three linear joints: applies() stays false
      linear_[static_cast<std::size_t>(linear++)] = j;
    } else if (rotary < direction_equations) {
      rotary_[static_cast<std::size_t>(rotary++)] = j;
    }
  }
  applies_ = linear == 3 && rotary == direction_equations && direction_equations >= 0 && direction_equations <= 2;
}

bool IdealJacobianSolver::factorize(const CorrectionTarget& target, const PoseDerivatives& ideal) noexcept {
  if (!applies_ || target.direction_equations != rotary_count_) return false;
  Eigen::Matrix3d a;
  for (int k = 0; k < 3; ++k) {
    const int j = linear_[static_cast<std::size_t>(k)];
    if (!(ideal.direction.col(j).array() == 0.0).all()) return false;
    a.col(k) = ideal.tip.col(j);
  }
  Eigen::Matrix2d d = Eigen::Matrix2d::Identity();
  for (int k = 0; k < rotary_count_; ++k) {
    const int j = rotary_[static_cast<std::size_t>(k)];
    c_.col(k) = ideal.tip.col(j);
    const Eigen::Vector3d rate = target.direction.cross(ideal.direction.col(j));
    for (int m = 0; m < rotary_count_; ++m) d(m, k) = target.basis[static_cast<std::size_t>(m)].dot(rate);
  }
  double det_a = 0.0, det_d = 0.0;
  bool a_invertible = false, d_invertible = false;
  a.computeInverseAndDetWithCheck(a_inverse_, det_a, a_invertible, 0.0);
  d.computeInverseAndDetWithCheck(d_inverse_, det_d, d_invertible, 0.0);
  // A step from inverses of huge entries is not finite: the callers check the step.
  return a_invertible && d_invertible && std::isfinite(det_a) && std::isfinite(det_d);
}

Joints IdealJacobianSolver::solve(const Joints& r) const noexcept {
  Eigen::Vector2d rotary = Eigen::Vector2d::Zero();
  for (int m = 0; m < rotary_count_; ++m) rotary[m] = r[3 + m];
  rotary = d_inverse_ * rotary;
  Eigen::Vector3d tip = r.head<3>();
  for (int k = 0; k < rotary_count_; ++k) tip -= c_.col(k) * rotary[k];
  const Eigen::Vector3d linear = a_inverse_ * tip;
  Joints x = Joints::Zero(joints_);
  for (int k = 0; k < 3; ++k) x[linear_[static_cast<std::size_t>(k)]] = linear[k];
  for (int k = 0; k < rotary_count_; ++k) x[rotary_[static_cast<std::size_t>(k)]] = rotary[k];
  return x;
}

}  // namespace vc::machine
