// Reads a part program line by line, as the pre-distorter does: each line parsed and
// interpreted, then handed to `visit(raw, block, effect, line)`. A line that cannot be read
// throws vc::LoadError with file:line:column.
#pragma once

#include <istream>
#include <string>

#include "vc/interpreter/interpreter.hpp"

namespace vc::shop {

template <typename Visit>
void for_each_block(std::istream& program, interpreter::Interpreter& interpreter, Visit visit) {
  gcode::Block block;
  interpreter::Effect effect;
  std::string raw;
  for (int line = 1; std::getline(program, raw); ++line) {
    interpreter.read(raw, line, block, effect);
    visit(raw, block, effect, line);
  }
}

}  // namespace vc::shop
