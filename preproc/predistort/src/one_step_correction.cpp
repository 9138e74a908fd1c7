#include "vc/predistort/one_step_correction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vc/machine/correct.hpp"

namespace vc::predistort {
namespace {

using machine::Joints;
using machine::Machine;
using machine::SquareMatrix;

constexpr int kMaxSteps = 3;

}  // namespace

OneStepCorrection::OneStepCorrection(const machine::Model& model, const machine::Conditions& conditions)
    : model_(model),
      conditions_(conditions),
      applies_(model.joint_count() == 3 + model.rotary_count()),
      affine_(model.joint_count() == 3 && model.rotary_count() == 0),
      blocks_(model, model.rotary_count()) {
  for (int j = 0; j < machine::kMaxAxes; ++j) all_joints_[j] = j;
}

// |W r|: direction rows weighed by the lever, so the bound is one number in mm.
double OneStepCorrection::weighted_norm(const Joints& residual) const {
  return std::sqrt(residual.head(3).squaredNorm() +
                   machine::kDirectionLeverMm * machine::kDirectionLeverMm * machine::direction_squared_norm(residual));
}

bool OneStepCorrection::equations_at(const PerTool& tool, const Joints& target, machine::CorrectionTarget& equations,
                                     machine::PoseDerivatives& d, int& band) const {
  band = 0;
  if (affine_) {
    equations =
        machine::position_target({tool.jacobian * target.head<3>() + tool.tip_at_zero, Eigen::Vector3d::UnitZ()});
    return true;
  }
  const machine::ToolPose ideal = machine::tool_pose(model_, Machine::Ideal, target, tool.tool_length_mm, d);
  band = tool.bound.band_at(ideal, d);
  if (band < 0) return false;
  equations = machine::full_target(model_, ideal, d);
  return true;
}

OneStepCorrection::PerTool& OneStepCorrection::for_tool(double tool_length_mm) {
  for (PerTool& t : per_tool_)
    if (t.tool_length_mm == tool_length_mm) return t;
  PerTool t{tool_length_mm, machine::ContractionBound(model_, {tool_length_mm}), {}, {}, {}};
  if (affine_) {
    const Joints zero = Joints::Zero(3);
    machine::PoseDerivatives d;
    t.tip_at_zero = machine::tool_pose(model_, Machine::Ideal, zero, tool_length_mm, d).tip_mm;
    t.jacobian = d.tip.leftCols<3>();
    t.lu.compute(SquareMatrix(t.jacobian));
  }
  per_tool_.push_back(t);
  return per_tool_.back();
}

bool OneStepCorrection::factorize(const PerTool& tool, const machine::CorrectionTarget& equations,
                                  const machine::PoseDerivatives& d) {
  if (affine_) return std::abs(tool.lu.determinant()) > 0.0;
  blocks_used_ = blocks_.factorize(equations, d);
  if (blocks_used_) return true;
  point_lu_.compute(machine::correction_jacobian(equations, d, all_joints_, model_.joint_count()));
  return std::abs(point_lu_.determinant()) > 0.0;
}

Joints OneStepCorrection::solve(const PerTool& tool, const Joints& residual) const {
  if (affine_) return tool.lu.solve(residual);
  return blocks_used_ ? blocks_.solve(residual) : Joints(point_lu_.solve(residual));
}

bool OneStepCorrection::correct(const Joints& target, double tool_length_mm, const Joints& seed, Joints& corrected) {
  if (!applies_ || !target.allFinite() || !seed.allFinite()) return false;
  const PerTool& t = for_tool(tool_length_mm);
  machine::CorrectionTarget equations;
  machine::PoseDerivatives d;
  int band;
  if (!equations_at(t, target, equations, d, band)) return false;
  const double kappa = t.bound.kappa(band);
  if (!(kappa < 1e-2) || !factorize(t, equations, d)) return false;
  const machine::SolverOptions& opt = model_.solver;
  const int n = model_.joint_count();
  corrected = seed;
  double previous = std::numeric_limits<double>::infinity();
  for (int step = 0; step <= kMaxSteps; ++step) {
    const Joints residual = machine::correction_residual(
        equations, machine::tool_pose(model_, conditions_, Machine::Real, corrected, tool_length_mm), n);
    const double norm = weighted_norm(residual);
    if (!std::isfinite(norm)) return false;
    if (residual.head(3).norm() <= opt.position_tolerance_mm &&
        std::sqrt(machine::direction_squared_norm(residual)) <= opt.direction_tolerance_rad)
      return true;
    if (step == kMaxSteps || norm > 1e-2 * previous) return false;
    previous = norm;
    corrected -= solve(t, residual);
    if (kappa * norm <= kAcceptedResidualMm) return true;  // the residual is now below that
  }
  return false;
}

}  // namespace vc::predistort
