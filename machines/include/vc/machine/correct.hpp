// Correction: the joint positions that make the real machine do what the ideal machine does.
//
// Given nominal joints q_n, find q_c with (model.md, Correction)
//     pos P(q_c) = pos P'(q_n)    and, where rotary axes set the tool direction,
//     b1 . (k* x k(q_c)) = 0, b2 . (k* x k(q_c)) = 0     (two rotary axes; b1, b2 _|_ k*)
//     a . (k* x k(q_c)) = 0                               (one rotary axis, a its line)
// Near a kinematic pole (tool axis near a rotary axis line, angle phi) the rotary joints take
// f(phi) of their full correction and the linear joints then make the position exact.
// Newton with the exact Jacobian (table slopes included), seeded with q_n or a given seed.
// With a contraction bound (contraction_bound.hpp), a step that the bound proves lands within
// the solver's tolerance is taken without evaluating the real machine after it.
// Real-time: no allocation, no locks, at most 2 * max_iterations Newton steps.
#pragma once

#include "vc/machine/forward.hpp"
#include "vc/machine/status.hpp"

namespace vc::machine {

struct Correction {
  Joints nominal;  // q_n
  Joints joints;   // q_c (not clamped to the travel: limits are LinuxCNC's business)
  Status status = Status::Ok;
  int iterations = 0;           // Newton steps taken
  double residual_mm = 0.0;     // |pos P(q_c) - pos P'(q_n)|
  double residual_rad = 0.0;    // |k'(q_n) x k(q_c)|: tool direction error left (by design > 0 where f < 1)
  bool unchecked_step = false;  // the last step taken on the contraction bound: residual_mm is its bound
                                // (and residual_rad at full correction)
  double pole_angle_rad = 0.0;  // phi: ideal tool direction to the nearest rotary axis line
  double fade = 1.0;            // f in [0, 1]
  // In the fade band (0 < f < 1): the full correction's joints (no fade), which correct() solved
  // for on the way; else empty.
  Joints full_joints;
  bool full_unchecked_step = false;  // in the fade band: full_joints' last step taken on the bound
};

// The correction at the machine's `conditions` (its temperatures and the pole fade in force:
// model.hpp), its Newton iteration seeded at `seed` (e.g. the previous servo cycle's solution).
// A step is taken unevaluated where `bound` (may be null) proves it within the tolerance:
// at full correction (f = 1) and a pole angle the bound covers, or in the last solve where f < 1
// (the position's, rotary joints held), at a tool length it covers. `full_seed` (may
// be null): where the full correction's Newton starts (an estimate of full_joints; the servo
// thread keeps them); `seed` is then the estimate of the faded answer (the fade band), where
// the linear joints start. Any seeds give the same answer (to the tolerances).
// The forms without conditions: at the machine file's (Model::reference_conditions()).
class ContractionBound;
Correction correct(const Model& model, const Conditions& conditions, const Joints& nominal, double tool_length_mm,
                   const Joints& seed, const ContractionBound* bound = nullptr,
                   const Joints* full_seed = nullptr) noexcept;
inline Correction correct(const Model& model, const Conditions& conditions, const Joints& nominal,
                          double tool_length_mm) noexcept {
  return correct(model, conditions, nominal, tool_length_mm, nominal);
}
inline Correction correct(const Model& model, const Joints& nominal, double tool_length_mm) noexcept {
  return correct(model, model.reference_conditions(), nominal, tool_length_mm, nominal);
}
inline Correction correct(const Model& model, const Joints& nominal, double tool_length_mm, const Joints& seed,
                          const ContractionBound* bound = nullptr, const Joints* full_seed = nullptr) noexcept {
  return correct(model, model.reference_conditions(), nominal, tool_length_mm, seed, bound, full_seed);
}

// The position alone: the linear joints of `joints` (in: their seed) moved so that the real
// machine puts the tool tip where the ideal machine puts it at `nominal`, the rotary joints
// staying as `joints` has them (a clamped rotary axis: held_rotary.hpp). `direction_error_rad`
// receives |k'(q_n) x k(joints)|, the tool direction error left.
Status correct_position(const Model& model, const Conditions& conditions, const Joints& nominal, double tool_length_mm,
                        Joints& joints, int& iterations, double& direction_error_rad) noexcept;

// The full correction (position and tool direction, no pole fade) at `nominal`, seeded at
// `seed`: what correct() fades near a pole (without rotary joints, correct() itself); `fade`
// reports the f that correct() would apply.
Correction full_correction(const Model& model, const Conditions& conditions, const Joints& nominal,
                           double tool_length_mm, const Joints& seed) noexcept;
inline Correction full_correction(const Model& model, const Joints& nominal, double tool_length_mm,
                                  const Joints& seed) noexcept {
  return full_correction(model, model.reference_conditions(), nominal, tool_length_mm, seed);
}

// Pole angle phi and fade factor f at nominal joints (ideal machine, part frame).
double pole_angle(const Model& model, const Joints& nominal, double tool_length_mm) noexcept;
double fade_factor(const PoleFade& fade, double pole_angle_rad) noexcept;

// The inverse of the correction map: the nominal joints q_n whose correction is `corrected`.
// Fixed-point iteration q_n <- q_n - (correct(q_n) - q_c); the map is the identity plus a
// small smooth function, so it contracts by about the largest table slope per step.
// Real-time: at most max_iterations corrections.
struct Uncorrection {
  Joints nominal;
  Status status = Status::Ok;
  int iterations = 0;  // corrections evaluated
  // invert_correction: the ideal machine's last Newton step was proved within the tolerances
  // (ideal_step_remainder), not evaluated.
  bool unchecked_step = false;
};
// For a partly applied correction, q_c = q_n + gain * (correct(q_n) - q_n) with gain in [0, 1]
// (the module's enable ramp), starting at `nominal_seed` (e.g. the previous answer).
Uncorrection uncorrect(const Model& model, const Conditions& conditions, const Joints& corrected, double tool_length_mm,
                       double gain, const Joints& nominal_seed) noexcept;
inline Uncorrection uncorrect(const Model& model, const Joints& corrected, double tool_length_mm, double gain,
                              const Joints& nominal_seed) noexcept {
  return uncorrect(model, model.reference_conditions(), corrected, tool_length_mm, gain, nominal_seed);
}
inline Uncorrection uncorrect(const Model& model, const Joints& corrected, double tool_length_mm) noexcept {
  return uncorrect(model, corrected, tool_length_mm, 1.0, corrected);
}

}  // namespace vc::machine
