// machine::correct for a machine of three linear axes, cheaper: the ideal tool tip is then
// affine in the joints, tip = A q + b (A and b once per tool length, no chain walk), and
// Newton runs with the constant A, factorized once.
//
// One step from q to q+ = q - A^-1 F(q), F = real tip - ideal tip at the target, leaves
// F(q+) = -(Jbar - A) A^-1 F(q) exactly, Jbar the mean real Jacobian between q and q+
// (mean value theorem); Jbar - A is the slope of the volumetric error. So
// |F(q+)| <= kappa |F(q)| with kappa = sup |(J_real - A) A^-1| (Frobenius), sampled at 400
// points over the travel and doubled for what the sampling may miss. A step whose bound
// kappa |F(q)| is below kAcceptedResidualMm (1e-9 mm, a thousandth of the last digit
// the pre-distorter writes) is taken without evaluating the real machine after it: most
// points then cost one chain walk instead of three. Otherwise Newton goes on with the
// core's stopping rule (tip residual <= the solver's position tolerance).
#pragma once

#include <Eigen/LU>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::predistort {

class LinearCorrection {
 public:
  static constexpr double kAcceptedResidualMm = 1e-9;

  // For a machine of three linear joints (applies() false otherwise: correct() refuses).
  explicit LinearCorrection(const machine::Model& model);
  bool applies() const { return applies_; }

  // Corrected joints for the nominal `target`, Newton from `seed`. False where a step gains
  // less than two digits or the steps run out: the caller then asks machine::correct().
  bool correct(const machine::Joints& target, double tool_length_mm, const machine::Joints& seed,
               machine::Joints& corrected);

  // kappa for a tool length (tests).
  double contraction(double tool_length_mm) { return for_tool(tool_length_mm).kappa; }

 private:
  struct PerTool {
    double tool_length_mm;
    Eigen::Matrix3d jacobian;  // A
    Eigen::Vector3d tip_at_zero;  // b
    Eigen::PartialPivLU<Eigen::Matrix3d> lu;
    double kappa;
  };
  PerTool& for_tool(double tool_length_mm);

  const machine::Model& model_;
  bool applies_;
  std::vector<PerTool> per_tool_;
};

}  // namespace vc::predistort
