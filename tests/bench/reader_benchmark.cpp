// Cost per line of the pre-distorter's reader: parse_block alone, and parse_block plus the
// interpreter, on the lines of the end-to-end benchmark programs (tests/bench/make_programs.py:
// "X.. Y.. Z.. B.. C.." on the MC-300, "X.. Y.. Z.." on mill3), 4096 lines cycled.
// Run: build/tests/bench/reader_benchmark --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "vc/gcode/parser.hpp"
#include "vc/interpreter/interpreter.hpp"

namespace vc {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<std::string> program_lines(bool five_axis) {
  std::vector<std::string> lines;
  char text[128];
  for (int k = 0; k < 4096; ++k) {
    const double c = std::fmod(k * 0.05, 720.0), t = c * kPi / 180.0;
    if (five_axis)
      std::snprintf(text, sizeof text, "X%.4f Y%.4f Z%.4f B%.4f C%.4f", -300 + 60 * std::cos(t),
                    -160 + 60 * std::sin(t), -200 + 5 * std::sin(3 * t), -35 + 10 * std::sin(2 * t), c);
    else
      std::snprintf(text, sizeof text, "X%.4f Y%.4f Z%.4f", -140 + 0.55 * k, -55.0, -2 + 0.5 * std::sin(k / 7.0));
    lines.emplace_back(text);
  }
  return lines;
}

void BM_ParseBlock(benchmark::State& state, bool five_axis) {
  const std::vector<std::string> lines = program_lines(five_axis);
  gcode::Block block;
  std::size_t i = 0;
  for (auto _ : state) {
    gcode::parse_block(lines[i], block);
    benchmark::DoNotOptimize(block.words.data());
    i = (i + 1) % lines.size();
  }
}

void BM_ParseAndInterpret(benchmark::State& state, bool five_axis) {
  const std::vector<std::string> lines = program_lines(five_axis);
  interpreter::Setup setup;
  setup.file = "benchmark.ngc";
  setup.machine_axes = five_axis ? 0b110111u : 0b000111u;  // X Y Z (B C)
  interpreter::Interpreter interpreter(setup);
  gcode::Block block;
  interpreter::Effect effect;
  int number = 0;
  const char* start = five_axis ? "G54 G0 X0 Y0 Z0 B0 C0" : "G54 G0 X0 Y0 Z0";
  for (const char* preamble : {"G21 G90 G17 G94", "G10 L2 P1 X0 Y0 Z0", start, "G1 F2000"}) {
    gcode::parse_block(preamble, block);
    interpreter.execute(block, ++number, effect);
  }
  std::size_t i = 0;
  for (auto _ : state) {
    gcode::parse_block(lines[i], block);
    interpreter.execute(block, ++number, effect);
    benchmark::DoNotOptimize(effect.moves.data());
    i = (i + 1) % lines.size();
  }
}

BENCHMARK_CAPTURE(BM_ParseBlock, mc300_5axis, true);
BENCHMARK_CAPTURE(BM_ParseBlock, mill3_3axis, false);
BENCHMARK_CAPTURE(BM_ParseAndInterpret, mc300_5axis, true);
BENCHMARK_CAPTURE(BM_ParseAndInterpret, mill3_3axis, false);

}  // namespace
}  // namespace vc

BENCHMARK_MAIN();
