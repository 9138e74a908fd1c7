#include "vc/predistort/ideal_jacobian_solver.hpp"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

namespace vc::predistort {

IdealJacobianSolver::IdealJacobianSolver(const machine::Model& model) {
  int linear = 0;
  for (int j = 0; j < model.joint_count(); ++j) {
    if (model.axes[j].type == machine::AxisType::Linear) {
      if (linear == 3) throw std::logic_error("IdealJacobianSolver: more than three linear joints");
      linear_[static_cast<std::size_t>(linear++)] = j;
    } else {
      if (rotary_count_ == 2) throw std::logic_error("IdealJacobianSolver: more than two rotary joints");
      rotary_[static_cast<std::size_t>(rotary_count_++)] = j;
    }
  }
  if (linear != 3 || rotary_count_ == 0)
    throw std::logic_error("IdealJacobianSolver: needs three linear and one or two rotary joints");
}

bool IdealJacobianSolver::factorize(const machine::SquareMatrix& b) {
  Eigen::Matrix3d a;
  Eigen::Matrix2d d = Eigen::Matrix2d::Identity();
  for (int k = 0; k < 3; ++k) {
    const int j = linear_[static_cast<std::size_t>(k)];
    a.col(k) = b.block<3, 1>(0, j);
    for (int m = 0; m < 2; ++m)
      if (m < rotary_count_ && b(3 + m, j) != 0.0) return false;
  }
  for (int k = 0; k < 2; ++k) {
    if (k >= rotary_count_) break;
    const int j = rotary_[static_cast<std::size_t>(k)];
    c_.col(k) = b.block<3, 1>(0, j);
    for (int m = 0; m < 2; ++m)
      if (m < rotary_count_) d(m, k) = b(3 + m, j);
  }
  const double det_a = a.determinant(), det_d = d.determinant();
  if (!(std::abs(det_a) > 0.0) || !(std::abs(det_d) > 0.0) || !std::isfinite(det_a) || !std::isfinite(det_d))
    return false;
  a_inverse_ = a.inverse();
  d_inverse_ = d.inverse();
  return a_inverse_.allFinite() && d_inverse_.allFinite();
}

machine::Joints IdealJacobianSolver::solve(const machine::Joints& r) const {
  Eigen::Vector2d rotary = Eigen::Vector2d::Zero();
  for (int m = 0; m < rotary_count_; ++m) rotary[m] = r[3 + m];
  rotary = d_inverse_ * rotary;
  const Eigen::Vector3d linear = a_inverse_ * (r.head<3>() - c_.leftCols(rotary_count_) * rotary.head(rotary_count_));
  machine::Joints x(r.size());
  for (int k = 0; k < 3; ++k) x[linear_[static_cast<std::size_t>(k)]] = linear[k];
  for (int k = 0; k < rotary_count_; ++k) x[rotary_[static_cast<std::size_t>(k)]] = rotary[k];
  return x;
}

}  // namespace vc::predistort
