#include "vc/machine/correct.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "small_lu.hpp"
#include "vc/machine/contraction_bound.hpp"
#include "vc/machine/correction_equations.hpp"
#include "vc/machine/ideal_jacobian_solver.hpp"

namespace vc::machine {
namespace {

using FreeJoints = std::array<bool, kMaxAxes>;

// How newton() may stop: the direction tolerance where it is not the solver's (> 0), and the
// contraction kappa of a step with the ideal Jacobian (0: none; contraction_bound.hpp).
struct Stopping {
  double direction_tolerance_rad = 0.0;
  double kappa = 0.0;
};

// Newton on the real machine for the free joints; the others stay fixed. It starts with the
// ideal machine's Jacobian (`ideal`, already computed for the target), solved by its blocks
// (ideal_jacobian_solver.hpp): the real one differs by the error slopes, ~1e-4, so each step
// still gains about four digits. Where a step gains less than two, the exact Jacobian of the
// real machine (table slopes included, an LU) replaces it.
// While the Jacobian is the ideal one, a step whose residual bound kappa |W F| (W: direction
// rows times kDirectionLeverMm) is within both tolerances ends the solve unevaluated: `pose`
// is then the real pose before it and `unchecked_bound` that bound (else -1). Otherwise `pose`
// returns the real pose at the final joints.
Status newton(const Model& model, const Conditions& conditions, const CorrectionTarget& target, double tool_length_mm,
              const FreeJoints& free, const PoseDerivatives& ideal, Joints& q, int& iterations, ToolPose& pose,
              double& unchecked_bound, const Stopping& stopping = {}) noexcept {
  const SolverOptions& opt = model.solver;
  const double direction_tolerance =
      stopping.direction_tolerance_rad > 0.0 ? stopping.direction_tolerance_rad : opt.direction_tolerance_rad;
  const double unchecked_limit = std::min(opt.position_tolerance_mm, kDirectionLeverMm * direction_tolerance);
  bool ideal_jacobian = true;
  unchecked_bound = -1.0;
  int unknowns = 0;
  std::array<int, kMaxAxes> index{};
  for (int j = 0; j < model.joint_count(); ++j)
    if (free[j]) index[unknowns++] = j;
  // Factored when a step is first needed (a seed from the servo thread's last corrections is
  // often within the tolerance already). The blocks where the free joints are theirs (the
  // full correction's or the position's), else an LU.
  IdealJacobianSolver blocks(model, target.direction_equations);
  const bool by_blocks = blocks.applies() && unknowns == 3 + target.direction_equations;
  SmallLu lu;
  double previous_norm = std::numeric_limits<double>::infinity();
  for (int step = 0;; ++step) {
    pose = tool_pose(model, conditions, Machine::Real, q, tool_length_mm);
    const Joints residual = correction_residual(target, pose, unknowns);
    if (!residual.allFinite()) return Status::NonFinite;
    const double position = residual.head(3).norm();
    const double direction = std::sqrt(direction_squared_norm(residual));
    if (position <= opt.position_tolerance_mm && direction <= direction_tolerance) return Status::Ok;
    if (step == opt.max_iterations) return Status::NotConverged;
    const double norm = position + kDirectionLeverMm * direction;
    if (step == 0) {
      if (by_blocks ? !blocks.factorize(target, ideal)
                    : !lu.compute(correction_jacobian(target, ideal, index, unknowns)))
        return Status::Singular;
    } else if (norm > 1e-2 * previous_norm) {
      PoseDerivatives exact;
      tool_pose(model, conditions, Machine::Real, q, tool_length_mm, exact);
      if (!lu.compute(correction_jacobian(target, exact, index, unknowns))) return Status::Singular;
      ideal_jacobian = false;
    }
    previous_norm = norm;
    if (ideal_jacobian && by_blocks) {
      const Joints step_vector = blocks.solve(residual);  // over all joints
      if (!step_vector.allFinite()) return Status::Singular;
      q -= step_vector;
    } else {
      const Joints step_vector = lu.solve(-residual);  // over the unknowns
      if (!step_vector.allFinite()) return Status::Singular;
      for (int c = 0; c < unknowns; ++c) q[index[c]] += step_vector[c];
    }
    ++iterations;
    if (ideal_jacobian && stopping.kappa > 0.0) {
      // |W F| without std::hypot (~40 instructions a call; an overflow gives inf: no stop).
      const double lever = kDirectionLeverMm * direction;
      const double bound = stopping.kappa * std::sqrt(position * position + lever * lever);
      if (bound <= unchecked_limit) {
        unchecked_bound = bound;
        return Status::Ok;
      }
    }
  }
}

}  // namespace

double fade_factor(const PoleFade& fade, double phi) noexcept {
  const double s = std::clamp((phi - fade.start_rad) / (fade.full_rad - fade.start_rad), 0.0, 1.0);
  return fade.orientation * (s * s * (3.0 - 2.0 * s));  // FOR switched off: 0 everywhere
}

double pole_angle(const Model& model, const Joints& nominal, double tool_length_mm) noexcept {
  PoseDerivatives d;
  const ToolPose ideal = tool_pose(model, Machine::Ideal, nominal, tool_length_mm, d);
  return pole_angle_at(model, ideal, d);
}

namespace {

// Where the full correction's Newton runs: not at all (no rotary joints), everywhere
// (full_correction), or where correct() will use it (the fade above 0).
enum class Full { Never, Always, WhereFaded };

// What correct() and full_correction() share: the checks, the ideal pose at q_n with its
// derivatives, the pole angle and fade, and the full correction's Newton.
struct Start {
  Correction out;
  PoseDerivatives d;
  ToolPose ideal;
  ToolPose real;                  // the real pose at out.joints, set by newton() (before an unchecked step)
  double unchecked_bound = -1.0;  // newton()'s bound after an unchecked step, else -1
  FreeJoints linear{};
  bool ok = false;
};

// A sampled kappa a solve may stop on where it describes the steps at all (a step gains a digit
// or more: 0.001-0.004 at full correction on the shipped machines, 0.03-0.05 at the fade band's
// start); 0 (every step evaluated) else.
double stopping_kappa(double kappa) noexcept { return kappa < 0.1 ? kappa : 0.0; }

// The contraction the full correction's solve may stop on (0: every step evaluated): the bound's
// at the pole angle (its band's, or the fade band's), where it covers the tool length.
double kappa_for(const ContractionBound* bound, double tool_length_mm, const Correction& c) noexcept {
  if (!bound || !bound->covers(tool_length_mm)) return 0.0;
  return stopping_kappa(bound->full_kappa(c.pole_angle_rad));
}

// The same for the position's solve alone (the rotary joints held where the fade is below 1).
double position_kappa_for(const ContractionBound* bound, double tool_length_mm) noexcept {
  return bound && bound->covers(tool_length_mm) ? stopping_kappa(bound->position_kappa()) : 0.0;
}

Start start(const Model& model, const Conditions& conditions, const Joints& nominal, double tool_length_mm,
            const Joints& seed, Full full, const ContractionBound* bound = nullptr,
            const Joints* full_seed = nullptr) noexcept {
  Start s;
  s.out.nominal = nominal;
  s.out.joints = seed;
  if (!nominal.allFinite() || !seed.allFinite() || !std::isfinite(tool_length_mm)) {
    s.out.status = Status::NonFinite;
    return s;
  }
  const int n = model.joint_count();
  s.ideal = tool_pose(model, Machine::Ideal, nominal, tool_length_mm, s.d);
  s.real = s.ideal;
  FreeJoints all{};
  for (int j = 0; j < n; ++j) {
    s.linear[j] = model.axes[j].type == AxisType::Linear;
    all[j] = true;
  }
  if (model.rotary_count() > 0) {
    s.out.pole_angle_rad = pole_angle_at(model, s.ideal, s.d);
    s.out.fade = fade_factor(conditions.fade, s.out.pole_angle_rad);
  }
  if (full == Full::Always || (full == Full::WhereFaded && s.out.fade > 0.0)) {
    // Near the pole a direction residual e moves the rotary joints by e / sin phi, and in the
    // fade band the linear joints follow them (the inverse in invert_correction.cpp evaluates
    // this full correction at q_n again): there the tolerance shrinks with sin phi, so that
    // the joints are as exact as elsewhere.
    const double tolerance =
        s.out.fade < 1.0 ? model.solver.direction_tolerance_rad * std::sin(s.out.pole_angle_rad) : 0.0;
    if (full_seed) s.out.joints = *full_seed;
    s.out.status =
        newton(model, conditions, full_target(model, s.ideal, s.d), tool_length_mm, all, s.d, s.out.joints,
               s.out.iterations, s.real, s.unchecked_bound, {tolerance, kappa_for(bound, tool_length_mm, s.out)});
    if (s.out.status != Status::Ok) return s;
  }
  s.ok = true;
  return s;
}

// The residuals left at the answer. After an unchecked step (not evaluated) the position's is
// its bound (|W F| <= bound), and so is the direction's where that step solved it; after the
// position's solve alone (`position_alone`: fade < 1, the linear joints moved, the rotary ones
// held) the direction is the real pose's before the step (its change, through the tables'
// angular error slopes, is ~1e-14 rad).
void set_residuals(Correction& out, const Start& s, bool position_alone = false) noexcept {
  out.unchecked_step = s.unchecked_bound >= 0.0;
  out.residual_mm = out.unchecked_step ? s.unchecked_bound : (s.real.tip_mm - s.ideal.tip_mm).norm();
  out.residual_rad = out.unchecked_step && !position_alone ? s.unchecked_bound / kDirectionLeverMm
                                                           : s.ideal.direction.cross(s.real.direction).norm();
}

}  // namespace

Correction full_correction(const Model& model, const Conditions& conditions, const Joints& nominal,
                           double tool_length_mm, const Joints& seed) noexcept {
  if (model.rotary_count() == 0)
    return correct(model, conditions, nominal, tool_length_mm, seed);  // no fade to leave out
  Start s = start(model, conditions, nominal, tool_length_mm, seed, Full::Always);
  if (s.ok) set_residuals(s.out, s);
  return s.out;
}

Correction correct(const Model& model, const Conditions& conditions, const Joints& nominal, double tool_length_mm,
                   const Joints& seed, const ContractionBound* bound, const Joints* full_seed) noexcept {
  const int rotary = model.rotary_count();
  if (full_seed && !(full_seed->size() == nominal.size() && full_seed->allFinite())) full_seed = nullptr;
  Start s = start(model, conditions, nominal, tool_length_mm, seed, rotary > 0 ? Full::WhereFaded : Full::Never, bound,
                  full_seed);
  Correction& out = s.out;
  if (!s.ok) return out;
  const int n = model.joint_count();
  const PoseDerivatives& d = s.d;
  const ToolPose& ideal = s.ideal;
  const FreeJoints& linear = s.linear;
  CorrectionTarget target = position_target(ideal);
  if (rotary > 0 && out.fade < 1.0) {
    if (out.fade > 0.0) {
      out.full_joints = out.joints;
      out.full_unchecked_step = s.unchecked_bound >= 0.0;
    }
    // Rotary joints take f of their full correction; linear joints make the position exact,
    // from the seed's where the full correction had its own seed (the seed is then the faded
    // answer's estimate, the full solution's linear joints are not).
    for (int j = 0; j < n; ++j) {
      if (!linear[j])
        out.joints[j] = nominal[j] + out.fade * (out.joints[j] - nominal[j]);
      else if (full_seed)
        out.joints[j] = seed[j];
    }
  }
  const bool position_alone = rotary > 0 && out.fade < 1.0;
  if (rotary == 0 || position_alone)
    out.status = newton(
        model, conditions, target, tool_length_mm, linear, d, out.joints, out.iterations, s.real, s.unchecked_bound,
        {0.0, rotary == 0 ? kappa_for(bound, tool_length_mm, out) : position_kappa_for(bound, tool_length_mm)});
  set_residuals(out, s, position_alone);
  return out;
}

Status correct_position(const Model& model, const Conditions& conditions, const Joints& nominal, double tool_length_mm,
                        Joints& joints, int& iterations, double& direction_error_rad) noexcept {
  direction_error_rad = 0.0;
  if (!nominal.allFinite() || !joints.allFinite()) return Status::NonFinite;
  PoseDerivatives d;
  const ToolPose ideal = tool_pose(model, Machine::Ideal, nominal, tool_length_mm, d);
  FreeJoints linear{};
  for (int j = 0; j < model.joint_count(); ++j) linear[j] = model.axes[j].type == AxisType::Linear;
  ToolPose real;
  double unchecked = -1.0;
  const Status s =
      newton(model, conditions, position_target(ideal), tool_length_mm, linear, d, joints, iterations, real, unchecked);
  direction_error_rad = ideal.direction.cross(real.direction).norm();
  return s;
}

Uncorrection uncorrect(const Model& model, const Conditions& conditions, const Joints& corrected, double tool_length_mm,
                       double gain, const Joints& nominal_seed) noexcept {
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
    const Correction c = correct(model, conditions, out.nominal, tool_length_mm, correction_seed);
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
