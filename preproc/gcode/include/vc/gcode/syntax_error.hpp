// An error in a block, located by column: the interpreter adds the file name and line.
#pragma once

#include <stdexcept>
#include <string>

namespace vc::gcode {

struct SyntaxError : std::runtime_error {
  SyntaxError(int at, const std::string& message) : std::runtime_error(message), offset(at) {}
  int offset;  // 0-based byte offset in the raw line (column = offset + 1)
};

}  // namespace vc::gcode
