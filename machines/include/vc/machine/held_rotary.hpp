// Rotary axes that cannot take their correction now: clamped between indexing moves (3+2 work,
// LinuxCNC's locking indexer). ISO/TR 16907 11.2 b (L901): "a clamped axis cannot take
// compensation". A held rotary joint keeps the correction it had when it was clamped, so it
// does not move; the linear joints put the tool tip exactly where the ideal machine has it for
// the rotary joints so placed (the position alone: the tool direction keeps what the held
// joints leave of its error). A joint unclamped again goes back to its free correction over a
// release ramp (volkins: ramp-time), so that neither clamping nor unclamping moves anything
// abruptly.
//
// With a rotary joint j's free correction F_j (correct(): with its pole fade, times the gain g
// of the enable ramp), its correction is
//     c_j = offset_j + release_j (F_j - offset_j)       (release 0: held at offset_j; 1: free)
// and the linear joints are q_n + g (P - q_n), P their position solve for the rotary joints at
// q_n + c (correct_position). With every release 1 that is correct()'s answer at g = 1 and at g
// = 0 (between, the linear joints solve for the applied rather than the full rotary
// correction: a clamp that engages during the enable ramp moves them by up to g (1 - g) times
// the position effect of the rotary correction; clamps engage at rest, after an indexing move).
// Real-time: no allocation; bounded (one correct() and one position solve per evaluation, the
// inverse a fixed point of at most max_iterations of them).
#pragma once

#include <array>

#include "vc/machine/correct.hpp"

namespace vc::machine {

struct HeldRotary {
  std::array<double, kMaxAxes> offset_deg{};                           // by joint: the correction held (rotary joints)
  std::array<double, kMaxAxes> release{1.0, 1.0, 1.0, 1.0, 1.0, 1.0};  // 0 held .. 1 free
  // Some rotary joint of `model` is not free: the held path applies.
  bool any(const Model& model) const noexcept;
};

// q_c for nominal joints q_n (gain included: a held joint does not follow it). `seed`: the
// previous answer, or q_n. residual_rad reports the tool direction error left.
Correction correct_held(const Model& model, const Conditions& conditions, const Joints& nominal, double tool_length_mm,
                        double gain, const HeldRotary& held, const Joints& seed) noexcept;

// Its inverse: q_n with correct_held(q_n) = q_c, by the fixed point q_n <- q_n - (correct_held(q_n)
// - q_c), started at `nominal_seed`.
Uncorrection uncorrect_held(const Model& model, const Conditions& conditions, const Joints& corrected,
                            double tool_length_mm, double gain, const HeldRotary& held,
                            const Joints& nominal_seed) noexcept;

}  // namespace vc::machine
