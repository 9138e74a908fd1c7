// Newton steps with B, the ideal machine's Jacobian of the correction equations (rows: tip,
// then direction; correction_equations.hpp), solved by blocks. The ideal machine's linear
// joints do not turn the tool, so the direction rows of their columns are exactly zero and B
// is block triangular: B = [A C; 0 D] (columns: the three linear joints, then the rotary
// joints with direction equations). Two closed-form inverses (3 x 3, and 1 x 1 or 2 x 2)
// replace a pivoting LU: several times cheaper per step, and a fraction of its code, which is
// what the servo thread pays for (it fetches its code anew every cycle).
// Real-time: no allocation, no exceptions.
#pragma once

#include <array>

#include "vc/machine/correction_equations.hpp"

namespace vc::machine {

class IdealJacobianSolver {
 public:
  // Unknowns: the three linear joints and the first `direction_equations` rotary joints (0:
  // the position alone, the rotary joints held). applies() is false for a machine without
  // exactly three linear joints or with fewer rotary joints than direction equations.
  IdealJacobianSolver(const Model& model, int direction_equations) noexcept;
  bool applies() const noexcept { return applies_; }

  // B at the ideal machine's derivatives `ideal` for `target` (its direction equations must be
  // the solver's); false if a block is singular, or if `ideal` turns the tool with a linear
  // joint (not the ideal machine's derivatives: B is not block triangular).
  bool factorize(const CorrectionTarget& target, const PoseDerivatives& ideal) noexcept;
  // x with B x = r, over all joints (0 for the joints held).
  Joints solve(const Joints& r) const noexcept;

 private:
  bool applies_ = false;
  int joints_ = 0;
  int rotary_count_ = 0;  // unknowns among the rotary joints: direction_equations
  std::array<int, 3> linear_{};
  std::array<int, 2> rotary_{};
  Eigen::Matrix3d a_inverse_;
  Eigen::Matrix<double, 3, 2> c_;
  Eigen::Matrix2d d_inverse_;  // 1 x 1 in the top left corner with one rotary unknown
};

}  // namespace vc::machine
