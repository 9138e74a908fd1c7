#include "vc/machine/invert_correction.hpp"

#include <algorithm>
#include <cmath>

#include "vc/machine/correction_equations.hpp"
#include "vc/machine/ideal_jacobian_solver.hpp"
#include "vc/tables/units.hpp"

namespace vc::machine {

bool usable_correction(const Joints* correction, const Joints& point) noexcept {
  return correction && correction->size() == point.size() && correction->allFinite() &&
         correction->cwiseAbs().maxCoeff() <= kSeedRadius;
}

StepRemainder ideal_step_remainder(const Model& model, const Joints& from, const Joints& to,
                                   double tool_length_mm) noexcept {
  double reach = model.spindle.ideal.translation().norm() + std::abs(tool_length_mm);  // R
  double turn = 0.0, travel = 0.0;                                                     // Omega, V
  for (int j = 0; j < model.joint_count(); ++j) {
    const Axis& axis = model.axes[j];
    const double step = std::abs(to[j] - from[j]);
    reach += axis.pole_mm.norm();
    if (axis.type == AxisType::Linear) {
      reach += std::max(std::abs(from[j]), std::abs(to[j]));
      travel += step;
    } else {
      turn += step * tables::kDegToRad;
    }
  }
  return {1.5 * (turn * turn * reach + turn * travel), turn * turn, turn};
}

namespace {

// The ideal machine at the current guess, with the derivatives Newton and the pole angle need.
struct IdealPose {
  ToolPose pose;
  PoseDerivatives d;
};

// Newton on the ideal machine: its tip onto target.tip_mm and, with direction equations, its
// tool direction parallel to target.direction (the real machine's pose at q_c). The unknowns
// are all joints (with direction equations) or the linear ones (without: the rotary joints
// stay). Exact Jacobian at every step: the ideal machine's derivatives are cheap, and the
// rotary joints' trigonometry makes a frozen one converge slowly. `ideal` holds the pose at q
// if `evaluated`, and returns the pose at the final q.
// With `unchecked` set, a step whose remainder bound (ideal_step_remainder) is within half the
// tolerances ends the solve without evaluating the pose after it: *unchecked is then true and
// `ideal` holds the pose before the step.
Status ideal_newton(const Model& model, const CorrectionTarget& target, double tool_length_mm, Joints& q,
                    int& iterations, IdealPose& ideal, bool evaluated = false, bool* unchecked = nullptr) noexcept {
  const SolverOptions& opt = model.solver;
  IdealJacobianSolver solver(model, target.direction_equations);
  if (!solver.applies()) return Status::Singular;  // not a square system of the solver's blocks
  const int equations = 3 + target.direction_equations;
  for (int step = 0;; ++step) {
    if (step > 0 || !evaluated) ideal.pose = tool_pose(model, Machine::Ideal, q, tool_length_mm, ideal.d);
    const Joints residual = correction_residual(target, ideal.pose, equations);
    if (!residual.allFinite()) return Status::NonFinite;
    const double position = residual.head(3).norm();
    const double direction = std::sqrt(direction_squared_norm(residual));
    if (position <= opt.position_tolerance_mm && direction <= opt.direction_tolerance_rad) return Status::Ok;
    if (step == opt.max_iterations) return Status::NotConverged;
    if (!solver.factorize(target, ideal.d)) return Status::Singular;
    const Joints step_vector = solver.solve(residual);
    if (!step_vector.allFinite()) return Status::Singular;
    const Joints before = q;
    q -= step_vector;
    ++iterations;
    if (unchecked) {
      const StepRemainder left = ideal_step_remainder(model, before, q, tool_length_mm);
      if (left.position_mm <= 0.5 * opt.position_tolerance_mm &&
          left.direction_rad <= 0.5 * opt.direction_tolerance_rad) {
        *unchecked = true;
        return Status::Ok;
      }
    }
  }
}

double fade_at(const Model& model, const Conditions& conditions, const IdealPose& ideal) noexcept {
  return fade_factor(conditions.fade, pole_angle_at(model, ideal.pose, ideal.d));
}

// The rotary joints of `from` copied into `q`.
void set_rotary(const Model& model, const Joints& from, Joints& q) noexcept {
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[j].type == AxisType::Rotary) q[j] = from[j];
}

// A first estimate of the full correction D at q: one Newton step of its equations from q + d
// with the ideal Jacobian at q (`ideal`: the ideal pose at q). It leaves ~1e-4 of d's error
// (the error slopes). That is all a first round needs: D at an estimate of q_n is itself off by
// ~1e-2 of the estimate's error, and the next round's D, solved to the tolerances where q_n
// moved to, makes up for both.
bool first_full_correction(const Model& model, const Conditions& conditions, const Joints& q, double tool_length_mm,
                           const IdealPose& ideal, Joints& d, int& iterations) noexcept {
  const CorrectionTarget target = full_target(model, ideal.pose, ideal.d);
  IdealJacobianSolver solver(model, target.direction_equations);
  if (!solver.applies() || !solver.factorize(target, ideal.d)) return false;
  const ToolPose real = tool_pose(model, conditions, Machine::Real, Joints(q + d), tool_length_mm);
  const Joints step = solver.solve(correction_residual(target, real, 3 + target.direction_equations));
  if (!step.allFinite()) return false;
  d -= step;
  ++iterations;
  return true;
}

// The fade band's answer from an estimate q_n (the ideal pose at it in `ideal`) and an estimate
// d of the full correction D there (q_c - q_full from the full solution q_full, or one the
// caller kept). D is estimated at q_n (first_full_correction); with D fixed, the rotary joints
// are set to q_c - f(q_n) D and the linear ones solve the position, until f (ideal machine only)
// stops moving them. Near the pole D moves by up to ~1e-2 times q_n's change (its rotary part
// grows as 1/sin phi), so D is solved again (full_correction, seeded with the last) where q_n
// moved to: each such round moves q_n by K times the last round's move, K the rounds'
// contraction (~1e-3), and leaves an error of about K / (1 - K) times its own move. The solve
// ends where that error, K estimated from the last two moves and taken kBandSafety times, is
// within kBandSettledMm (or the move itself is): then D's own error is ~1e-11.
// The position solves take their one step unevaluated: the ideal tip is affine in the linear
// joints (ideal_step_remainder: no turn, no remainder), and f depends on the rotary joints
// alone (the pole angle is the tool direction's against the rotary lines), so the pose before
// the step still gives it (`ideal` returns it: its tip is not the answer's).
// False where a solve fails, the pose leaves the band or it does not settle in kBandRounds:
// the caller polishes with whole corrections.
constexpr double kBandSettledMm = 1e-10;  // mm or deg
constexpr double kBandSafety = 10.0;
constexpr double kBandContracting = 0.1;  // the largest K the error estimate is trusted for
constexpr int kBandRounds = 4;

bool band_solve(const Model& model, const Conditions& conditions, const Joints& corrected, double tool_length_mm,
                Joints d, const CorrectionTarget& position, Joints& q, int& iterations, IdealPose& ideal) noexcept {
  const double f0 = fade_at(model, conditions, ideal);
  if (!(f0 > 0.0 && f0 < 1.0)) return false;  // not in the band: not this solve's case
  double last_move = 0.0;
  for (int round = 0; round < kBandRounds; ++round) {
    const Joints at = q;
    if (round == 0) {
      if (!first_full_correction(model, conditions, q, tool_length_mm, ideal, d, iterations)) return false;
    } else {
      const Correction full = full_correction(model, conditions, q, tool_length_mm, Joints(q + d));
      iterations += full.iterations + 1;
      if (full.status != Status::Ok) return false;
      d = full.joints - q;
    }
    bool settled = false;
    for (int pass = 0; pass < model.solver.max_iterations && !settled; ++pass) {
      const double f = fade_at(model, conditions, ideal);
      if (!(f > 0.0 && f < 1.0)) return false;  // left the band: not this solve's case
      double moved = 0.0;
      for (int j = 0; j < model.joint_count(); ++j)
        if (model.axes[j].type == AxisType::Rotary) {
          const double r = corrected[j] - f * d[j];
          moved = std::max(moved, std::abs(r - q[j]));
          q[j] = r;
        }
      bool unchecked = false;
      if (ideal_newton(model, position, tool_length_mm, q, iterations, ideal, false, &unchecked) != Status::Ok)
        return false;
      settled = moved <= model.solver.position_tolerance_mm;
    }
    if (!settled) return false;
    const double move = (q - at).cwiseAbs().maxCoeff();
    if (move <= kBandSettledMm) return true;
    const double contraction = round > 0 ? move / last_move : 1.0;
    if (contraction <= kBandContracting && kBandSafety * contraction / (1.0 - contraction) * move <= kBandSettledMm)
      return true;
    last_move = move;
  }
  return false;
}

}  // namespace

