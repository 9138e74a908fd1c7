// What a line says that depends on where it is read: LinuxCNC's #<_line> is the number of the
// line in the file, and a pre-distorted program has other line numbers (a header, moves split
// into pieces). These functions give such a line the meaning it had in the original program.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "vc/gcode/parameters.hpp"

namespace vc::interpreter {

// The text of a (DEBUG,...), (PRINT,...) or (LOG,...) message as LinuxCNC 2.9 expands it
// (interp_convert.cc, convert_param_comment): #n and #<name> become their values in the
// format of the last %d, %f or %.Nf before them ("%f" at first), unknown ones "######".
// `line` is the value of #<_line>.
std::string expand_message(std::string_view text, const gcode::Parameters& parameters, int line);

// Rewrites `raw` (line `line` of its file) if it reads #<_line>: in words and expressions the
// number itself, in DEBUG/PRINT/LOG comments the message expanded as LinuxCNC would expand it
// there. Returns false if the line does not read #<_line> (then `raw` is unchanged), and
// throws gcode::SyntaxError(offset) for a message whose expansion cannot be written back
// (it would contain '#' or '%', which LinuxCNC would expand again).
bool pin_line_number(std::string& raw, int line, const gcode::Parameters& parameters);

}  // namespace vc::interpreter
