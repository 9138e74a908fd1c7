// Lathe cycles G70-G72: a roughing cycle worked out by hand, the profile's lines read and not
// run, and LinuxCNC's refusals. The full behaviour (fillets, chamfers, arcs, pockets, G72's
// turned profile, the .1/.2 variants, inches) is checked against LinuxCNC's own interpreter in
// the acceptance corpus (tests/acceptance/corpus/own/lathe_cycles_*.ngc and LinuxCNC's samples).
#include <gtest/gtest.h>

#include <sstream>

#include "program_reader.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::interpreter {
namespace {

using Line = test::LineMoves;

std::vector<Line> run(const std::string& program) { return test::run_lines(program, "lathe.ngc"); }

std::string refusal(const std::string& program) {
  try {
    run(program);
  } catch (const LoadError& e) {
    return e.what();
  }
  return "not refused";
}

const char* const kProfile =
    "O1 SUB\n"
    "G1 X2 Z0 F999\n"  // F (and anything but the motion) is not run in a profile
    "G1 Z-10\n"
    "G1 X10\n"
    "O1 ENDSUB\n";

TEST(LatheCycles, TurningByHand) {
  // From X10 Z1, a step profile: 2 mm deep cuts (I2) along Z down to the profile, each
  // escaping diagonally by R0.5 and coming back in rapids, then the finished contour.
  const std::vector<Line> lines = run(std::string("G18 G21 G90 G54\nG0 X20 Y0 Z5\nF100\n") + kProfile +
                                      "G71 Q1 X10 Z1 D0 I2 R0.5\n"
                                      "G1 X12\n"
                                      "M2\n");
  ASSERT_GE(lines.size(), 5u);
  const Line& cycle = lines[3];
  EXPECT_EQ(cycle.number, 9);
  struct Expected {
    MoveKind kind;
    double x, z;
  };
  const MoveKind G0 = MoveKind::Rapid, G1 = MoveKind::Line;
  std::vector<Expected> expected = {{G0, 10, 1}};  // to the cycle's X Z
  expected.push_back({G0, 10, 1});                 // to the profile's start
  const double dive_z[] = {1, 0.75, 0.5, 0.25};    // the approach line crosses X10 X8 X6 X4 here
  for (int k = 0; k < 4; ++k) {
    const double x = 10 - 2 * k, z = dive_z[k];
    expected.push_back({G0, x, z});              // down the approach to this depth
    expected.push_back({G1, x, -10});            // the cut, to the shoulder
    expected.push_back({G0, x + 0.5, -9.5});     // escape
    expected.push_back({G0, x + 0.5, z - 0.5});  // back
    expected.push_back({G0, x, z});              // and down again
  }
  expected.push_back({G0, 2, 0});    // the last depth reaches the profile
  expected.push_back({G1, 2, -10});  // along it
  expected.push_back({G1, 10, -10});
  ASSERT_EQ(cycle.moves.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(cycle.moves[i].kind, expected[i].kind);
    EXPECT_NEAR(cycle.moves[i].end[0], expected[i].x, 1e-12);
    EXPECT_NEAR(cycle.moves[i].end[2], expected[i].z, 1e-12);
    EXPECT_EQ(cycle.moves[i].feed, 100.0);  // the program's feed, not the profile's
  }
  // After the cycle the tool is at the profile's end; the next move starts there, as a G1.
  const Line& after = lines[4];
  ASSERT_EQ(after.moves.size(), 1u);
  EXPECT_EQ(after.moves[0].kind, MoveKind::Line);
  EXPECT_NEAR(after.moves[0].start[2], -10, 1e-12);
  EXPECT_NEAR(after.moves[0].end[0], 12, 1e-12);
}

TEST(LatheCycles, RefusesWhatLinuxCncRefusesWithTheLine) {
  const std::string setup = std::string("G18 G21 G90 G54\nG0 X20 Y0 Z5\nF100\n") + kProfile;
  EXPECT_NE(refusal(setup + "G71 X10 Z1 D0 I2\nM2\n").find("lathe.ngc:9:1: error: G71: G7x.x requires a Q word"),
            std::string::npos);
  EXPECT_NE(refusal("G17 G21 G90 G54\nG0 X20 Y0 Z5\nF100\n" + std::string(kProfile) + "G71 Q1 X10 Z1\nM2\n")
                .find("lathe.ngc:9:1: error: G71: LinuxCNC runs the lathe cycles in the XZ plane (G18) only"),
            std::string::npos);
  EXPECT_NE(
      refusal(setup + "G71 Q1 X10 Z1 I0\nM2\n").find("lathe.ngc:9:15: error: G7X error: I must be greater than zero"),
      std::string::npos);
  EXPECT_NE(refusal(setup + "G41.1 D1\nG71 Q1 X10 Z1\nM2\n")
                .find("lathe.ngc:10:1: error: G71: LinuxCNC refuses this cycle with cutter compensation on"),
            std::string::npos);
  EXPECT_NE(refusal(setup + "G91 G71 Q1 X10 Z1\nM2\n").find("error: G71: in incremental mode (G91)"),
            std::string::npos);
  EXPECT_NE(refusal(setup + "G72 Q7 X10 Z1\nM2\n").find("subroutine o7 (the profile of this lathe cycle)"),
            std::string::npos);
  // A profile LinuxCNC cannot cut, with its reason, at the cycle's line.
  EXPECT_NE(refusal("G18 G21 G90 G54\nG0 X20 Y0 Z5\nF100\nO2 SUB\nG1 X2 Z0\nG1 Z-10\nG1 X4 Z-8\nG1 X10\nO2 ENDSUB\n"
                    "G71 Q2 X10 Z1\nM2\n")
                .find("lathe.ngc:10:1: error: G71: G7X error: Not monotonic"),
            std::string::npos);
  EXPECT_NE(refusal(setup + "G0 X10 Z1\nO3 SUB\nG1 X2 Z0 A1 C1\nG1 Z-10\nO3 ENDSUB\nG71 Q3\nM2\n")
                .find("lathe.ngc:11:10: error: G7X error: Both A and C parameters on a corner"),
            std::string::npos);
  // A profile on which LinuxCNC loops forever (rs274 never returns): refused, and quickly.
  EXPECT_NE(refusal("G20 G18 G90 G54\nG0 X2 Y0 Z2\nF10\nO420 SUB\nG0 X0.2 Z0\nG1 X0.5\nZ-0.1\nX0.6 Z-0.25\nX0.8\n"
                    "Z-0.05\nX1.2\nO420 ENDSUB\nG0 X1.3 Z0.1\nG72.2 Q420 X1.3 Z0.1 D0.004 I0.03 R0.01\nM2\n")
                .find("lathe.ngc:14:1: error: G72.2: G7X error: more than 200000 moves"),
            std::string::npos);
}

}  // namespace
}  // namespace vc::interpreter
