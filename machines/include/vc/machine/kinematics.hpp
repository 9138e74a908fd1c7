// World <-> joints, as a LinuxCNC kinematics module sees them, with the correction inside.
//
// World conventions (model.md, Correction):
//   Axes: world coordinates are the nominal joints themselves (identity, as trivkins).
//   Tcp:  linear world coordinates are the ideal tool tip in the part frame, rotary ones the
//         rotary joints (tool-centre-point control, as LinuxCNC's xyzbc-trt-kins).
// Inverse:  world -> nominal joints q_n -> corrected joints q_c = correct(q_n).
// Forward:  its exact inverse, q_c -> q_n = invert_correction(q_c) -> world, so FK(IK(w)) = w.
// Real-time: no allocation, no locks, bounded iterations.
#pragma once

#include <limits>

#include "vc/machine/invert_correction.hpp"

namespace vc::machine {

enum class WorldConvention { Axes, Tcp };

// Nominal (ideal machine) kinematics.
Status nominal_inverse(const Model& model, WorldConvention convention, const Joints& world, double tool_length_mm,
                       Joints& nominal) noexcept;
Joints nominal_forward(const Model& model, WorldConvention convention, const Joints& nominal,
                       double tool_length_mm) noexcept;

// Corrected kinematics. `report` (optional) receives the correction's summary.
Status joints_from_world(const Model& model, WorldConvention convention, const Joints& world, double tool_length_mm,
                         Joints& joints, Correction* report = nullptr) noexcept;
Status world_from_joints(const Model& model, WorldConvention convention, const Joints& joints, double tool_length_mm,
                         Joints& world) noexcept;

// What the kinematics module asks: a fraction of the correction, and solvers that start near
// the answer. LinuxCNC passes the previous joints to the inverse and the previous world
// position to the forward; a seed farther than kSeedRadius (mm or deg, any joint) from the
// nominal joints is ignored, so any seed gives the same answer (to the solver tolerance).
// A nearer start is the last correction the module applied: the correction changes by the
// error slopes (~1e-4) times the step between cycles, so q_n + that correction is within
// ~1e-5 mm of this cycle's joints (the previous joints are a whole step, ~0.1 mm, away), and
// the joints less it within slope x following error of this cycle's nominal joints. Where
// given, it takes the place of `seed`.
struct HeldRotary;  // held_rotary.hpp

struct Applied {
  double gain = 1.0;                   // 0: nominal kinematics, 1: full correction
  const Joints* seed = nullptr;        // joints (inverse) or world position (forward), or none
  const Joints* correction = nullptr;  // a full correction q_c - q_n of a pose nearby, or none
  // The inverse: where it proves a Newton step within the tolerance, the step is taken without
  // evaluating the real machine after it (contraction_bound.hpp), or none.
  const ContractionBound* contraction = nullptr;
  // A full correction without the pole fade (Correction::full_joints less the nominal joints)
  // of a pose nearby, or none: where the inverse's full Newton starts, and the forward's
  // estimate of it in the fade band (invert_correction.hpp). Outside the band, the same as
  // `correction`.
  const Joints* full_correction = nullptr;
  // The tool length of the nominal TCP kinematics where it differs from the correction's
  // (NaN: the same). volkins' correction follows a new tool length offset over a slew time,
  // while LinuxCNC's world position takes it at once (G43 adds it to world Z): the nominal
  // joints take it at once too, as LinuxCNC's own TCP kinematics do, so that a G43 does not
  // move the joints where the stock kinematics would not (at B = 0 the world's Z is the Z
  // joint's whatever the offset). With a tool-axis coordinate (Model::tool_axis_coordinate) it
  // also holds its value w: the nominal kinematics place a tool L + w long, the correction is
  // for the real tool. Only the Tcp convention's nominal joints depend on it.
  double nominal_tool_length_mm = std::numeric_limits<double>::quiet_NaN();
  // The machine's conditions (temperatures, pole fade: model.hpp), or none: the file's.
  const Conditions* conditions = nullptr;
  // Rotary joints clamped or on their way back from a clamp (held_rotary.hpp), or none. Where
  // any is, the held path solves (the seeds above but `seed` and the contraction are not used).
  const HeldRotary* held = nullptr;
  static constexpr double kSeedRadius = machine::kSeedRadius;
};
// q = q_n + gain * (correct(q_n) - q_n).
Status joints_from_world(const Model& model, WorldConvention convention, const Joints& world, double tool_length_mm,
                         const Applied& applied, Joints& joints, Correction* report = nullptr) noexcept;
// Its exact inverse; `iterations` (optional) receives the corrections evaluated.
Status world_from_joints(const Model& model, WorldConvention convention, const Joints& joints, double tool_length_mm,
                         const Applied& applied, Joints& world, int* iterations = nullptr) noexcept;

}  // namespace vc::machine
