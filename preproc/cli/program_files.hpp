// The LinuxCNC files a part program is read with (tool table, parameter file) and the
// cutting conditions, loaded once for the commands that run programs.
#pragma once

#include <optional>
#include <string>

#include "vc/interpreter/interpreter.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/predistort/deflection.hpp"

namespace vc::cli {

struct ProgramFiles {
  std::optional<interpreter::ToolTable> tools;  // lengths in mm
  std::optional<gcode::Parameters> parameters;  // as in the file: the machine's units
  double machine_unit_mm = 1.0;                 // 25.4: LinuxCNC set up in inches

  // machine_units: "mm" or "inch", LinuxCNC's [TRAJ]LINEAR_UNITS, the unit of both files.
  ProgramFiles(const std::string& tool_table, const std::string& var_file, const std::string& machine_units);
  // The interpreter's setup for `program` on `model` (tool length in world Z unless `tcp`).
  interpreter::Setup setup(const std::string& program, const machine::Model& model, bool tcp) const;
  // The deflection model of `process` on `model`, or nothing if no process file is given.
  std::optional<predistort::Deflection> deflection(const std::string& process, const machine::Model& model) const;
};

// The length of "mm" or "inch" (--machine-units) in mm; throws std::runtime_error otherwise.
double machine_unit_mm(const std::string& name);

// Where the machine is when the program starts (world coordinates, mm and deg), from
// `--start`: "X,Y,Z[,A,B,C]" (mm and deg), or a LinuxCNC INI file whose [JOINT_n]HOME values
// the machine has after homing (joint n is the n-th letter of [TRAJ]COORDINATES, as trivkins
// maps them; in its [TRAJ]LINEAR_UNITS, which must be the --machine-units given).
// Throws vc::LoadError (file:line) or std::runtime_error with what cannot be read.
interpreter::Position start_position(const std::string& value, double machine_unit_mm);

// "axes" or "tcp" (throws otherwise).
machine::WorldConvention world_convention(const std::string& name);

}  // namespace vc::cli
