// Values of expressions and the effect of a block's assignments, with LinuxCNC's semantics
// (checked against `rs274 -g`): angles in degrees, EQ/NE/GT/... give 1 or 0, AND/OR/XOR
// test for non-zero, MOD and ROUND/FIX/FUP as LinuxCNC computes them.
#pragma once

#include "vc/gcode/block.hpp"
#include "vc/gcode/parameters.hpp"
#include "vc/gcode/syntax_error.hpp"

namespace vc::gcode {

// Throws SyntaxError(offset) for division by zero, a function outside its domain (SQRT of a
// negative, LN of a non-positive, ACOS/ASIN outside [-1, 1]), an unknown parameter or an
// index outside 1..5601. `offset` is where the expression was written (a word's begin).
double evaluate(const ast::Expression& expression, const Parameters& parameters, int offset);

// Evaluates every assignment of the block with the values from before the line, then sets
// them in the order written (LinuxCNC: "parameter setting ... after the line is read").
void apply_assignments(const Block& block, Parameters& parameters);

}  // namespace vc::gcode
