// What a line says that depends on where it is read: LinuxCNC's #<_line> is the number of the
// line in the file, and a pre-distorted program has other line numbers (a header, moves split
// into pieces). These functions give such a line the meaning it had in the original program.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "vc/gcode/block.hpp"
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

// The line `raw` (parsed into `block`, line `line` of its file) as it reads outside the
// subroutine call it is executed in: each word whose value is an expression or a parameter
// gets the value (with the parameters from before the line), assignments to the call's own
// parameters (names without '_' unless the line is the main program's: `in_main_program`, and
// #1..#30 unless the call shares them: `numbered_shared`) are dropped and the others get their
// values, and DEBUG/PRINT/LOG messages are expanded.
// Numbers are written as the shortest decimals that read back as the same double. Throws
// gcode::SyntaxError(offset) for what cannot be evaluated or written.
std::string evaluated_line(std::string_view raw, const gcode::Block& block, const gcode::Parameters& parameters,
                           int line, bool numbered_shared, bool in_main_program);

// The shortest fixed-point decimal that reads back as `value`, as a G-code word or parameter
// value is written (G-code has no exponents; vc::number_text, the files' formatter, may write "1e-07").
std::string gcode_number_text(double value);

}  // namespace vc::interpreter
