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

#include "vc/machine/invert_correction.hpp"

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

// What the kinematics module asks: a fraction of the correction, and solvers that start near
// the answer. LinuxCNC passes the previous joints to the inverse and the previous world
// position to the forward; a seed farther than kSeedRadius (mm or deg, any joint) from the
// nominal joints is ignored, so any seed gives the same answer (to the solver tolerance).
struct Applied {
  double gain = 1.0;                  // 0: nominal kinematics, 1: full correction
  const Joints* seed = nullptr;       // joints (inverse) or world position (forward), or none
  static constexpr double kSeedRadius = machine::kSeedRadius;
};
// q = q_n + gain * (correct(q_n) - q_n).
Status joints_from_world(const Model& model, WorldConvention convention, const Joints& world,
                         double tool_length_mm, const Applied& applied, Joints& joints,
                         Correction* report = nullptr) noexcept;
// Its exact inverse; `iterations` (optional) receives the corrections evaluated.
Status world_from_joints(const Model& model, WorldConvention convention, const Joints& joints,
                         double tool_length_mm, const Applied& applied, Joints& world,
                         int* iterations = nullptr) noexcept;

}  // namespace vc::machine
