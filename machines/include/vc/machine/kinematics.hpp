// World <-> joints, as a LinuxCNC kinematics module sees them, with the correction inside.
//
// World conventions (model.md, Correction):
//   Axes: world coordinates are the nominal joints themselves (identity, as trivkins).
//   Tcp:  linear world coordinates are the ideal tool tip in the part frame, rotary ones the
//         rotary joints (tool-centre-point control, as LinuxCNC's xyzbc-trt-kins).
// Inverse:  world -> nominal joints q_n -> corrected joints q_c = correct(q_n).
// Forward:  its exact inverse, q_c -> q_n = uncorrect(q_c) -> world, so FK(IK(w)) = w.
// Real-time: no allocation, no locks, bounded iterations.
#pragma once

#include "vc/machine/correct.hpp"

namespace vc::machine {

enum class WorldConvention { Axes, Tcp };

// Nominal (ideal machine) kinematics.
Status nominal_inverse(const Model& model, WorldConvention convention, const Joints& world,
                       double tool_length_mm, Joints& nominal) noexcept;
Joints nominal_forward(const Model& model, WorldConvention convention, const Joints& nominal,
                       double tool_length_mm) noexcept;

// Corrected kinematics. `report` (optional) receives the correction's summary.
Status joints_from_world(const Model& model, WorldConvention convention, const Joints& world,
                         double tool_length_mm, Joints& joints, Correction* report = nullptr) noexcept;
Status world_from_joints(const Model& model, WorldConvention convention, const Joints& joints,
                         double tool_length_mm, Joints& world) noexcept;

}  // namespace vc::machine
