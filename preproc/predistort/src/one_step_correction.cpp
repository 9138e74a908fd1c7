#include "vc/predistort/one_step_correction.hpp"

#include <cmath>
#include <limits>

#include "travel_samples.hpp"
#include "vc/machine/correct.hpp"

namespace vc::predistort {
namespace {

using machine::Joints;
using machine::Machine;
using machine::SquareMatrix;

constexpr int kSamples = 400;
constexpr double kMargin = 2.0;
constexpr int kMaxSteps = 3;

}  // namespace

OneStepCorrection::OneStepCorrection(const machine::Model& model)
    : model_(model),
      applies_(model.joint_count() == 3 + model.rotary_count()),
      affine_(model.joint_count() == 3 && model.rotary_count() == 0) {
  for (int j = 0; j < machine::kMaxAxes; ++j) all_joints_[j] = j;
}

// |W r|: direction rows weighed by the lever, so the bound is one number in mm.
double OneStepCorrection::weighted_norm(const Joints& residual) const {
  const int n = static_cast<int>(residual.size());
  return std::sqrt(residual.head(3).squaredNorm() +
                   machine::kDirectionLeverMm * machine::kDirectionLeverMm * residual.tail(n - 3).squaredNorm());
}

bool OneStepCorrection::equations_at(const PerTool& tool, const Joints& target, machine::CorrectionTarget& equations,
                                     Eigen::PartialPivLU<SquareMatrix>& lu) const {
  if (affine_) {
    equations = machine::position_target({tool.jacobian * target.head<3>() + tool.tip_at_zero, Eigen::Vector3d::UnitZ()});
    return true;
  }
  machine::PoseDerivatives d;
  const machine::ToolPose ideal = machine::tool_pose(model_, Machine::Ideal, target, tool.tool_length_mm, d);
  if (machine::fade_factor(model_.fade, machine::pole_angle_at(model_, ideal, d)) < 1.0) return false;
  equations = machine::full_target(model_, ideal, d);
  lu.compute(machine::correction_jacobian(equations, d, all_joints_, model_.joint_count()));
  return true;
}

OneStepCorrection::PerTool& OneStepCorrection::for_tool(double tool_length_mm) {
  for (PerTool& t : per_tool_)
    if (t.tool_length_mm == tool_length_mm) return t;
  const int n = model_.joint_count();
  PerTool t;
  t.tool_length_mm = tool_length_mm;
  if (affine_) {
    const Joints zero = Joints::Zero(3);
    machine::PoseDerivatives d;
    t.tip_at_zero = machine::tool_pose(model_, Machine::Ideal, zero, tool_length_mm, d).tip_mm;
    t.jacobian = d.tip.leftCols<3>();
    t.lu.compute(SquareMatrix(t.jacobian));
  }
  // kappa: the largest slope of the real machine's equations against B, seen through B^-1,
  // over the travel where this applies (W: the weights of weighted_norm).
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, machine::kMaxAxes, 1> w = Eigen::VectorXd::Ones(n);
  w.tail(n - 3).setConstant(machine::kDirectionLeverMm);
  TravelSamples samples(model_);
  double kappa = 0.0;
  Eigen::PartialPivLU<SquareMatrix> lu;
  for (int sample = 0; sample < kSamples; ++sample) {
    const Joints q = samples.next();
    machine::CorrectionTarget equations;
    if (!equations_at(t, q, equations, lu)) continue;
    const Eigen::PartialPivLU<SquareMatrix>& b = affine_ ? t.lu : lu;
    const machine::Correction core = machine::correct(model_, q, tool_length_mm);
    if (core.status != machine::Status::Ok) continue;
    machine::PoseDerivatives real;
    machine::tool_pose(model_, Machine::Real, core.joints, tool_length_mm, real);
    const SquareMatrix jacobian = machine::correction_jacobian(equations, real, all_joints_, n);
    const SquareMatrix contraction = (b.reconstructedMatrix() - jacobian) * b.inverse();
    kappa = std::max(kappa, (w.asDiagonal() * contraction * w.cwiseInverse().asDiagonal()).norm());
  }
  t.kappa = kMargin * kappa;
  per_tool_.push_back(t);
  return per_tool_.back();
}

bool OneStepCorrection::correct(const Joints& target, double tool_length_mm, const Joints& seed, Joints& corrected) {
  if (!applies_ || !target.allFinite() || !seed.allFinite()) return false;
  const PerTool& t = for_tool(tool_length_mm);
  if (!(t.kappa < 1e-2)) return false;
  machine::CorrectionTarget equations;
  if (!equations_at(t, target, equations, point_lu_)) return false;
  const Eigen::PartialPivLU<SquareMatrix>& b = affine_ ? t.lu : point_lu_;
  if (!(std::abs(b.determinant()) > 0.0)) return false;
  const machine::SolverOptions& opt = model_.solver;
  const int n = model_.joint_count();
  corrected = seed;
  double previous = std::numeric_limits<double>::infinity();
  for (int step = 0; step <= kMaxSteps; ++step) {
    const Joints residual = machine::correction_residual(
        equations, machine::tool_pose(model_, Machine::Real, corrected, tool_length_mm), n);
    const double norm = weighted_norm(residual);
    if (!std::isfinite(norm)) return false;
    if (residual.head(3).norm() <= opt.position_tolerance_mm &&
        residual.tail(n - 3).norm() <= opt.direction_tolerance_rad)
      return true;
    if (step == kMaxSteps || norm > 1e-2 * previous) return false;
    previous = norm;
    corrected -= b.solve(residual);
    if (t.kappa * norm <= kAcceptedResidualMm) return true;  // the residual is now below that
  }
  return false;
}

}  // namespace vc::predistort
