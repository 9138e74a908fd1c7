// What volcomp predistort says about its corrections (issue 36): the tool lengths L the moves
// were corrected for and where each came from; the warning for moves without G43, whose
// figure is computed here independently from the machine library (the volumetric errors at
// the program's poses for the likely tool's L and for the L corrected for); and the axis,
// position and grid end of corrected points outside an error table's grid. Run as a user runs
// it, on the MC-300 (its angular errors leave ~20 um at the tip of a 100 mm tool).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc {
namespace {

const std::string kMc300 = test::machine_path("mc300");
const std::string kTools = test::source_path("kins/configs/mc300/mc300.tbl");  // T1: Z100
// Inside every grid, so that the start of the first move is not a point outside one.
const std::string kStart = " --start=-300,-160,-200,0,0";

std::string write_program(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("correction_notes_" + name);
  std::ofstream(path) << text;
  return path.string();
}

test::CommandResult predistort(const std::string& program, const std::string& options = "") {
  const std::string out = (std::filesystem::temp_directory_path() / "correction_notes_out.ngc").string();
  return test::run_volcomp("predistort " + kMc300 + " " + program + " -o " + out + " --tool-table " + kTools + kStart +
                           options);
}

// Poses (X Y Z B C, mm and deg: world = program with G54 at zero and no G43) the program
// below visits with rapids (the pre-distorter corrects rapids at their ends only).
const std::vector<std::array<double, 5>> kPoses = {{-300, -160, -200, 0, 0},     {-150, -80, -180, -60, 135},
                                                   {-450, -240, -300, -90, 10},  {-420, -100, -150, 0, 270},
                                                   {-200, -280, -250, -110, 45}, {-300, -160, -200, -45, 180}};

std::string move_line(const std::array<double, 5>& p, double z_offset = 0.0) {
  char text[128];
  std::snprintf(text, sizeof text, "G0 X%g Y%g Z%g B%g C%g\n", p[0], p[1], p[2] - z_offset, p[3], p[4]);
  return text;
}

// Lines 1-3 set up, 4..(3 + poses) move without G43; with `then_g43`, G43 H1 follows and the
// same poses again with the tool's offset in Z (the machine goes to the same joints).
std::string program_text(bool then_g43) {
  std::string text = "G21 G90 G17 G40 G49 G94\nG10 L2 P1 X0 Y0 Z0 B0 C0\nT1 M6 G54\n";
  for (const auto& p : kPoses) text += move_line(p);
  if (then_g43) {
    text += "G43 H1\n";
    for (const auto& p : kPoses) text += move_line(p, 100.0);
  }
  return text + "M2\n";
}

// The largest tool-tip error a 100 mm tool keeps where the machine was corrected for L = 0, at
// the program's poses, in um, from the model's rule rather than the pre-distorter's path: with
// the orientation corrected (the tool more than 10 deg off the C axis: pole_fade_deg) the tool
// points right and its tip is right at any L; at B = 0 (the tool along C, the pole) only the
// position is corrected (the fade), so the tip keeps the direction error times 100 mm: the
// volumetric error for L = 100 less the one for L = 0.
double expected_error_um(std::vector<int>* worst_lines) {
  const machine::Model model = machine::load_machine(kMc300);
  double worst = 0.0;
  for (std::size_t k = 0; k < kPoses.size(); ++k) {
    const auto& p = kPoses[k];
    if (p[3] != 0.0) continue;  // ~0 there (second order in the corrections)
    machine::Joints q(5);
    q << p[0], p[1], p[2], p[3], p[4];
    const Eigen::Vector3d left =
        machine::volumetric_error(model, q, 100.0).position_mm - machine::volumetric_error(model, q, 0.0).position_mm;
    worst = std::max(worst, left.norm() * 1e3);
    worst_lines->push_back(4 + static_cast<int>(k));
  }
  return worst;
}

double number_after(const std::string& text, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(text, m, std::regex(pattern))) return NAN;
  return std::stod(m[1].str());
}

