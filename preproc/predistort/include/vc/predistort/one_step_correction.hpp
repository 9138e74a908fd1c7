// machine::correct, cheaper where it can be: seeded next to the answer (a point of a path,
// seed extrapolated from the points before), one Newton step is accepted without evaluating
// the real machine after it, on a bound of the residual it leaves.
//
// The equations F(q) = 0 (correction_equations.hpp, the full correction: every joint free,
// 3 + rotary joints = joints) are solved by Newton with the ideal machine's Jacobian B at
// the target q_n, the core's first matrix. One step leaves a residual within kappa times
// the one before it, kappa sampled over the travel per band of the pole angle, once per tool
// length (machine::ContractionBound). A step whose bound kappa |W F(q)| is below
// kAcceptedResidualMm (1e-9 mm, a thousandth of the last digit the pre-distorter writes;
// 1e-12 rad) is taken unverified: most points then cost one real chain walk instead of two or
// three. Otherwise Newton goes on with the core's stopping rule.
//
// Three linear axes: the ideal tip is affine, tip = A q + b (once per tool length), so B = A
// and no ideal chain walk is needed. With rotary joints: one ideal walk with derivatives
// per point (target, B, pole angle); near a pole (fade < 1) it declines.
#pragma once

#include <Eigen/LU>
#include <array>
#include <vector>

#include "vc/machine/contraction_bound.hpp"
#include "vc/machine/correction_equations.hpp"
#include "vc/machine/ideal_jacobian_solver.hpp"

namespace vc::predistort {

class OneStepCorrection {
 public:
  static constexpr double kAcceptedResidualMm = 1e-9;

  // applies() false (correct() declines) unless 3 + rotary joints = joints.
  OneStepCorrection(const machine::Model& model, const machine::Conditions& conditions);
  bool applies() const { return applies_; }

  // Corrected joints for the nominal `target`, Newton from `seed`. False where it declines
  // (near a pole), a step gains less than two digits or the steps run out: the caller then
  // asks machine::correct().
  bool correct(const machine::Joints& target, double tool_length_mm, const machine::Joints& seed,
               machine::Joints& corrected);

  // kappa for a tool length where the pole angle is phi (tests).
  double contraction(double tool_length_mm, double pole_angle_rad) {
    const machine::ContractionBound& bound = for_tool(tool_length_mm).bound;
    return bound.kappa(bound.band_of(pole_angle_rad));
  }
  // The band of a pole angle (x [1, 1.5), [1.5, 2), [2, 3), [3, ...) the full-correction
  // angle), and of the pole angle at nominal joints, -1 below full correction (tests: the two
  // agree).
  int band_of(double pole_angle_rad, double tool_length_mm) {
    return for_tool(tool_length_mm).bound.band_of(pole_angle_rad);
  }
  int band_at(const machine::Joints& target, double tool_length_mm) {
    machine::PoseDerivatives d;
    const machine::ToolPose ideal = machine::tool_pose(model_, machine::Machine::Ideal, target, tool_length_mm, d);
    return for_tool(tool_length_mm).bound.band_at(ideal, d);
  }

 private:
  struct PerTool {
    double tool_length_mm;
    machine::ContractionBound bound;                // kappa per band of the pole angle
    Eigen::Matrix3d jacobian;                       // A (three linear axes)
    Eigen::Vector3d tip_at_zero;                    // b
    Eigen::PartialPivLU<machine::SquareMatrix> lu;  // of A
  };
  // The equations at `target`, the ideal machine's derivatives there (B's columns) and the band
  // of the pole angle; false near a pole.
  bool equations_at(const PerTool& tool, const machine::Joints& target, machine::CorrectionTarget& equations,
                    machine::PoseDerivatives& d, int& band) const;
  // B at the current point, for solve(); false if singular.
  bool factorize(const PerTool& tool, const machine::CorrectionTarget& equations, const machine::PoseDerivatives& d);
  machine::Joints solve(const PerTool& tool, const machine::Joints& residual) const;
  PerTool& for_tool(double tool_length_mm);
  double weighted_norm(const machine::Joints& residual) const;

  const machine::Model& model_;
  machine::Conditions conditions_;
  bool applies_;
  bool affine_;  // three linear axes
  std::array<int, machine::kMaxAxes> all_joints_{};
  std::vector<PerTool> per_tool_;
  machine::IdealJacobianSolver blocks_;  // rotary joints: B block triangular
  bool blocks_used_ = false;             // B at the current point in blocks_ (else point_lu_)
  Eigen::PartialPivLU<machine::SquareMatrix> point_lu_;
};

}  // namespace vc::predistort
