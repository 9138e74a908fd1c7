// Reads a G-code file with the project's own reader (vc_gcode + vc_interpreter) at full
// precision: the moves the interpreter makes, with the world frame of each.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "vc/gcode/parser.hpp"
#include "vc/interpreter/interpreter.hpp"

namespace vc::test {

inline std::vector<interpreter::Move> read_moves(const std::string& path, interpreter::Setup setup) {
  setup.file = path;
  interpreter::Interpreter interp(setup);
  std::ifstream in(path);
  gcode::Block block;
  interpreter::Effect effect;
  std::vector<interpreter::Move> moves;
  int line = 0;
  for (std::string text; std::getline(in, text);) {
    gcode::parse_block(text, block);
    interp.execute(block, ++line, effect);
    moves.insert(moves.end(), effect.moves.begin(), effect.moves.end());
  }
  return moves;
}

}  // namespace vc::test
