// The interpreter's meaning of blocks: positions, frames, arcs, and what it refuses.
#include <gtest/gtest.h>

#include <array>

#include <sstream>

#include "vc/gcode/parser.hpp"
#include "vc/interpreter/interpreter.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::interpreter {
namespace {

constexpr unsigned kXyzbc = 0b110111;

struct Interpreted {
  std::vector<Move> moves;
  std::vector<Effect> effects;
  std::array<double, 10> locals{};  // #1..#10 at the end
};

Interpreted interpret(const std::string& program, const ToolTable* tools = nullptr,
                      const gcode::Parameters* var = nullptr, unsigned axes = kXyzbc, double machine_unit_mm = 1.0) {
  Setup setup;
  setup.file = "test.ngc";
  setup.machine_axes = axes;
  setup.tools = tools;
  setup.var_file = var;
  setup.machine_unit_mm = machine_unit_mm;
  Interpreter interp(setup);
  std::istringstream in(program);
  Interpreted run;
  gcode::Block block;
  int line = 0;
  for (std::string text; std::getline(in, text);) {
    Effect effect;
    gcode::parse_block(text, block);
    interp.execute(block, ++line, effect);
    run.moves.insert(run.moves.end(), effect.moves.begin(), effect.moves.end());
    run.effects.push_back(effect);
  }
  for (int i = 1; i <= 10; ++i) run.locals[static_cast<std::size_t>(i - 1)] = interp.parameters()[i];
  return run;
}

std::string refusal(const std::string& program, const ToolTable* tools = nullptr) {
  gcode::Parameters zero;
  try {
    interpret(program, tools, &zero);
  } catch (const LoadError& e) {
    return e.what();
  }
  return "accepted";
}

const std::string kStart = "G21 G90 G54\nG0 X0 Y0 Z0 B0 C0\n";

TEST(Interpreter, LinesInMillimetresInchesAbsoluteAndIncremental) {
  gcode::Parameters var;
  const Interpreted r = interpret(kStart + "G1 X10 Y-5 F100\nG91 X1 Y1\nG90 G20 X1\n", nullptr, &var);
  ASSERT_EQ(r.moves.size(), 4u);
  EXPECT_EQ(r.moves[1].kind, MoveKind::Line);
  EXPECT_DOUBLE_EQ(r.moves[1].end[0], 10.0);
  EXPECT_DOUBLE_EQ(r.moves[2].end[0], 11.0);
  EXPECT_DOUBLE_EQ(r.moves[2].end[1], -4.0);
  EXPECT_DOUBLE_EQ(r.moves[3].end[0], 25.4);
  EXPECT_TRUE(r.effects[4].inches);
}

TEST(Interpreter, WorkOffsetsFromTheParameterFileAndG10) {
  gcode::Parameters var;
  var[5221] = 100;  // G54 X
  var[5243] = -20;  // G55 Z
  const Interpreted r =
      interpret(kStart + "G55 G0 X1 Z1\nG10 L2 P1 Y7\nG54 G1 Y0 F10\nG10 L20 P1 X0\nG0 X5\n", nullptr, &var);
  ASSERT_EQ(r.moves.size(), 4u);
  EXPECT_DOUBLE_EQ(r.moves[0].frame.world(r.moves[0].end)[0], 100.0);  // G54 X0
  EXPECT_DOUBLE_EQ(r.moves[1].frame.world(r.moves[1].end)[2], -19.0);  // G55 Z1
  EXPECT_DOUBLE_EQ(r.moves[2].frame.world(r.moves[2].end)[1], 7.0);    // G54 after G10 L2 Y7
  // G10 L20: the current X (world 1) becomes X0; X5 is then world 6.
  EXPECT_DOUBLE_EQ(r.moves[3].frame.world(r.moves[3].end)[0], 6.0);
}

TEST(Interpreter, ToolLengthKeepsTheMachineStillAndShiftsWorldZ) {
  ToolTable tools{{1, mill_tool(1, 100.0, 10.0)}};
  gcode::Parameters var;
  const Interpreted r = interpret(kStart + "G43 H1\nG1 X1 F100\nG1 Z0\n", &tools, &var);
  ASSERT_EQ(r.moves.size(), 3u);
  EXPECT_DOUBLE_EQ(r.moves[1].start[2], -100.0);  // program Z after G43: the tip, machine unmoved
  EXPECT_DOUBLE_EQ(r.moves[1].frame.world(r.moves[1].end)[2], 0.0);
  EXPECT_DOUBLE_EQ(r.moves[2].frame.world(r.moves[2].end)[2], 100.0);
  EXPECT_DOUBLE_EQ(r.moves[2].tool_offset_mm, 100.0);
}

TEST(Interpreter, MachineCoordinatesIgnoreWorkOffsets) {
  gcode::Parameters var;
  var[5221] = 100;
  const Interpreted r = interpret(kStart + "G53 G0 X-5\n", nullptr, &var);
  ASSERT_EQ(r.moves.size(), 2u);
  EXPECT_TRUE(r.moves[1].machine_coordinates);
  EXPECT_DOUBLE_EQ(r.moves[1].frame.world(r.moves[1].end)[0], -5.0);
}

TEST(Interpreter, ArcsInEveryPlaneWithCenterAndRadiusForms) {
  gcode::Parameters var;
  const Interpreted r = interpret(kStart +
                                      "G1 X10 F100\n"
                                      "G3 X0 Y10 I-10 J0\n"    // quarter turn CCW about the origin
                                      "G2 X10 Y0 R-10\n"       // R < 0: the long way round (270 deg)
                                      "G18 G2 X20 Z0 I5 K0\n"  // XZ plane
                                      "G19 G3 Y0 Z10 J-5 K5\n"
                                      "G17 G2 X20 Y0 I-5 J0 P3\n",  // three full turns
                                  nullptr, &var);
  ASSERT_EQ(r.moves.size(), 7u);
  EXPECT_NEAR(r.moves[2].arc.sweep_rad, M_PI / 2, 1e-12);
  EXPECT_NEAR(r.moves[3].arc.sweep_rad, -1.5 * M_PI, 1e-12);
  EXPECT_NEAR(r.moves[3].arc.center_first, 10.0, 1e-12);  // the long way round (0, 10) -> (10, 0)
  EXPECT_NEAR(r.moves[3].arc.center_second, 10.0, 1e-12);
  EXPECT_EQ(r.moves[4].arc.first, 2);  // G18: Z then X
  EXPECT_NEAR(r.moves[6].arc.sweep_rad, -6 * M_PI, 1e-12);
  const Position mid = point_at(r.moves[2], 0.5);
  EXPECT_NEAR(mid[0], 10 * std::cos(M_PI / 4), 1e-12);
  EXPECT_NEAR(mid[1], 10 * std::sin(M_PI / 4), 1e-12);
}

TEST(Interpreter, ParametersAndExpressions) {
  gcode::Parameters var;
  const Interpreted r = interpret(kStart + "#1 = 3\n#<depth> = [#1 * 2]\nG1 X#<depth> Y[#1 + 1] F100\n", nullptr, &var);
  ASSERT_EQ(r.moves.size(), 2u);
  EXPECT_DOUBLE_EQ(r.moves[1].end[0], 6.0);
  EXPECT_DOUBLE_EQ(r.moves[1].end[1], 4.0);
}

// LinuxCNC's read-only parameters, in program units (values as rs274 -g prints them; the
// acceptance corpus compares whole programs that print them, tests/acceptance).
TEST(Interpreter, StateParametersAsLinuxCncShowsThem) {
  gcode::Parameters var;
  const Interpreted r = interpret(kStart +
                                      "G20 G55 G91 G0 X1 Y2\n"
                                      "#1 = #<_x>\n#2 = #5421\n#3 = #<_coord_system>\n#4 = #<_imperial>\n"
                                      "#5 = #<_incremental>\n#6 = #<_motion_mode>\n#7 = EXISTS[#<_metric>]\n"
                                      "G1 X#1 F10\n",
                                  nullptr, &var);
  ASSERT_EQ(r.moves.size(), 3u);
  EXPECT_NEAR(r.locals[0], 1.0, 1e-12);  // inches
  EXPECT_NEAR(r.locals[1], 2.0, 1e-12);
  EXPECT_EQ(r.locals[2], 550);
  EXPECT_EQ(r.locals[3], 1);
  EXPECT_EQ(r.locals[4], 1);
  EXPECT_EQ(r.locals[5], 0);  // G0
  EXPECT_EQ(r.locals[6], 1);
  EXPECT_NEAR(r.moves[2].end[0], 2 * 25.4, 1e-9);  // G91: X1 more
}

TEST(Interpreter, RefusesWhatItCannotTranslateWithLineAndColumn) {
  EXPECT_EQ(refusal(kStart + "G41 D1 G1 X5\n").substr(0, 14), "test.ngc:3:1: ");
  EXPECT_NE(refusal(kStart + "G41 D1 G1 X5\n").find("pass --tool-table"), std::string::npos);
  EXPECT_NE(refusal(kStart + "G42 G1 X5\n").find("has not loaded one"), std::string::npos);
  EXPECT_NE(refusal(kStart + "G19 G41.1 D1\n").find("XY (G17) or XZ (G18) plane"), std::string::npos);
  EXPECT_NE(refusal(kStart + "G41.1 D1 F1 G1 X5\nG92 X0\n").find("test.ngc:4:1: error: cannot use G92 with cutter"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G1 F1 D1 X5\n").find("D word without G41"), std::string::npos);
  EXPECT_NE(refusal(kStart + "G41 D100000000000000000000 G1 X5\n").find("out of range"),
            std::string::npos);  // (the fuzzer's)
  EXPECT_NE(refusal(kStart + "G1 F10 G87 X1 Z-1 R1\n").find("test.ngc:3:8: error: G87: the back boring"),
            std::string::npos);
  EXPECT_NE(refusal(kStart + "G18 F10 G81 X1 Y-1 R1 @1\n").find("XY plane (G17) only"), std::string::npos);
  EXPECT_NE(refusal(kStart + "F10 G81 X1 Z-1\n").find("R (the retract plane) is missing"), std::string::npos);
  EXPECT_NE(refusal(kStart + "o100 sub\n").find("O-word"), std::string::npos);
  EXPECT_NE(refusal(kStart + "G92\n").find("needs at least one axis word"), std::string::npos);
  EXPECT_NE(refusal(kStart + "G43 H7\n", nullptr).find("tool table"), std::string::npos);
  const ToolTable tools{{1, mill_tool(1, 100.0, 10.0)}};
  EXPECT_NE(refusal(kStart + "G43 H7\n", &tools).find("test.ngc:3:5: error: tool 7 is not in the tool table"),
            std::string::npos);
  ToolTable lathe_tool{{2, mill_tool(2, 10.0, 4.0)}};
  lathe_tool[2].offset[0] = 1.5;  // an X offset, which G43 would apply too
  EXPECT_NE(refusal(kStart + "T2 M6 G43\n", &lathe_tool).find("tool 2 has an offset in X in the tool table"),
            std::string::npos);
  EXPECT_NE(refusal("G1 X1 Y1 F100\n").find("unknown position"), std::string::npos);
  EXPECT_NE(refusal(kStart + "G1 A5 F100\n").find("no A axis"), std::string::npos);
  EXPECT_NE(refusal(kStart + "G2 X1 Y1 I0.2 J0.1\n").find("radius to end of arc differs"), std::string::npos);
  EXPECT_NE(refusal(kStart + "G1 X[1/0]\n").find("test.ngc:3:"), std::string::npos);
}

// A cycle block writes out every move it makes: one that would make millions (a retract plane
// 1e11 mm up, pecks of 0.07 mm: the fuzzer's, which ran out of memory; a million holes) is refused
// at its line and column, as is a Q the heights cannot step by. A deep real hole is not.
TEST(Interpreter, RefusesCycleBlocksThatWouldMakeMillionsOfMoves) {
  const std::string drill = kStart + "G0 Z1\nS1500 M3\nF5\n";
  const std::string pecks = refusal(drill + "G98 G73 X0.5 Y0.5 Z-0.3 R111111111110.1 Q0.07\n");
  EXPECT_EQ(pecks.substr(0, 16), "test.ngc:6:5: er") << pecks;
  EXPECT_NE(pecks.find("G73: this block would make"), std::string::npos) << pecks;
  EXPECT_NE(pecks.find("more than 1000000 are refused"), std::string::npos) << pecks;
  const std::string holes = refusal(drill + "G99 G81 X1 Z-1 R0.5 L1000000\n");
  EXPECT_NE(holes.find("x L 1000000)"), std::string::npos) << holes;
  const std::string stuck = refusal(drill + "G98 G83 X1 Z99999999999999900 R100000000000000000 Q1\n");
  EXPECT_NE(stuck.find("below the resolution"), std::string::npos) << stuck;
  // 500 mm deep in pecks of 0.01 mm: 150,000 moves, written out.
  const gcode::Parameters zero;
  const Interpreted deep = interpret(drill + "G98 G83 X1 Z-500 R0.5 Q0.01\n", nullptr, &zero);
  EXPECT_GT(deep.moves.size(), 150'000u);
}

TEST(Interpreter, RefusesUnknownWorkOffsetsWithoutParameterFile) {
  interpreter::Setup setup;
  setup.file = "p.ngc";
  setup.machine_axes = kXyzbc;
  Interpreter interp(setup);
  gcode::Block block;
  Effect effect;
  gcode::parse_block("G0 X0 Y0 Z0 B0 C0", block);
  try {
    interp.execute(block, 1, effect);
    FAIL() << "accepted";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("work offset G54 is not known: pass --var"), std::string::npos) << e.what();
  }
}

// LinuxCNC 2.9's limits (interp_internal.hh): an R arc may fall 0.00127 mm short of the end
// point; an IJK arc's radii may differ by 0.0283 mm, or by more if that is under 0.1 % of
// the radius, never by 2.83 mm.
TEST(Interpreter, ArcToleranceIsLinuxCncs) {
  const std::string from = kStart + "G1 X0 Y0 F100\n";
  EXPECT_EQ(refusal(from + "G2 X10 Y0 R4.99875\n"), "accepted");
  EXPECT_NE(refusal(from + "G2 X10 Y0 R4.99870\n").find("radius too small"), std::string::npos);
  EXPECT_EQ(refusal(from + "G2 X10 Y0 I5.014 J0\n"), "accepted");  // radii differ by 0.028 mm (0.56 %)
  EXPECT_NE(refusal(from + "G2 X10 Y0 I5.0145 J0\n").find("differs"), std::string::npos);     // 0.029 mm
  EXPECT_EQ(refusal(from + "G2 X100 Y0 I50.0162 J0\n"), "accepted");                          // 0.0324 mm, 0.065 %
  EXPECT_NE(refusal(from + "G2 X10000 Y0 I5001.5 J0\n").find("differs"), std::string::npos);  // 3 mm, 0.06 %
  EXPECT_NE(refusal(from + "G2 X0.001 Y0 I0.0005 J0\n").find("zero radius"), std::string::npos);
  EXPECT_EQ(refusal(from + "G20 G2 X1 Y0 I0.5014 J0\n"), "accepted");  // 0.0028 in (0.0283 in G21 would refuse)
}

// After a tool change, LinuxCNC keeps the machine still through a G43 on the same line (as on
// the next): the tool length words go on a line of their own, where every interpreter agrees.
TEST(Interpreter, ToolLengthOnAToolChangeLineIsMarkedForALineOfItsOwn) {
  ToolTable tools{{1, mill_tool(1, 15.875, 6.0)}};
  gcode::Parameters var;
  const Interpreted r = interpret(kStart + "G0 Z50\nT1 M6 G43 H1\nG0 X10 Y10\nT1 M6 G43 H1 G0 X0\n", &tools, &var);
  const Effect& change = r.effects[3];
  ASSERT_EQ(change.after_tool_change_words.size(), 2u);  // G43, H1
  EXPECT_EQ(change.after_tool_change_words[0], 2);
  EXPECT_EQ(change.after_tool_change_words[1], 3);
  EXPECT_DOUBLE_EQ(r.moves[2].frame.world(r.moves[2].end)[2], 50.0);  // the machine stays at Z50
  EXPECT_TRUE(r.effects[5].after_tool_change_words.empty());          // a move on the line: no ambiguity
}

// G43.1's axis words are the tool's length, not a move.
TEST(Interpreter, DynamicToolLengthDoesNotMove) {
  gcode::Parameters var;
  const Interpreted r = interpret(kStart + "G43.1 Z10\nG0 X1\n", nullptr, &var);
  ASSERT_EQ(r.moves.size(), 2u);
  EXPECT_DOUBLE_EQ(r.moves[1].frame.world(r.moves[1].end)[2], 0.0);
  EXPECT_DOUBLE_EQ(r.moves[1].tool_offset_mm, 10.0);
}

// G92, G52 and G92.1-G92.3 keep the machine still and shift later moves (LinuxCNC's
// convert_axis_offsets); the offsets go before the rotation of the coordinate system.
TEST(Interpreter, AxisOffsetsShiftTheProgramAndKeepTheMachineStill) {
  gcode::Parameters var;
  const Interpreted r = interpret(kStart +
                                      "G0 X10 Y0\n"
                                      "G92 X0\n"  // here becomes X0: offset 10
                                      "G0 X5\n"   // world 15
                                      "G52 X2\n"  // offset 2: program X 13 here
                                      "G0 X5\n"   // world 7
                                      "G92.2\n"   // off, #5211 kept
                                      "G0 X5\n"   // world 5
                                      "G92.3\n"   // back on: offset 2
                                      "G0 X5\n"   // world 7
                                      "G92.1\n"   // off and zeroed
                                      "G0 X5\n",  // world 5
                                  nullptr, &var);
  ASSERT_EQ(r.moves.size(), 7u);
  const double expected[] = {15, 7, 5, 7, 5};
  for (int k = 0; k < 5; ++k)
    EXPECT_DOUBLE_EQ(
        r.moves[static_cast<std::size_t>(k + 2)].frame.world(r.moves[static_cast<std::size_t>(k + 2)].end)[0],
        expected[k])
        << k;
  EXPECT_DOUBLE_EQ(r.moves[3].start[0], 13.0);  // after G52 X2, at world 15
  gcode::Parameters rotated;
  rotated[5230] = 90;  // G54 turned 90 deg: the G92 offset turns with it
  const Interpreted q = interpret(kStart + "G0 X0 Y0\nG92 X-10\nG0 X0\n", nullptr, &rotated);
  const Position world = q.moves[2].frame.world(q.moves[2].end);
  EXPECT_NEAR(world[0], 0.0, 1e-12);
  EXPECT_NEAR(world[1], 10.0, 1e-12);
}

// A documented start position lets a program cut before it has set every axis.
TEST(Interpreter, StartPositionMakesTheFirstCutKnown) {
  gcode::Parameters var;
  var[5221] = 100;
  interpreter::Setup setup;
  setup.file = "test.ngc";
  setup.machine_axes = 0b111;
  setup.var_file = &var;
  setup.start_world = Position{0, 0, 250, 0, 0, 0};
  Interpreter interp(setup);
  gcode::Block block;
  Effect effect;
  gcode::parse_block("G1 X110 F100", block);
  interp.execute(block, 1, effect);
  ASSERT_EQ(effect.moves.size(), 1u);
  EXPECT_DOUBLE_EQ(effect.moves[0].start[0], -100.0);  // world 0 in G54 (X offset 100)
  EXPECT_DOUBLE_EQ(effect.moves[0].start[2], 250.0);
}

// G10 L1 changes a tool's length in the table; the next G43 takes it (checked against rs274).
TEST(Interpreter, ToolTableChangesTakeEffectAtTheNextG43) {
  ToolTable tools{{1, mill_tool(1, 12.7, 6.35)}};
  gcode::Parameters var;
  const Interpreted r = interpret(kStart + "G43 H1\nG0 X1\nG10 L1 P1 Z20\nG0 X2\nG43 H1\nG0 X3\n", &tools, &var);
  ASSERT_EQ(r.moves.size(), 4u);
  EXPECT_DOUBLE_EQ(r.moves[1].tool_offset_mm, 12.7);
  EXPECT_DOUBLE_EQ(r.moves[2].tool_offset_mm, 12.7);  // not before the G43
  EXPECT_DOUBLE_EQ(r.moves[3].tool_offset_mm, 20.0);
  EXPECT_DOUBLE_EQ(tools.at(1).z_offset(), 12.7);  // the caller's table is not changed
  EXPECT_NE(refusal(kStart + "G10 L1 P7 Z1\n", &tools).find("tool 7 is not in the tool table"), std::string::npos);
}

// A LinuxCNC set up in inches ([TRAJ]LINEAR_UNITS = inch): the .var file, the tool table and the
// parameters that hold their lengths are in inches; #1..#10 at the end of the program.
std::array<double, 10> run_on_inch_machine(const std::string& program, const ToolTable& tools,
                                           const gcode::Parameters& var, std::vector<Move>* moves = nullptr) {
  const Interpreted run = interpret(program, &tools, &var, kXyzbc, 25.4);
  if (moves) *moves = run.moves;
  return run.locals;
}

TEST(Interpreter, OnAnInchMachineTheParameterFileAndToolTableAreInInches) {
  gcode::Parameters var;
  var[5221] = 1.0;                                      // G54 X, inches
  var[5163] = 2.0;                                      // G28 Z, inches
  const ToolTable tools{{1, mill_tool(1, 50.8, 6.0)}};  // read from a file in inches: 2 in
  std::vector<Move> moves;
  const auto locals = run_on_inch_machine(
      "G21 G90 G54\nG0 X0 Y0 Z0 B0 C0\n#1 = #5221\nG10 L2 P1 X2.54\n#2 = #5221\nT1 M6 G43\nG0 X0\nG28 Z10\n", tools,
      var, &moves);
  EXPECT_DOUBLE_EQ(moves.at(0).frame.world(moves[0].end)[0], 25.4);  // G54 X0 is 1 in
  EXPECT_DOUBLE_EQ(locals[0], 1.0);                                  // the program reads inches
  EXPECT_NEAR(locals[1], 0.1, 1e-15);                                // G10 L2 writes them
  EXPECT_DOUBLE_EQ(moves.at(1).frame.world(moves[1].end)[0], 2.54);
  EXPECT_DOUBLE_EQ(moves[1].tool_offset_mm, 50.8);
  EXPECT_THROW(run_on_inch_machine("G21 G90\n#1 = #5403\n", tools, var), LoadError);  // no M6 yet
}

// #5400-#5413 after M6: the spindle's tool table entry, as it is now, in machine units (numbers
// from rs274 -g on the same program and table).
TEST(Interpreter, ToolDataParametersReadTheSpindlesToolAfterM6) {
  gcode::Parameters var;
  ToolTable tools{{1, mill_tool(1, 11.0, 1.1)}, {2, mill_tool(2, 12.0, 1.2)}};
  tools[2].front_angle = 30;
  tools[2].orientation = 2;
  const auto locals = run_on_inch_machine(
      "G20 G90\nT1 M6\n#1 = #5400\n#2 = #5403\n#3 = #5410\nG10 L1 P1 Z1\n#4 = #5403\nG10 L1 P2 Z3\n#5 = #5403\n"
      "T2 M6\n#6 = #5411\n#7 = #5413\n#8 = #5401\n",
      tools, var);
  EXPECT_DOUBLE_EQ(locals[0], 1.0);
  EXPECT_NEAR(locals[1], 0.433071, 1e-6);
  EXPECT_NEAR(locals[2], 0.043307, 1e-6);
  EXPECT_DOUBLE_EQ(locals[3], 1.0);  // G10 L1 on the loaded tool changes it at once
  EXPECT_DOUBLE_EQ(locals[4], 1.0);  // on another tool, not
  EXPECT_DOUBLE_EQ(locals[5], 30.0);
  EXPECT_DOUBLE_EQ(locals[6], 2.0);
  EXPECT_DOUBLE_EQ(locals[7], 0.0);
  // After M61 LinuxCNC's answer depends on when the task resynchronises the interpreter.
  EXPECT_THROW(run_on_inch_machine("G20\nT1 M6\nM61 Q2\n#1 = #5403\n", tools, var), LoadError);
}

// G10 L10 and L11, against the values LinuxCNC's own regression tests state (tests/interp/g10,
// g10-l1-l10 and g10-l11: "should be ...").
TEST(Interpreter, G10L10AndL11SetToolOffsetsSoThatThePositionReadsTheValuesGiven) {
  gcode::Parameters var;
  const ToolTable tools{{1, mill_tool(1, 0.0, 0.0)}};
  auto l10 = run_on_inch_machine(
      "G20 G90 G54\nG10 L1 P1 X0 Y0 Z0\nT1 M6 G43\nG0 X.1 Y.2 Z.3 B0 C0\n"
      "G10 L10 P1 X1\n#1 = #5401\nG10 L10 P1 Y2\n#2 = #5402\nG10 L10 P1 Z3\n#3 = #5403\n",
      tools, var);
  EXPECT_NEAR(l10[0], -0.9, 1e-12);
  EXPECT_NEAR(l10[1], -1.8, 1e-12);
  EXPECT_NEAR(l10[2], -2.7, 1e-12);
  // In a system rotated by 45 deg, X alone keeps the offset's component along the system's Y.
  l10 = run_on_inch_machine(
      "G20 G90 G54\nG10 L2 P1 R45\nG0 X0 Y0 Z0 B0 C0\nG10 L10 P1 X0 Y0 Z0\nT1 M6 G43\n"
      "G10 L10 P1 X1\n#1 = #5401\n#2 = #5402\nG10 L10 P1 Y1\n#3 = #5401\n#4 = #5402\n",
      tools, var);
  EXPECT_NEAR(l10[0], -0.70710678, 1e-8);
  EXPECT_NEAR(l10[1], -0.70710678, 1e-8);
  EXPECT_NEAR(l10[2], 0.0, 1e-12);
  EXPECT_NEAR(l10[3], -1.41421356, 1e-8);
  // L11: in G59.3's coordinates, without G92 (a touch-off fixture).
  const auto l11 = run_on_inch_machine(
      "G20 G90\nG10 L2 P1 X1 Y2 Z-3 R10\nG10 L2 P2 X4 Y5 Z-6 R20\nG10 L2 P9 X25 Y26 Z-27 R0\nG54\n"
      "G0 G53 X0 Y0 Z-30 B0 C0\nG10 L11 P1 Z0\nT1 M6\n#1 = #5403\nG55\nG0 G53 Z-30\nG10 L11 P1 Z1\n#2 = #5403\n"
      "G92 X33 Y44 Z55\nG54\nG0 G53 Z-30\nG10 L11 P1 Z0\n#3 = #5403\n",
      tools, var);
  EXPECT_NEAR(l11[0], -3.0, 1e-12);
  EXPECT_NEAR(l11[1], -4.0, 1e-12);
  EXPECT_NEAR(l11[2], -3.0, 1e-12);
}

}  // namespace
}  // namespace vc::interpreter
