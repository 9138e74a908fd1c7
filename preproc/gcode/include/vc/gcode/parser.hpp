// Reads one line of RS274/NGC as LinuxCNC does: spaces and tabs ignored outside comments,
// letters case-insensitive, '(' comments ')' and ';' comments, '/' block delete, N line
// numbers, words with numbers or [expressions], #parameter assignments, O words (recorded,
// not interpreted). Grammar: Boost.Spirit X3 (parser_def.hpp).
#pragma once

#include <string_view>

#include "vc/gcode/block.hpp"
#include "vc/gcode/syntax_error.hpp"

namespace vc::gcode {

// Fills `block` (cleared first) from `line` (without its end of line). Throws SyntaxError
// with the offset of the first character that cannot be read and a message saying what was
// expected there.
void parse_block(std::string_view line, Block& block);

}  // namespace vc::gcode
