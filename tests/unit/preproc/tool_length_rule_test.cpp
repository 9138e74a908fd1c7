// The tool-length rule (L = the machine file's tool_length_reference_mm + LinuxCNC's tool
// length offset): the same physical tool, set up in each of the three shop practices, gets the
// same pre-distorted motion; the rule's L is the one the core's correction is computed for.
#include <gtest/gtest.h>

#include <regex>
#include <sstream>

#include "test_support.hpp"
#include "vc/interpreter/linuxcnc_files.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/predistort.hpp"

namespace vc::predistort {
namespace {

// A 100 mm tool (gauge point to tip) cutting a slanted line on mill3, in one practice.
struct Practice {
  double reference_mm;            // the machine file's tool_length_reference_mm
  std::optional<double> table_z;  // T1's length in the tool table (none: no tool table)
  bool g43;                       // the program uses G43 H1
  double g54_z;                   // the work offset Z the operator set (touch-off)
};

// The motion lines of the pre-distorted program (lines with an X word), in order.
std::vector<std::string> motion(const Practice& p) {
  machine::Model model = machine::load_machine(test::machine_path("mill3"));
  model.tool_length_reference_mm = p.reference_mm;
  interpreter::ToolTable tools;
  if (p.table_z) tools[1] = interpreter::mill_tool(1, *p.table_z, 10.0);
  gcode::Parameters parameters;
  interpreter::read_var_file(test::source_path("tests/programs/mill3.var"), parameters);
  parameters[5223] = p.g54_z;
  Job job;
  job.model = &model;
  job.setup.file = "practice.ngc";
  job.setup.machine_axes = program_axes(model);
  job.setup.tools = p.table_z ? &tools : nullptr;
  job.setup.var_file = &parameters;
  std::istringstream in(std::string("G21 G90 G54 G17\nT1 M6\n") + (p.g43 ? "G43 H1\n" : "") +
                        "G0 X-200 Y-120 Z10\nG1 Z-5 F500\nG1 X180 Y110 Z-12\nG2 X200 Y90 R20\nG0 Z50\nM2\n");
  std::ostringstream out;
  predistort(in, out, job);
  std::vector<std::string> lines;
  std::istringstream written(out.str());
  for (std::string line; std::getline(written, line);)
    if (line.find('X') != std::string::npos && line[0] != '(') lines.push_back(line);
  return lines;
}

TEST(ToolLengthRule, TheThreePracticesGiveTheSameMotion) {
  // The world Z of a program point is Z + G54 Z + offset: each practice touches off so that
  // the same program point is the same machine position.
  const Practice gauge{0.0, 100.0, true, -340.0};                // tool table: gauge lengths
  const Practice relative{100.0, 0.0, true, -240.0};             // reference tool (100 mm) at 0: this tool is it
  const Practice touch_off{100.0, std::nullopt, false, -240.0};  // no tool table, no G43
  const std::vector<std::string> a = motion(gauge);
  ASSERT_GE(a.size(), 5u);
  EXPECT_EQ(motion(relative), a);
  EXPECT_EQ(motion(touch_off), a);
  // Without the rule's reference, the touch-off program would be corrected at the spindle
  // nose (L = 0): another motion, by the angular errors times 100 mm.
  EXPECT_NE(motion({0.0, std::nullopt, false, -240.0}), a);
}

TEST(ToolLengthRule, LIsTheReferencePlusTheOffset) {
  machine::Model model = machine::load_machine(test::machine_path("mill3"));
  EXPECT_EQ(model.tool_length_reference_mm, 0.0);  // shipped files: gauge lengths in the table
  model.tool_length_reference_mm = 80.0;
  EXPECT_DOUBLE_EQ(model.correction_length(25.0), 105.0);
  EXPECT_DOUBLE_EQ(model.correction_length(0.0), 80.0);
}

}  // namespace
}  // namespace vc::predistort
