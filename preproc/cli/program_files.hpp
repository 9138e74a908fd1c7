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
  std::optional<interpreter::ToolTable> tools;
  std::optional<gcode::Parameters> parameters;

  ProgramFiles(const std::string& tool_table, const std::string& var_file);
  // The interpreter's setup for `program` on `model` (tool length in world Z unless `tcp`).
  interpreter::Setup setup(const std::string& program, const machine::Model& model, bool tcp) const;
  // The deflection model of `process` on `model`, or nothing if no process file is given.
  std::optional<predistort::Deflection> deflection(const std::string& process, const machine::Model& model) const;
};

// "axes" or "tcp" (throws otherwise).
machine::WorldConvention world_convention(const std::string& name);

}  // namespace vc::cli