TEST(CorrectionNotes, NamesTheToolLengthOfEveryStretchAndWhereItCameFrom) {
  const auto r = predistort(write_program("mixed.ngc", program_text(true)));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const int last_without = 3 + static_cast<int>(kPoses.size()), first_with = last_without + 2;
  const int last_with = first_with + static_cast<int>(kPoses.size()) - 1;
  EXPECT_NE(r.out.find("tool lengths: L = 0 mm (no G43: the spindle gauge point) for lines 4-" +
                       std::to_string(last_without) +
                       "; L = 100 mm (reference 0 mm + G43 offset of tool 1 from mc300.tbl) for lines " +
                       std::to_string(first_with) + "-" + std::to_string(last_with) + "\n"),
            std::string::npos)
      << r.out;
}

TEST(CorrectionNotes, WarnsOfMovesWithoutG43WithTheErrorTheToolKeeps) {
  const std::string program = write_program("no_g43.ngc", program_text(false));
  const auto r = predistort(program);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("warning: line 4 moves without G43 (no tool length offset in force): corrected for L = 0 mm "
                       "(the spindle gauge point); with tool 1 (100 mm, mc300.tbl) in the spindle the angular errors "
                       "would leave up to "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("Add G43 H1 after the tool change, or set tool_length_reference_mm."), std::string::npos)
      << r.out;
  const double printed = number_after(r.out, "would leave up to ([0-9.]+) um at the tip");
  std::vector<int> pole_lines;
  const double expected = expected_error_um(&pole_lines);
  ASSERT_GT(expected, 5.0);  // a figure that matters, else the test proves nothing
  // The pre-distorter runs the correction for L = 0 and measures the 100 mm tool's tip; the
  // difference of the volumetric errors is the same to first order in the corrections (um).
  EXPECT_NEAR(printed, expected, 0.1 + 0.01 * expected) << r.out;
  const int worst_line = static_cast<int>(number_after(r.out, "um at the tip \\(at line ([0-9]+)\\)"));
  EXPECT_NE(std::find(pole_lines.begin(), pole_lines.end(), worst_line), pole_lines.end()) << r.out;

  // Within the tolerance (0.1 mm = 100 um here) the program is as the user meant: no warning,
  // but the tool length is still said.
  const auto loose = predistort(program, " --tolerance 0.1");
  ASSERT_EQ(loose.exit_code, 0) << loose.out;
  EXPECT_EQ(loose.out.find("without G43"), std::string::npos) << loose.out;
  EXPECT_NE(loose.out.find("tool lengths: L = 0 mm (no G43: the spindle gauge point)"), std::string::npos) << loose.out;
}

