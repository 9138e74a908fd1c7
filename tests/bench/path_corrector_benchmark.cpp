// Cost per move of the pre-distorter's correction alone (PathCorrector::correct: the point's
// correction, the bounds that accept its piece, check points where needed), on the moves of
// the end-to-end benchmark programs (tests/bench/make_programs.py), interpreted once and
// cycled: the correcting threads' share of a run, without reading or writing.
// Run: build/tests/bench/path_corrector_benchmark --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vc/gcode/parser.hpp"
#include "vc/interpreter/interpreter.hpp"
#include "vc/interpreter/linuxcnc_files.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/path_corrector.hpp"
#include "vc/predistort/predistort.hpp"

namespace vc::predistort {
namespace {

struct Program {
  machine::Model model;
  std::vector<interpreter::Move> moves;
};

// The first `lines` lines of make_programs.py's program for `machine` ("mc300": 5axis,
// "mill3": 3axis), generated into a temporary file and interpreted with the test files.
Program interpreted(const std::string& machine, int lines) {
  const std::string kind = machine == "mc300" ? "5axis" : "3axis";
  const std::string path = "/tmp/path_corrector_benchmark_" + kind + ".ngc";
  const std::string command = "python3 " + test::source_path("tests/bench/make_programs.py") + " " + kind + " " +
                              std::to_string(lines) + " " + path;
  if (std::system(command.c_str()) != 0) throw std::runtime_error("cannot run " + command);
  Program p{machine::load_machine(test::machine_path(machine)), {}};
  const interpreter::ToolTable tools =
      interpreter::read_tool_table(test::source_path("tests/programs/" + machine + ".tbl"));
  gcode::Parameters var;
  interpreter::read_var_file(test::source_path("tests/programs/" + machine + ".var"), var);
  interpreter::Setup setup;
  setup.file = path;
  setup.machine_axes = program_axes(p.model);
  setup.tools = &tools;
  setup.var_file = &var;
  interpreter::Interpreter interpreter(setup);
  {
    std::ifstream in(path);
    gcode::Block block;
    interpreter::Effect effect;
    std::string raw;
    for (int number = 1; std::getline(in, raw); ++number) {
      interpreter.read(raw, number, block, effect);
      if (effect.translate && effect.moves.size() == 1 && effect.moves.front().kind == interpreter::MoveKind::Line)
        p.moves.push_back(effect.moves.front());
    }
  }
  std::remove(path.c_str());
  return p;
}

void BM_CorrectMove(benchmark::State& state, const std::string& machine) {
  const Program p = interpreted(machine, 20000);
  PathCorrector corrector(p.model, p.model.reference_conditions(), CorrectorOptions{}, nullptr);
  std::vector<Piece> pieces;
  std::size_t i = 0;
  for (auto _ : state) {
    corrector.correct(p.moves[i], pieces);
    benchmark::DoNotOptimize(pieces.data());
    if (++i == p.moves.size()) {
      i = 0;
      corrector.lost_position();  // the cycle jumps back to the start
    }
  }
  state.counters["pieces_per_move"] = static_cast<double>(corrector.stats().pieces) / corrector.stats().moves;
}

BENCHMARK_CAPTURE(BM_CorrectMove, mc300_5axis, std::string("mc300"));
BENCHMARK_CAPTURE(BM_CorrectMove, mill3_3axis, std::string("mill3"));

}  // namespace
}  // namespace vc::predistort

BENCHMARK_MAIN();
