// B^-1 r for B the ideal machine's Jacobian of the full correction's equations (rows: tip,
// then direction; correction_equations.hpp). The ideal machine's linear joints do not turn
// the tool, so the direction rows of their columns are exactly zero and B is block
// triangular: B = [A C; 0 D] (columns: linear, then rotary joints). Two small inverses
// (3x3 and 1x1 or 2x2) then replace a general LU, several times cheaper per point.
#pragma once

#include <array>

#include "vc/machine/correction_equations.hpp"

namespace vc::predistort {

class IdealJacobianSolver {
 public:
  // Three linear joints and one or two rotary ones.
  explicit IdealJacobianSolver(const machine::Model& model);

  // Takes B; false if it is singular, or not block triangular (then solve() must not be used).
  bool factorize(const machine::SquareMatrix& b);
  // x with B x = r.
  machine::Joints solve(const machine::Joints& r) const;

 private:
  int rotary_count_ = 0;
  std::array<int, 3> linear_{};
  std::array<int, 2> rotary_{};
  Eigen::Matrix3d a_inverse_;
  Eigen::Matrix<double, 3, 2> c_;
  Eigen::Matrix2d d_inverse_;  // 1 x 1 in the top left corner with one rotary joint
};

}  // namespace vc::predistort
