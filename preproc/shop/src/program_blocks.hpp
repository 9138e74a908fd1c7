// Reads a part program line by line, as the pre-distorter does: each line parsed and
// interpreted, then handed to `visit(raw, block, effect, line)`. A line that cannot be read
// throws vc::LoadError with file:line:column.
#pragma once

#include <istream>
#include <string>

#include "vc/gcode/parser.hpp"
#include "vc/interpreter/interpreter.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::shop {

template <typename Visit>
void for_each_block(std::istream& program, interpreter::Interpreter& interpreter, const std::string& file, Visit visit) {
  gcode::Block block;
  interpreter::Effect effect;
  std::string raw;
  for (int line = 1; std::getline(program, raw); ++line) {
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();  // DOS line ends
    try {
      gcode::parse_block(raw, block);
    } catch (const gcode::SyntaxError& e) {
      throw LoadError({file, line, e.offset + 1}, e.what());
    }
    interpreter.execute(block, line, effect);
    visit(raw, block, effect, line);
  }
}

}  // namespace vc::shop
