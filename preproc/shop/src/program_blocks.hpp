// Reads a part program as the pre-distorter does (interpreter::ProgramReader: the lines in the
// order LinuxCNC executes them, subroutines and loops flattened), each line interpreted, then
// handed to `visit(raw, block, effect, line)`. A line that cannot be read throws
// vc::LoadError with file:line:column.
#pragma once

#include <istream>
#include <string>

#include "vc/interpreter/interpreter.hpp"
#include "vc/interpreter/program_reader.hpp"

namespace vc::shop {

template <typename Visit>
void for_each_block(std::istream& program, interpreter::Interpreter& interpreter, const interpreter::Setup& setup,
                    Visit visit) {
  interpreter::ProgramReader reader(program, setup.file, interpreter, setup.subroutine_path);
  gcode::Block block;
  interpreter::Effect effect;
  interpreter::Origin origin;
  std::string raw;
  while (reader.next(raw, origin, block, effect)) visit(raw, block, effect, origin.line);
}

}  // namespace vc::shop
