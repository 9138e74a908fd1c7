// Splines and NURBS (G5, G5.1, G5.2/G5.3): the arcs LinuxCNC 2.9 makes of them, the motion
// mode they leave, and what is refused, with line and column.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "vc/gcode/parser.hpp"
#include "vc/interpreter/interpreter.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::interpreter {
namespace {

struct Interpreted {
  std::vector<Move> moves;
  std::vector<Effect> effects;  // per line
  double motion_mode = 0.0;     // #<_motion_mode> at the end
};

Interpreted interpret(const std::string& program, const ToolTable* tools = nullptr) {
  gcode::Parameters zero;
  Setup setup;
  setup.file = "test.ngc";
  setup.machine_axes = 0b000111;
  setup.var_file = &zero;
  setup.tools = tools;
  Interpreter interp(setup);
  std::istringstream in(program);
  Interpreted run;
  gcode::Block block;
  int line = 0;
  for (std::string text; std::getline(in, text);) {
    Effect effect;
    interp.read(text, ++line, block, effect);
    run.moves.insert(run.moves.end(), effect.moves.begin(), effect.moves.end());
    run.effects.push_back(effect);
  }
  gcode::Block probe;
  Effect effect;
  std::string read = "#1 = #<_motion_mode>";
  interp.read(read, ++line, probe, effect);
  run.motion_mode = interp.parameters()[1];
  return run;
}

std::string refusal(const std::string& program, const ToolTable* tools = nullptr) {
  try {
    interpret(program, tools);
  } catch (const LoadError& e) {
    return e.what();
  }
  return "accepted";
}

const std::string kStart = "G21 G90 G17 G54\nG0 X0 Y0 Z0\nF100\n";  // lines 1-3

// Moves as LinuxCNC 2.9's task canon makes them: its own emccanon.cc NURBS_FEED and
// nurbs_additional_functions.cc, compiled in a scratch harness, fed these control points
// (ARC_FEED end, centre and turn; program units, printed with %.17g).
struct Expected {
  std::size_t index;
  double x, y, cx, cy;
  int turn;  // 1 counterclockwise
};

void expect_arcs(const std::vector<Move>& moves, std::size_t first, const std::vector<Expected>& expected) {
  for (const Expected& e : expected) {
    const Move& m = moves.at(first + e.index);
    ASSERT_EQ(m.kind, MoveKind::Arc) << e.index;
    EXPECT_NEAR(m.end[0], e.x, 1e-9) << e.index;
    EXPECT_NEAR(m.end[1], e.y, 1e-9) << e.index;
    EXPECT_NEAR(m.arc.center_first, e.cx, 1e-9) << e.index;
    EXPECT_NEAR(m.arc.center_second, e.cy, 1e-9) << e.index;
    EXPECT_EQ(m.arc.clockwise, e.turn < 0) << e.index;
  }
}

TEST(Splines, CubicSplineIsLinuxCncsBiarcs) {
  // Control points (0,0) (2,0) (10,7) (10,10): 16 biarcs, 32 arcs here.
  const Interpreted r = interpret(kStart + "G5 X10 Y10 I2 J0 P0 Q-3\n");
  ASSERT_EQ(r.moves.size(), 33u);
  expect_arcs(r.moves, 1,
              {{0, 0.22345911041033722, 0.02302202625577961, -3.8371460104913373e-05, 1.0963660640059503, 1},
               {1, 0.44189453125, 0.079345703125, -0.26528441432693339, 2.3702070767336498, 1},
               {16, 6.1680702141064119, 4.2770439987984323, -16.315002698129181, 27.237944032951585, 1},
               {31, 10, 10, 8.1022196462868319, 10.000050606505877, 1}});
  for (std::size_t i = 2; i < r.moves.size(); ++i) EXPECT_EQ(r.moves[i].start, r.moves[i - 1].end);
  EXPECT_DOUBLE_EQ(r.moves[1].feed, 100.0);
  EXPECT_TRUE(r.effects[3].translate);
}

TEST(Splines, WeightedNurbsIsLinuxCncsBiarcs) {
  // Order 4, points (0,0) (0,20) (20,20) weight 3, (20,0) (40,0): the moves at G5.3.
  const Interpreted r = interpret(kStart + "G5.2 X0 Y20 P1 L4\nX20 Y20 P3\nX20 Y0 P1\nX40 Y0 P1\nG5.3\n");
  for (int line = 4; line <= 7; ++line) {
    EXPECT_TRUE(r.effects[static_cast<std::size_t>(line - 1)].moves.empty()) << line;
    EXPECT_TRUE(r.effects[static_cast<std::size_t>(line - 1)].translate) << line;  // its words go
  }
  EXPECT_EQ(r.effects[3].motion_words.size(), 4u);  // X Y P L (and the code)
  EXPECT_EQ(r.effects[7].moves.size(), 40u);
  expect_arcs(r.moves, 1,
              {{0, 0.20992810977086018, 2.9340775805973895, 20.613474547550044, -0.00030920022865763388, -1},
               {1, 0.82198443579766522, 5.8122568093385203, 22.061234431282234, -0.20852238893039843, -1},
               {16, 16.095169906271714, 18.388830521963264, 14.30572242241513, 13.636091847061675, -1},
               {31, 22.958579881656803, 8.0473372781065056, 39.281969402442272, 21.610404149623314, 1},
               {39, 40, 0, 40.000309218784622, 20.614711621163316, 1}});
}

TEST(Splines, MotionModeAfterwardsIsLinuxCncs) {
  // G5 and G5.1 leave the mode as it was: X alone is a G1 again.
  Interpreted r = interpret(kStart + "G1 X1\nG5.1 X2 Y1 I1 J0\nX3 Y0\n");
  EXPECT_EQ(r.effects[4].modal_motion, 10);
  EXPECT_EQ(r.moves.back().kind, MoveKind::Line);
  EXPECT_DOUBLE_EQ(r.moves.back().end[0], 3.0);
  EXPECT_DOUBLE_EQ(r.motion_mode, 10.0);
  r = interpret(kStart + "G0 X1\nG5 X2 Y1 I1 J0 P0 Q-1\n");
  EXPECT_DOUBLE_EQ(r.motion_mode, 0.0);
  // G5.2 is a mode; after G5.3 there is none (#<_motion_mode> -1, as LinuxCNC's).
  r = interpret(kStart + "G5.2 X1 Y1 P1\n");
  EXPECT_DOUBLE_EQ(r.motion_mode, 52.0);
  r = interpret(kStart + "G5.2 X1 Y1 P1\nX2 Y0 P1\nG5.3\n");
  EXPECT_DOUBLE_EQ(r.motion_mode, -1.0);
  EXPECT_EQ(r.effects[5].modal_motion, -1);
  EXPECT_DOUBLE_EQ(r.moves.back().end[0], 2.0);
}

TEST(Splines, G5WithoutIJContinuesFromTheLastPQ) {
  // Without I J the first control point is the start minus the last G5's P Q.
  const Interpreted implicit = interpret(kStart + "G5 X10 Y10 I2 J0 P0 Q-3\nG5 X20 Y0 P2 Q0\n");
  const Interpreted explicit_ij = interpret(kStart + "G5 X10 Y10 I2 J0 P0 Q-3\nG5 X20 Y0 I0 J3 P2 Q0\n");
  ASSERT_EQ(implicit.moves.size(), explicit_ij.moves.size());
  for (std::size_t i = 0; i < implicit.moves.size(); ++i) EXPECT_EQ(implicit.moves[i].end, explicit_ij.moves[i].end);
  // The first G5 of a program without I J starts along its chord's first point: the start.
  EXPECT_EQ(refusal(kStart + "G5 X10 Y10 P0 Q-3\n"), "accepted");
}

TEST(Splines, InchesAreComputedInInches) {
  // LinuxCNC's test for an arc too flat to be one is in program units: this shallow curve is
  // straight lines in inches, arcs in millimetres.
  const Interpreted inch = interpret("G20 G90 G17 G54\nG0 X0 Y0 Z0\nF10\nG5.1 X1 Y0 I0.5 J0.0001\n");
  const Interpreted mm = interpret(kStart + "G5.1 X25.4 Y0 I12.7 J0.00254\n");
  ASSERT_EQ(inch.moves.size(), 25u);
  ASSERT_EQ(mm.moves.size(), 25u);
  for (std::size_t i = 1; i < 25; ++i) {
    EXPECT_EQ(inch.moves[i].kind, MoveKind::Line);
    EXPECT_EQ(mm.moves[i].kind, MoveKind::Arc);
    EXPECT_NEAR(inch.moves[i].end[0], mm.moves[i].end[0], 1e-9);
  }
  EXPECT_NEAR(inch.moves.back().end[0], 25.4, 1e-12);
  EXPECT_NEAR(inch.moves[1].feed, 10.0, 1e-12);  // inches per minute, as the program's units
}

TEST(Splines, ArcsTooSmallForG2G3AreWrittenAsChords) {
  // This curve turns sharply: one of LinuxCNC's arcs has a radius of 1 um, which a G2/G3
  // could not have (LinuxCNC refuses a radius under 0.00127 mm): chords on that arc instead.
  const Interpreted r = interpret(kStart + "G5.1 X-0.1993722 Y-0.0311048 I0.0543611 J-0.0081788\n");
  int chords = 0;
  for (std::size_t i = 1; i < r.moves.size(); ++i) {
    const Move& m = r.moves[i];
    EXPECT_EQ(m.start, r.moves[i - 1].end);
    if (m.kind == MoveKind::Arc)
      EXPECT_GE(std::hypot(m.start[0] - m.arc.center_first, m.start[1] - m.arc.center_second), 0.0013);
    else
      ++chords;
  }
  EXPECT_GE(chords, 5);
  // They lie on LinuxCNC's fifth arc (centre (0.0085749640, -0.0034154656), radius 1.03 um).
  ASSERT_EQ(r.moves[5].kind, MoveKind::Line);
  for (std::size_t i = 5; i < 5 + static_cast<std::size_t>(chords); ++i)
    EXPECT_NEAR(std::hypot(r.moves[i].end[0] - 0.0085749640, r.moves[i].end[1] + 0.0034154656), 0.00103, 2e-5) << i;
  EXPECT_NEAR(r.moves.back().end[0], -0.1993722, 1e-12);
}

TEST(Splines, RefusesWhatLinuxCncRefusesWithLineAndColumn) {
  EXPECT_NE(refusal(kStart + "G18 G5 X1 Y1 I1 J0 P0 Q1\n").find("test.ngc:4:5: error: G5 spline outside the XY plane"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5 X1 Y1 I1 P0 Q1\n").find("test.ngc:4:10: error: G5 needs both I and J, or neither"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5 X1 Y1 I1 J0 P1\n").find("test.ngc:4:1: error: G5 needs both P and Q"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.1 X1 Y1 I1\n").find("test.ngc:4:1: error: G5.1 needs both I and J"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.1 X1 Y1 Z1 I1 J0\n").find("test.ngc:4:12: error: splines may not have motion in Z"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.1 I1 J0\n").find("test.ngc:4:1: error: G5.1 without axis words"), std::string::npos);
  EXPECT_NE(
      refusal("G21 G90 G54\nG0 X0 Y0 Z0\nG5.1 X1 Y1 I1 J0\n").find("test.ngc:3:1: error: G5.1 spline with zero feed"),
      std::string::npos);
  EXPECT_NE(refusal(kStart + "G93 G5.1 X1 Y1 I1 J0 F1\n").find("inverse time feed (G93) is not translated"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.3\n").find("test.ngc:4:1: error: G5.3 without G5.2 first"), std::string::npos);
  EXPECT_NE(refusal(kStart + "G81 X1 Y1 Z-1 R1\nG5.3\n").find("test.ngc:5:1: error: G5.3 without G5.2 first"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.2 X1 Y1 P1 L4\nX2 Y0 P1\nG5.3\n")
                .find("test.ngc:6:1: error: a NURBS of order L = 4 needs "
                      "at least 4 control points"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.2 X1 Y1 P1 L65\n").find("test.ngc:4:15: error: a NURBS of order L above 64"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.2 X1 P1\n").find("test.ngc:4:6: error: a G5.2 control point needs both X and Y"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.2 X1 Y1 P1\nX2 Y0\n")
                .find("test.ngc:5:1: error: every G5.2 control point needs a "
                      "positive weight P"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.2 X1 Y1 P1\nG5.2 P2\n")
                .find("test.ngc:5:6: error: P without X and Y is the weight of the "
                      "first G5.2 point only"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.2 X1 Y1 P1\nX2 Y0 P1\nG5.3 G1 X3\n")
                .find("test.ngc:6:6: error: between G5.2 and G5.3 only "
                      "more G5.2"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.2 X1 Y1 P1\nX2 Y0 P1\nG5.3\nX3\n")
                .find("test.ngc:7:1: error: axis words without a motion "
                      "mode (G0, G1, G2 or G3): G5.3 leaves none"),
            std::string::npos);
  EXPECT_NE(
      refusal(kStart + "G5.2 X1 Y1 P1\nX2 Y0 P1\nG5.3 G4 P1\n").find("test.ngc:6:6: error: G4 on a line with G5.3"),
      std::string::npos);
  EXPECT_NE(refusal(kStart + "G53 G5.1 X1 Y1 I1 J0\n").find("test.ngc:4:1: error: G53 on a line with G5.1"),
            std::string::npos);
  const ToolTable tools{{1, mill_tool(1, 10.0, 6.0)}};
  EXPECT_NE(refusal(kStart + "G41 D1 G1 X5\nG5.1 X7 Y1 I1 J0\n", &tools)
                .find("test.ngc:5:1: error: G5.1 spline with "
                      "cutter radius compensation on"),
            std::string::npos);
  // What a pre-distorter cannot write faithfully: a P, Q or L the moves would read as theirs,
  // a curve starting off the tool, LinuxCNC's own arithmetic failing (a straight piece).
  EXPECT_NE(refusal(kStart + "G64 P0.01 G5.1 X1 Y1 I1 J0\n").find("test.ngc:4:5: error: P on a line with G5.1"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G5 X1 Y1 I1 J0 P0 Q1 M50\n").find("P on this line is both G5's and another code's"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G41 D1 G1 X5\nG40\nG5.1 X7 Y1 I1 J0\n", &tools)
                .find("test.ngc:6:1: error: G5.1 spline "
                      "where the tool is not at the "
                      "programmed point (just after G40"),
            std::string::npos);
  EXPECT_EQ(refusal(kStart + "G41 D1 G1 X5\nG40\nG1 X6\nG5.1 X7 Y1 I1 J0\n", &tools), "accepted");
  EXPECT_NE(refusal(kStart + "G5.1 X10 Y0 I5 J0\n")
                .find("test.ngc:4:1: error: LinuxCNC 2.9's arcs for this curve are not "
                      "finite"),
            std::string::npos);
  EXPECT_NE(
      refusal(kStart + "G5.2 X1 Y1 P1\nX2 Y0 P1\nG1 X5\nG5.1 X6 Y1 I1 J0\n").find("after G5.2 points no G5.3 ended"),
      std::string::npos);
  EXPECT_NE(refusal(kStart + "G5.2 X1 Y1 P1\nX2 Y0 P1\nG92 X5\nG5.3\n").find("no longer where the tool is"),
            std::string::npos);
  EXPECT_NE(refusal("G21 G90 G54\nF100\nG5.1 X1 Y1 I1 J0\n").find("from an unknown position"), std::string::npos);
}

}  // namespace
}  // namespace vc::interpreter
