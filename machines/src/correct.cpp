#include "vc/machine/correct.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "small_lu.hpp"
#include "vc/machine/correction_equations.hpp"

namespace vc::machine {
namespace {

using FreeJoints = std::array<bool, kMaxAxes>;

// Newton on the real machine for the free joints; the others stay fixed. It starts with the
// ideal machine's Jacobian (`ideal`, already computed for the target): the real one differs
// by the error slopes, ~1e-4, so each step still gains about four digits. Where a step gains
// less than two, the exact Jacobian of the real machine (table slopes included) replaces it.
// `pose` returns the real pose at the final joints.
Status newton(const Model& model, const CorrectionTarget& target, double tool_length_mm, const FreeJoints& free,
              const PoseDerivatives& ideal, Joints& q, int& iterations, ToolPose& pose) noexcept {
  const SolverOptions& opt = model.solver;
  int unknowns = 0;
  std::array<int, kMaxAxes> index{};
  for (int j = 0; j < model.joint_count(); ++j)
    if (free[j]) index[unknowns++] = j;
  SmallLu lu;
  lu.compute(correction_jacobian(target, ideal, index, unknowns));
  double previous_norm = std::numeric_limits<double>::infinity();
  for (int step = 0;; ++step) {
    pose = tool_pose(model, Machine::Real, q, tool_length_mm);
    const Joints residual = correction_residual(target, pose, unknowns);
    if (!residual.allFinite()) return Status::NonFinite;
    const double position = residual.head(3).norm();
    const double direction = std::sqrt(direction_squared_norm(residual));
    if (position <= opt.position_tolerance_mm && direction <= opt.direction_tolerance_rad) return Status::Ok;
    if (step == opt.max_iterations) return Status::NotConverged;
    const double norm = position + kDirectionLeverMm * direction;
    if (norm > 1e-2 * previous_norm) {
      PoseDerivatives exact;
      tool_pose(model, Machine::Real, q, tool_length_mm, exact);
      lu.compute(correction_jacobian(target, exact, index, unknowns));
    }
    previous_norm = norm;
    if (!lu.ok()) return Status::Singular;
    const Joints step_vector = lu.solve(-residual);
    if (!step_vector.allFinite()) return Status::Singular;
    for (int c = 0; c < unknowns; ++c) q[index[c]] += step_vector[c];
    ++iterations;
  }
}

}  // namespace

double fade_factor(const PoleFade& fade, double phi) noexcept {
  const double s = std::clamp((phi - fade.start_rad) / (fade.full_rad - fade.start_rad), 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

double pole_angle(const Model& model, const Joints& nominal, double tool_length_mm) noexcept {
  PoseDerivatives d;
  const ToolPose ideal = tool_pose(model, Machine::Ideal, nominal, tool_length_mm, d);
  return pole_angle_at(model, ideal, d);
}

Correction correct(const Model& model, const Joints& nominal, double tool_length_mm) noexcept {
  return correct(model, nominal, tool_length_mm, nominal);
}

Correction correct(const Model& model, const Joints& nominal, double tool_length_mm,
                   const Joints& seed) noexcept {
  Correction out;
  out.nominal = nominal;
  out.joints = seed;
  if (!nominal.allFinite() || !seed.allFinite() || !std::isfinite(tool_length_mm)) {
    out.status = Status::NonFinite;
    return out;
  }
  const int n = model.joint_count();
  PoseDerivatives d;
  const ToolPose ideal = tool_pose(model, Machine::Ideal, nominal, tool_length_mm, d);
  ToolPose real = ideal;  // the real pose at the final joints, set by newton()

  FreeJoints linear{}, all{};
  for (int j = 0; j < n; ++j) {
    linear[j] = model.axes[j].type == AxisType::Linear;
    all[j] = true;
  }
  const int rotary = model.rotary_count();
  if (rotary > 0) {
    out.pole_angle_rad = pole_angle_at(model, ideal, d);
    out.fade = fade_factor(model.fade, out.pole_angle_rad);
  }
  CorrectionTarget target = position_target(ideal);
  if (rotary > 0 && out.fade > 0.0) {
    // Full correction: position and tool direction.
    target = full_target(model, ideal, d);
    out.status = newton(model, target, tool_length_mm, all, d, out.joints, out.iterations, real);
    if (out.status != Status::Ok) return out;
    target.direction_equations = 0;
  }
  if (rotary > 0 && out.fade < 1.0) {
    // Rotary joints take f of their full correction; linear joints make the position exact.
    for (int j = 0; j < n; ++j)
      if (!linear[j]) out.joints[j] = nominal[j] + out.fade * (out.joints[j] - nominal[j]);
  }
  if (rotary == 0 || out.fade < 1.0)
    out.status = newton(model, target, tool_length_mm, linear, d, out.joints, out.iterations, real);
  out.residual_mm = (real.tip_mm - ideal.tip_mm).norm();
  out.residual_rad = ideal.direction.cross(real.direction).norm();
  return out;
}

Uncorrection uncorrect(const Model& model, const Joints& corrected, double tool_length_mm) noexcept {
  return uncorrect(model, corrected, tool_length_mm, 1.0, corrected);
}

Uncorrection uncorrect(const Model& model, const Joints& corrected, double tool_length_mm, double gain,
                       const Joints& nominal_seed) noexcept {
  Uncorrection out;
  out.nominal = corrected;
  if (!corrected.allFinite() || !nominal_seed.allFinite() || !std::isfinite(gain)) {
    out.status = Status::NonFinite;
    return out;
  }
  if (gain == 0.0) return out;  // nothing applied: the joints are the nominal ones
  out.nominal = nominal_seed;
  Joints correction_seed = corrected;  // where the correction of the current guess lands
  for (out.iterations = 1; out.iterations <= model.solver.max_iterations; ++out.iterations) {
    const Correction c = correct(model, out.nominal, tool_length_mm, correction_seed);
    if (c.status != Status::Ok) {
      out.status = c.status;
      return out;
    }
    const Joints applied = out.nominal + gain * (c.joints - out.nominal);
    const Joints difference = applied - corrected;
    out.nominal -= difference;
    correction_seed = c.joints - difference;
    if (difference.cwiseAbs().maxCoeff() <= model.solver.position_tolerance_mm) return out;
  }
  out.status = Status::NotConverged;
  out.iterations = model.solver.max_iterations;
  return out;
}

}  // namespace vc::machine
