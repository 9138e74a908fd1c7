// Reads a G-code file with the project's own reader (vc_gcode + vc_interpreter) at full
// precision: the moves the interpreter makes, with the world frame of each.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "vc/gcode/parser.hpp"
#include "vc/interpreter/interpreter.hpp"
#include "vc/interpreter/program_reader.hpp"

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

// A program (text) run through ProgramReader on an XYZ machine with zero offsets, as `file`:
// the lines in the order they come out, each with its own moves (cutter compensation and the
// lathe cycles hand lines out when their moves are final). Throws vc::LoadError.
struct LineMoves {
  int number;
  std::vector<interpreter::Move> moves;
};

inline std::vector<LineMoves> run_lines(const std::string& program, const std::string& file) {
  gcode::Parameters var;
  interpreter::Setup setup;
  setup.file = file;
  setup.machine_axes = 0b111;
  setup.var_file = &var;
  interpreter::Interpreter interpreter(setup);
  std::istringstream in(program);
  interpreter::ProgramReader reader(in, file, interpreter);
  std::vector<LineMoves> lines;
  std::string raw;
  interpreter::Origin origin;
  gcode::Block block;
  interpreter::Effect effect;
  while (reader.next(raw, origin, block, effect)) lines.push_back({origin.line, effect.moves});
  return lines;
}

}  // namespace vc::test
