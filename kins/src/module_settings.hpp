// What `loadrt volkins machine=... coordinates=... world=... sparm=... units=...` asks for, checked at load time.
//
// Pure C++ (no LinuxCNC headers) so the rules are unit-tested without a running HAL. Throws
// vc::LoadError (machine file and tables: file, line, problem) or std::runtime_error (the
// parameters themselves); never used in the servo thread.
#pragma once

#include <array>
#include <optional>

#include "vc/machine/contraction_bound.hpp"
#include "vc/machine/kinematics.hpp"

namespace vc::kins {

// Temperature inputs the module takes (a HAL pin each): as many as a model has.
inline constexpr int kMaxTemperatureInputs = machine::kMaxTemperatureInputs;
// LinuxCNC's joints (EMCMOT_MAX_JOINTS).
inline constexpr int kMaxJoints = 16;

struct ModuleSettings {
  machine::Model model;
  // The kinematics types motion.switchkins-type selects (LinuxCNC 2.9 switchable kinematics):
  // type 0, the one LinuxCNC starts in, and type 1, the other world convention (identity and
  // TCP, as LinuxCNC's trt modules with and without sparm=identityfirst). A machine without a
  // Z axis has no TCP world: one type only.
  std::array<machine::WorldConvention, 2> kinematics_types{machine::WorldConvention::Axes,
                                                           machine::WorldConvention::Tcp};
  int kinematics_type_count() const { return z_joint >= 0 ? 2 : 1; }
  // For each joint of the machine file (one per axis), its field in LinuxCNC's EmcPose in the
  // order x y z a b c u v w.
  std::array<int, machine::kMaxAxes> pose_field{};
  // LinuxCNC's joints, one per letter of coordinates=: the machine file's joint each drives (a
  // letter given twice drives two joints alike: a gantry's two Y motors), and for each machine
  // joint the first of its LinuxCNC joints, the one the forward reads (LinuxCNC's principal joint).
  // A joint of the machine file's tool_axis_coordinate (5axiskins' W) drives no axis of the
  // model: model_joint -1, its command is the world's coordinate (the linear joints make its
  // motion); tool_axis_joint is the first such joint (-1: none), tool_axis_field its EmcPose field.
  int joint_count = 0;
  std::array<int, kMaxJoints> model_joint{};
  std::array<int, machine::kMaxAxes> principal_joint{};
  int tool_axis_joint = -1;
  int tool_axis_field = -1;
  // The Z joint. In the TCP convention LinuxCNC's G43 has added the tool length to world Z
  // (as with its own TCP kinematics, whose tool-offset pin follows motion.tooloffset.z): the
  // module takes it off before the core sees the tool tip, and adds it back in the forward.
  int z_joint = -1;
  // The inverse takes a Newton step without evaluating the real machine after it where this
  // bound proves the step within the solver's tolerance (machine::ContractionBound): sampled
  // at kBoundToolLengthsMm (the correction length between the first and the last, else every
  // step is evaluated) with the temperatures drawn over their inputs' ranges.
  std::optional<machine::ContractionBound> contraction;
  // LinuxCNC's length unit in mm (units=: 1 or 25.4). Motion hands the kinematics joints, world
  // positions and the tool length offset in it; the model is in mm. The module converts them
  // where they cross (linear_scale) and nowhere else.
  double mm_per_unit = 1.0;
  // Per joint of the machine file: mm per LinuxCNC unit for a linear axis, 1 for a rotary one (deg).
  std::array<double, machine::kMaxAxes> linear_scale{};
};

inline constexpr std::array<double, 6> kBoundToolLengthsMm{0.0, 100.0, 200.0, 300.0, 400.0, 500.0};

// machine: the machine file (required). coordinates: LinuxCNC's axis letters, one per joint
// (optional; default the machine's own, in its order): every axis of the machine file at least
// once, no other letter but its tool_axis_coordinate; a letter twice gives two joints the same
// command. world: the world of kinematics type 0, "axes" (default) or "tcp" (needs a Z axis).
// sparm: LinuxCNC's switchable modules' parameter; "identityfirst" makes type 0 the identity
// (axes) world, as world=axes. units: LinuxCNC's [TRAJ]LINEAR_UNITS, "mm" (default) or "inch".
ModuleSettings settings_from_parameters(const char* machine, const char* coordinates, const char* world,
                                        const char* sparm = nullptr, const char* units = nullptr);

}  // namespace vc::kins
