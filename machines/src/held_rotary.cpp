// Clamped rotary axes (held_rotary.hpp).
#include "vc/machine/held_rotary.hpp"

#include <cmath>

namespace vc::machine {

bool HeldRotary::any(const Model& model) const noexcept {
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[static_cast<std::size_t>(j)].type == AxisType::Rotary && release[static_cast<std::size_t>(j)] != 1.0)
      return true;
  return false;
}

Correction correct_held(const Model& model, const Conditions& conditions, const Joints& nominal, double tool_length_mm,
                        double gain, const HeldRotary& held, const Joints& seed) noexcept {
  Correction out = correct(model, conditions, nominal, tool_length_mm, seed);  // the free correction
  if (out.status != Status::Ok) return out;
  Joints& q = out.joints;
  for (int j = 0; j < model.joint_count(); ++j) {
    const auto k = static_cast<std::size_t>(j);
    if (model.axes[k].type != AxisType::Rotary) continue;
    const double free = gain * (q[j] - nominal[j]);
    q[j] = nominal[j] + held.offset_deg[k] + held.release[k] * (free - held.offset_deg[k]);
  }
  out.status = correct_position(model, conditions, nominal, tool_length_mm, q, out.iterations, out.residual_rad);
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[static_cast<std::size_t>(j)].type == AxisType::Linear)
      q[j] = nominal[j] + gain * (q[j] - nominal[j]);
  out.full_joints = Joints();  // not the servo thread's seeds: they are the free correction's
  out.unchecked_step = false;
  return out;
}

Uncorrection uncorrect_held(const Model& model, const Conditions& conditions, const Joints& corrected,
                            double tool_length_mm, double gain, const HeldRotary& held,
                            const Joints& nominal_seed) noexcept {
  Uncorrection out;
  if (!corrected.allFinite() || !nominal_seed.allFinite() || !std::isfinite(gain)) {
    out.nominal = corrected;
    out.status = Status::NonFinite;
    return out;
  }
  out.nominal = nominal_seed;
  Joints correction_seed = corrected;
  for (out.iterations = 1; out.iterations <= model.solver.max_iterations; ++out.iterations) {
    const Correction c = correct_held(model, conditions, out.nominal, tool_length_mm, gain, held, correction_seed);
    if (c.status != Status::Ok) {
      out.status = c.status;
      return out;
    }
    const Joints difference = c.joints - corrected;
    out.nominal -= difference;
    correction_seed = corrected;  // the answer's correction lands on q_c
    if (difference.cwiseAbs().maxCoeff() <= model.solver.position_tolerance_mm) return out;
  }
  out.status = Status::NotConverged;
  out.iterations = model.solver.max_iterations;
  return out;
}

}  // namespace vc::machine