Uncorrection invert_correction(const Model& model, const Conditions& conditions, const Joints& corrected,
                               double tool_length_mm, double gain, const Joints& nominal_seed,
                               const Joints* full_correction) noexcept {
  Uncorrection out;
  out.nominal = corrected;
  if (!corrected.allFinite() || !nominal_seed.allFinite() || !std::isfinite(gain) || !std::isfinite(tool_length_mm)) {
    out.status = Status::NonFinite;
    return out;
  }
  if (gain == 0.0) return out;  // nothing applied: the joints are the nominal ones
  if (gain != 1.0) return uncorrect(model, conditions, corrected, tool_length_mm, gain, nominal_seed);

  // Newton needs a start near the answer (a far one may lie nearer another turn of a rotary
  // joint or another branch of the ideal inverse); q_c is always within the correction.
  const bool near =
      nominal_seed.size() == corrected.size() && (nominal_seed - corrected).cwiseAbs().maxCoeff() <= kSeedRadius;
  const Joints start = near ? nominal_seed : corrected;
  const ToolPose real = tool_pose(model, conditions, Machine::Real, corrected, tool_length_mm);
  IdealPose ideal;
  Joints q = start;
  CorrectionTarget position{real.tip_mm, real.direction, {}, 0};
  if (model.rotary_count() == 0) {  // no fade: nothing needs the pose at the answer
    out.status = ideal_newton(model, position, tool_length_mm, q, out.iterations, ideal, false, &out.unchecked_step);
    out.nominal = q;
    return out;
  }

  // Which side of the fade band: judged at the seed, confirmed at the solution. With the rates
  // at once: in LinuxCNC the seed is never the answer (the joints fed back are the cubic
  // interpolator's way point, two cycles behind the last command and its correction: a step
  // is taken in nearly every cycle), so evaluating the pose without them first only costs.
  ideal.pose = tool_pose(model, Machine::Ideal, q, tool_length_mm, ideal.d);
  // Basis perpendicular to the real direction (two rotary axes), or the rotary axis line (one:
  // the same in the part frame at every q, only linear axes move it).
  const CorrectionTarget full = full_target(model, real, ideal.d);
  bool evaluated = true;  // `ideal` holds the pose at q
  const double seed_pole_angle = pole_angle_at(model, ideal.pose, ideal.d);
  const double seed_fade = fade_factor(conditions.fade, seed_pole_angle);
  if (seed_fade > 0.0 && seed_fade < 1.0 && near && usable_correction(full_correction, corrected)) {
    // In the band with a full correction at hand (the servo thread's, of the last commands):
    // straight to the band's solve from the seed, without the full solution's estimate of D.
    if (band_solve(model, conditions, corrected, tool_length_mm, *full_correction, position, q, out.iterations,
                   ideal)) {
      out.nominal = q;
      return out;
    }
    q = start;  // on as without it
    ideal.pose = tool_pose(model, Machine::Ideal, q, tool_length_mm, ideal.d);
  }
  if (seed_fade == 0.0) {  // at the pole: the rotary joints are not corrected
    set_rotary(model, corrected, q);
    const Status s = ideal_newton(model, position, tool_length_mm, q, out.iterations, ideal);
    if (s == Status::Ok && fade_at(model, conditions, ideal) == 0.0) {
      out.nominal = q;
      return out;
    }
    q = start;
    evaluated = false;
  }
  // Full correction (and the fade band's first estimate).
  const int steps_before = out.iterations;
  bool unchecked = false;
  Status s = ideal_newton(model, full, tool_length_mm, q, out.iterations, ideal, evaluated,
                          evaluated && seed_fade == 1.0 ? &unchecked : nullptr);
  // Where the seed was the answer (no step), the fade is the one judged there; after a step
  // that was not evaluated, the one judged there if the pole angle cannot have crossed into
  // the band (it moves by at most twice the turn from the seed), else the pose is evaluated.
  const bool at_seed = evaluated && out.iterations == steps_before;
  if (unchecked && seed_pole_angle - conditions.fade.full_rad <=
                       2.0 * ideal_step_remainder(model, start, q, tool_length_mm).turn_rad) {
    unchecked = false;
    ideal.pose = tool_pose(model, Machine::Ideal, q, tool_length_mm, ideal.d);
  }
  double fade = s != Status::Ok ? 0.0 : at_seed || unchecked ? seed_fade : fade_at(model, conditions, ideal);
  if (s == Status::Ok && fade == 1.0) {
    out.nominal = q;
    out.unchecked_step = unchecked;
    return out;
  }
  if (s != Status::Ok) q = corrected;  // near the pole the full system may be singular: no estimate
  // The fade band: q_c's rotary joints are q_n's plus f(q_n) times their full correction D(q_n),
  // which at q_n is nearly what it is at the full solution q (slopes ~1e-4): a first estimate.
  Joints estimate = start;
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[j].type == AxisType::Rotary) estimate[j] = corrected[j] - fade * (corrected[j] - q[j]);
  s = ideal_newton(model, position, tool_length_mm, estimate, out.iterations, ideal);
  if (s == Status::Ok && band_solve(model, conditions, corrected, tool_length_mm, Joints(corrected - q), position,
                                    estimate, out.iterations, ideal)) {
    out.nominal = estimate;
    return out;
  }
  if (s != Status::Ok) estimate = corrected;
  Uncorrection polished = uncorrect(model, conditions, corrected, tool_length_mm, 1.0, estimate);
  polished.iterations += out.iterations;
  return polished;
}

}  // namespace vc::machine
