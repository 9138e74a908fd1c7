// The inverse of the correction map for the servo thread's forward kinematics: the nominal
// joints q_n whose correction is the given q_c, by Newton on the real machine's pose.
//
// Where the correction is full (pole fade f = 1), q_c = correct(q_n) says that the real
// machine at q_c puts the tool where the ideal machine puts it at q_n (model.md, Correction):
//     pos P'(q_n) = pos P(q_c),   dir P'(q_n) || dir P(q_c)   (one rotary axis: a . (k' x k) = 0)
// So q_n is the ideal machine's inverse of one real pose: P(q_c) is evaluated once, then
// Newton runs on the ideal machine (cheap derivatives, exact Jacobian, quadratic), where the
// fixed point `uncorrect` evaluates whole corrections (each a Newton on the real machine) until
// they stop moving. At the pole (f = 0) the rotary joints are not corrected: q_n's are q_c's and
// the linear joints solve the position alone. The side is judged at the seed and confirmed at
// the solution (the fade at q_n is what correct() uses). In the band between (0 < f < 1) the
// rotary joints took f of a full correction D found by another solve: the two Newton solves above
// give q_n to ~1e-7, then D is estimated at q_n (one Newton step on the real machine) and q_n's
// rotary joints are q_c's less f(q_n) D, its linear ones from the position (ideal machine), with
// D solved again where q_n moved to until the rounds' contraction shows q_n's error within 1e-10
// (two rounds as a rule). Where that fails, `uncorrect` polishes the estimate (two corrections
// or more). A partial gain (the enable ramp) is the fixed point's.
// Where the full correction's Newton step is small enough, its result is proved instead of
// evaluated (ideal_step_remainder below): in the servo thread, seeded with the correction at the
// feedback, that is the rule. In the band, given a full correction kept from the last commands
// (the servo thread's), the band's rounds start from the seed and it: the two Newton solves of
// the first estimate are skipped and the first D starts next to its answer.
// Real-time: no allocation, no locks, no exceptions; bounded: at most 3 + 8 (1 + max_iterations)
// Newton solves of max_iterations steps and one bounded `uncorrect`.
#pragma once

#include "vc/machine/correct.hpp"

namespace vc::machine {

inline constexpr double kSeedRadius = 1.0;

// A correction (q_c - q_n) small enough to shift a seed by for joints like `point` (the answer
// is within it): given, of their size, finite, within kSeedRadius (mm or deg, any joint).
bool usable_correction(const Joints* correction, const Joints& point) noexcept;

// What a Newton step of the ideal machine's equations (tip onto a point, direction onto a
// direction) from `from` to `to` can leave of them. The step, with the exact Jacobian, cancels
// the first order; what is left is at most half the largest second derivative along the
// straight line between the two. The ideal machine, seen from the part, is one serial chain of
// rotations (rates w_i, Omega = sum |w_i| in rad) and translations (rates v_j, V = sum |v_j| in
// mm): the tip moves at sum w_i x (p - c_i) + sum v_j u_j, with c_i on axis i's line, so its
// acceleration is at most 3 Omega^2 R + 3 Omega V, and the direction's at most 2 Omega^2, where R
// bounds the tip's distance from every frame origin of the chain: the sum of the poles, the
// linear joints, the spindle's gauge point and the tool length.
struct StepRemainder {
  double position_mm;    // 1.5 (Omega^2 R + Omega V)
  double direction_rad;  // Omega^2
  double turn_rad;       // Omega: how far any direction of the chain turned (the pole angle moves
                         // by at most twice that)
};
StepRemainder ideal_step_remainder(const Model& model, const Joints& from, const Joints& to,
                                   double tool_length_mm) noexcept;

// q_n with q_c = q_n + gain * (correct(q_n) - q_n), the answer of `uncorrect` (to the solver
// tolerances), Newton started at `nominal_seed` (the previous answer), or at q_c where the seed
// is farther than kSeedRadius (mm or deg, any joint) from it.
// `full_correction` (optional): the full correction D (no fade, Correction::full_joints less
// the nominal joints) of a pose near the answer. In the fade band, with a near seed, the band's
// solve then starts from the seed and it instead of from the full solution's estimate: one
// evaluation of D fewer as a rule. Any D gives the same answer (to the tolerances).
// `iterations` counts the ideal machine's Newton steps plus the corrections evaluated.
// At the machine's `conditions`; the form without them at the machine file's.
Uncorrection invert_correction(const Model& model, const Conditions& conditions, const Joints& corrected,
                               double tool_length_mm, double gain, const Joints& nominal_seed,
                               const Joints* full_correction = nullptr) noexcept;
inline Uncorrection invert_correction(const Model& model, const Joints& corrected, double tool_length_mm, double gain,
                                      const Joints& nominal_seed, const Joints* full_correction = nullptr) noexcept {
  return invert_correction(model, model.reference_conditions(), corrected, tool_length_mm, gain, nominal_seed,
                           full_correction);
}

}  // namespace vc::machine
