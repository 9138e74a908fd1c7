// Cutter radius compensation: the offset path worked out by hand for a square with a 10 mm
// tool, and each line keeping its own moves though LinuxCNC holds them back. The full
// behaviour (every corner kind, arcs, lathe tools, inches) is checked against LinuxCNC's own
// interpreter in the acceptance corpus (tests/acceptance/corpus/own/cutter_comp_*.ngc).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "program_reader.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::interpreter {
namespace {

using Line = test::LineMoves;

std::vector<Line> run(const std::string& program) { return test::run_lines(program, "test.ngc"); }

void expect_at(const Position& p, double x, double y) {
  EXPECT_NEAR(p[0], x, 1e-9);
  EXPECT_NEAR(p[1], y, 1e-9);
}

TEST(CutterCompensation, SquareByHandWithEachLineKeepingItsMoves) {
  const std::vector<Line> lines =
      run("G21 G90 G17 G0 X-20 Y-20 Z0\n"  // 1
          "G41.1 D10 G1 X0 Y0 F100\n"      // 2: entry, tool on the left: ends 5 mm left of (0, 0)
          "G1 X40\n"                       // 3: convex corner at (0, 0): an arc, then the line
          "G1 Y40\n"                       // 4: concave corner at (40, 0): line 3 ends 5 mm short
          "G40 G1 X60 Y60\n"               // 5: out, from where the tool is
          "M2\n");
  ASSERT_EQ(lines.size(), 6u);
  const double h = 5 / std::sqrt(2.0);
  // The lines come out in order, each with its own moves.
  for (int i = 0; i < 6; ++i) EXPECT_EQ(lines[static_cast<std::size_t>(i)].number, i + 1);
  ASSERT_EQ(lines[1].moves.size(), 1u);
  expect_at(lines[1].moves[0].start, -20, -20);
  expect_at(lines[1].moves[0].end, -h, h);
  ASSERT_EQ(lines[2].moves.size(), 2u);
  const Move& corner = lines[2].moves[0];
  EXPECT_EQ(corner.kind, MoveKind::Arc);
  EXPECT_TRUE(corner.arc.clockwise);  // around the outside of a right turn
  EXPECT_NEAR(corner.arc.center_first, 0, 1e-12);
  EXPECT_NEAR(corner.arc.center_second, 0, 1e-12);
  EXPECT_NEAR(corner.arc.sweep_rad, -M_PI / 4, 1e-9);
  expect_at(corner.end, 0, 5);
  expect_at(lines[2].moves[1].end, 35, 5);
  ASSERT_EQ(lines[3].moves.size(), 1u);
  expect_at(lines[3].moves[0].start, 35, 5);
  expect_at(lines[3].moves[0].end, 35, 40);
  ASSERT_EQ(lines[4].moves.size(), 1u);
  expect_at(lines[4].moves[0].start, 35, 40);
  expect_at(lines[4].moves[0].end, 60, 60);
}

TEST(CutterCompensation, RefusesWhatLinuxCncRefusesWithTheLine) {
  const auto refusal = [](const std::string& program) {
    try {
      run(program);
    } catch (const LoadError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // A concave corner the tool cannot reach: the earlier move would have to run backwards.
  EXPECT_NE(refusal("G0 X0 Y0 Z0\nG41.1 D10 G1 X20 F100\nG1 X22\nG1 Y20\nG40 G1 X0\nM2\n")
                .find("test.ngc:4:4: error: straight feed in concave corner cannot be reached"),
            std::string::npos);
  EXPECT_NE(refusal("G0 X0 Y0 Z0\nG41.1 D10 G1 X20 F100\nG40\nG2 X0 Y0 R10\nM2\n").find("must be straight"),
            std::string::npos);
  EXPECT_NE(refusal("G0 X0 Y0 Z0\nG41.1 D10 G1 X20 F100\nG1 Y5 (MSG, now)\n").find("a message while cutter"),
            std::string::npos);
  EXPECT_NE(refusal("G0 X0 Y0 Z0\nG41.1 D10 G1 X20 F100\nG1 Y5\n").find("test.ngc:2:1: error: the program ends while"),
            std::string::npos);
}

}  // namespace
}  // namespace vc::interpreter