TEST(CorrectionNotes, NoWarningWhenEveryMoveHasG43) {
  std::string text = "G21 G90 G17 G40 G49 G94\nG10 L2 P1 X0 Y0 Z0 B0 C0\nT1 M6 G54\nG43 H1\n";
  for (const auto& p : kPoses) text += move_line(p, 100.0);
  const auto r = predistort(write_program("g43.ngc", text + "M2\n"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out.find("without G43"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tool lengths: L = 100 mm (reference 0 mm + G43 offset of tool 1 from mc300.tbl) for lines 5-" +
                       std::to_string(4 + kPoses.size()) + "\n"),
            std::string::npos)
      << r.out;
}

TEST(CorrectionNotes, PointsOutsideAGridNameTheAxisThePositionAndTheGridsEnd) {
  // The Z grid's lower end, from the table the machine file binds to Z.
  const machine::Model model = machine::load_machine(kMc300);
  const int z = model.joint_of('Z');
  double z_end = NAN;
  for (const machine::BoundTable& t : model.tables)
    if (std::filesystem::path(t.table.path()).filename() == "z.csv" && t.joint[0] == z) z_end = t.table.grid()[0].first;
  ASSERT_FALSE(std::isnan(z_end));
  ASSERT_EQ(z_end, std::round(z_end));           // printed as a whole number below
  const double commanded = z_end - 4.0 - 100.0;  // G43 H1 adds 100 mm: the joint 4 mm below the grid, once
  char dip[96];
  std::snprintf(dip, sizeof dip, "G0 Z%g\nG0 Z-200\n", commanded);
  const std::string text =
      "G21 G90 G17 G40 G49 G94\nG10 L2 P1 X0 Y0 Z0 B0 C0\nT1 M6 G54 G43 H1\nG0 X-300 Y-160 Z-300\n" + std::string(dip) +
      "M2\n";
  const auto r = predistort(write_program("outside.ngc", text));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  // The joint goes to commanded + 100 (plus its correction, a few um).
  const std::regex line("warning: line 5: Z = (-?[0-9.]+) mm is ([0-9.]+) mm beyond the end of z\\.csv's grid \\(" +
                        std::to_string(static_cast<int>(z_end)) +
                        " mm\\): the correction there holds the table's end value \\(1 point outside Z's grids\\)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, line)) << r.out;
  const double position = std::stod(m[1].str()), beyond = std::stod(m[2].str());
  EXPECT_NEAR(position, commanded + 100.0, 0.1);
  EXPECT_NEAR(beyond, z_end - position, 0.0011);
  EXPECT_EQ(r.out.find("Y's grids"), std::string::npos) << r.out;  // only Z left its grids
}

// A part cut with a 100 mm tool and no G43, touched off in G54 (Z 100 mm higher): selftune
// simulates the gauge point's path, 100 mm above the cut, and refuses the report; the refusal
// names the L it used, the tool likely used, and the causes it tested and ruled out.
TEST(CorrectionNotes, SelftuneRefusalNamesTheToolLengthUsed) {
  const std::string mill3 = test::machine_path("mill3"), tools = test::source_path("tests/programs/mill3.tbl");
  const std::string with_g43 = test::source_path("tests/programs/selftune/part_a.ngc");
  const std::string tmp = std::filesystem::temp_directory_path().string() + "/correction_notes_";
  // The part as cut (with G43), measured by the virtual shop.
  const std::string files = " --tool-table " + tools + " --var " + test::source_path("tests/programs/mill3.var");
  ASSERT_EQ(test::run_volcomp("simulate " + mill3 + " " + with_g43 + " -o " + tmp + "path.csv" + files).exit_code, 0);
  ASSERT_EQ(
      test::run_volcomp("measure " + tmp + "path.csv " +
                        test::source_path("tests/programs/selftune/part_a_points.csv") + " -o " + tmp + "report.csv")
          .exit_code,
      0);
  // The same program without G43, and G54 Z raised by the tool's length (a touch-off).
  std::ifstream in(with_g43);
  std::string text, line, tool_length;
  int first_move = 0, number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line == "G0 G43 H1 Z50.")
      line = "G0 Z50.";
    else if (!first_move && line.rfind("G0 X", 0) == 0)
      first_move = number;
    text += line + "\n";
  }
  ASSERT_GT(first_move, 0);
  const std::string program = write_program("part_a_no_g43.ngc", text);
  std::ifstream var_in(test::source_path("tests/programs/mill3.var"));
  std::ofstream var_out(tmp + "touch.var");
  while (std::getline(var_in, line)) {
    if (line.rfind("5223", 0) == 0) line = "5223\t" + std::to_string(std::stod(line.substr(5)) + 100.0);
    var_out << line << "\n";
  }
  var_out.close();
  std::ifstream table(tools);
  std::smatch m;
  const std::string table_text((std::istreambuf_iterator<char>(table)), std::istreambuf_iterator<char>());
  ASSERT_TRUE(std::regex_search(table_text, m, std::regex("T1 P1 Z([0-9.]+)")));
  const auto r = test::run_volcomp("selftune " + mill3 + " " + program + " " + tmp + "report.csv -o " + tmp +
                                   "next.ngc --tool-table " + tools + " --var " + tmp + "touch.var");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("outside the region the program cuts"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tested and not the cause: the program cuts"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("corrected for L = 0 mm (no G43 in " + program + " from line " + std::to_string(first_move) +
                       "); if the part was cut with a " + m[1].str() +
                       " mm tool (tool 1 in the tool table), add G43 H1 or set tool_length_reference_mm"),
            std::string::npos)
      << r.out;
}

}  // namespace
}  // namespace vc
