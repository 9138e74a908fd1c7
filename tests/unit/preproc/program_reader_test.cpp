// The order in which LinuxCNC executes a program's lines (O-word control flow, M98/M99) and
// the flat text each executed line gets. What the flat program means is checked against
// LinuxCNC's own interpreter in the acceptance corpus (tests/acceptance); here, the rules.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "linuxcnc_run.hpp"
#include "vc/interpreter/program_reader.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::interpreter {
namespace {

struct Executed {
  std::vector<int> lines;          // origin lines, in execution order
  std::vector<std::string> texts;  // the flat text of each
  std::vector<std::string> files;
};

Executed run(const std::string& program, std::vector<std::string> path = {}) {
  gcode::Parameters var;
  Setup setup;
  setup.file = "test.ngc";
  setup.machine_axes = 0b111;
  setup.var_file = &var;
  Interpreter interpreter(setup);
  std::istringstream in(program);
  ProgramReader reader(in, "test.ngc", interpreter, std::move(path));
  Executed e;
  std::string raw;
  Origin origin;
  gcode::Block block;
  Effect effect;
  while (reader.next(raw, origin, block, effect)) {
    e.lines.push_back(origin.line);
    e.texts.push_back(raw);
    e.files.push_back(reader.files()[static_cast<std::size_t>(origin.file)]);
  }
  return e;
}

std::string refusal(const std::string& program) {
  try {
    run(program);
  } catch (const LoadError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ProgramReader, SubroutineArgumentsLocalsAndReturnValue) {
  const Executed e =
      run("o<twice> sub\n"              // 1
          "#<half> = #1\n"              // 2: a local: dropped from the flat program
          "G0 X[#<half> * 2] Y#2\n"     // 3
          "o<twice> return [#1 + 1]\n"  // 4
          "o<twice> endsub\n"           // 5
          "#1 = 7\n"                    // 6
          "o<twice> call [5] [3]\n"     // 7
          "G0 X#<_value> Y#1\n"         // 8: the caller's #1 is back
          "M2\n");                      // 9
  EXPECT_EQ(e.lines, (std::vector<int>{6, 3, 8, 9}));
  EXPECT_EQ(e.texts[1], "G0 X10 Y3");
  EXPECT_EQ(e.texts[2], "G0 X6 Y7");  // reads the call's result: evaluated (the caller's #1 is back)
  EXPECT_EQ(e.texts[0], "#1 = 7");    // the main program's own lines keep their text
}

TEST(ProgramReader, LoopsAndConditionsRunAsLinuxCncRunsThem) {
  const Executed e =
      run("#1 = 0\n"                // 1
          "o10 while [#1 LT 4]\n"   // 2
          "#1 = [#1 + 1]\n"         // 3
          "o11 if [#1 EQ 2]\n"      // 4
          "o10 continue\n"          // 5
          "o11 elseif [#1 EQ 3]\n"  // 6
          "G0 X3\n"                 // 7
          "o11 else\n"              // 8
          "G0 X#1\n"                // 9
          "o11 endif\n"             // 10
          "o10 endwhile\n"          // 11
          "o20 repeat [2]\n"        // 12
          "G0 Y1\n"                 // 13
          "o20 endrepeat\n"         // 14
          "o30 do\n"                // 15
          "#1 = [#1 - 3]\n"         // 16
          "o30 while [#1 GT 0]\n"   // 17
          "M2\n");                  // 18
  // #1 = 1: X1 (else); 2: continue; 3: X3 (elseif); 4: X4 (else); then repeat twice; the do
  // loop runs while #1 - 3k > 0: twice (4 -> 1 -> -2).
  EXPECT_EQ(e.lines, (std::vector<int>{1, 3, 9, 3, 3, 7, 3, 9, 13, 13, 16, 16, 18}));
}

TEST(ProgramReader, BreakLeavesTheLoop) {
  const Executed e =
      run("#1 = 0\n"
          "o1 while [1]\n"
          "#1 = [#1 + 1]\n"
          "o2 if [#1 GE 3]\n"
          "o1 break\n"
          "o2 endif\n"
          "o1 endwhile\n"
          "G0 X#1\n"
          "M2\n");
  EXPECT_EQ(e.lines, (std::vector<int>{1, 3, 3, 3, 8, 9}));
}

TEST(ProgramReader, FanucSubprogramsWithRepeats) {
  const Executed e =
      run("G0 X0\n"         // 1
          "M98 P1000 L3\n"  // 2
          "G0 X1\n"         // 3
          "M30\n"           // 4
          "O1000\n"         // 5
          "G91 G0 Y1\n"     // 6
          "G90\n"           // 7
          "M99\n");         // 8
  EXPECT_EQ(e.lines, (std::vector<int>{1, 6, 7, 6, 7, 6, 7, 3, 4}));
}

TEST(ProgramReader, SubroutineFilesOnTheSubroutinePath) {
  const std::filesystem::path dir = test::run_folder("program_reader_subroutines");
  std::ofstream(dir / "probe_corner.ngc") << "o<probe_corner> sub\nG0 X#1 Y#2\no<probe_corner> endsub\n";
  const Executed e = run("G0 X0 Y0\no<probe_corner> call [4] [5]\nM2\n", {dir.string()});
  EXPECT_EQ(e.lines, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(e.texts[1], "G0 X4 Y5");
  EXPECT_EQ(e.files[1], (dir / "probe_corner.ngc").string());
}

TEST(ProgramReader, MessagesInACallAreExpandedAndTheLineNumberIsTheSources) {
  const Executed e = run("o1 sub\n(DEBUG, depth %.2f#1 at #<_line>)\no1 endsub\no1 call [2.5]\nM2\n");
  EXPECT_EQ(e.texts[0], "(DEBUG, depth 2.50 at 2.00)");
}

// A main-program line that reads the interpreter's state is written with its values; its
// assignments to the main program's own parameters stay in it (later lines read them), while a
// call's own are left out.
TEST(ProgramReader, MainProgramAssignmentsFromTheStateAreKept) {
  const Executed e =
      run("G0 X3 Y0 Z0\n#<home> = #<_x>\nG1 X#<home> F100\no1 sub\n#<own> = #<_x>\no1 endsub\no1 call\nM2\n");
  ASSERT_GE(e.texts.size(), 3u);
  EXPECT_EQ(e.texts[1], "#<home>=3");
  EXPECT_EQ(e.texts[2], "G1 X#<home> F100");
  for (const std::string& text : e.texts) EXPECT_EQ(text.find("own"), std::string::npos) << text;
}

// M70-M73: the state is restored by the G-code LinuxCNC writes for it (F with one decimal, the
// G and M codes that differ), run as lines of the flat program; M73's on the return.
TEST(ProgramReader, SavedModalStateIsRestoredByTheLinesLinuxCncRuns) {
  const Executed e =
      run("o<sub> sub\n"                                     // 1
          "M73\n"                                            // 2
          "G91 F5 M8\n"                                      // 3
          "o<sub> endsub\n"                                  // 4
          "G21 F100.04 S500 M3\n"                            // 5
          "M70 (save)\n"                                     // 6
          "F20 G91 M4\n"                                     // 7
          "M72\n"                                            // 8
          "o<sub> call\n"                                    // 9
          "M2\n");                                           // 10
  const std::vector<int> lines{5, 6, 7, 8, 8, 2, 3, 4, 10};  // (4: the restore after endsub)
  EXPECT_EQ(e.lines, lines);
  ASSERT_EQ(e.texts.size(), lines.size());
  EXPECT_EQ(e.texts[3], "M72");                     // (the writer leaves the word out: Effect::dropped_words)
  EXPECT_EQ(e.texts[4], " F100.0 S500 G90 G64M3");  // G64: LinuxCNC always states it
  EXPECT_EQ(e.texts[7], " F100.0 S500 G90 G64M9");  // M73's restore on the return from o<sub>
}

TEST(ProgramReader, RefusesWhatLinuxCncRefusesOrWhatNeverEnds) {
  EXPECT_NE(refusal("o1 call\nM2\n").find("test.ngc:2:1: error: the file ends before subroutine o1 is defined"),
            std::string::npos);
  EXPECT_NE(refusal("G0 X0\nM99\n").find("M99 in the main program repeats it forever"), std::string::npos);
  EXPECT_NE(refusal("o1 endwhile\n").find("endwhile without its while"), std::string::npos);
  EXPECT_NE(refusal("o1 if [1]\no1 endif\no1 if [1]\no1 endif\n").find("o1 is already used on line 1"),
            std::string::npos);
  EXPECT_NE(refusal("o1 sub\nG0 X#<_x>\no1 endsub\no1 call\n").find("test.ngc:2:"), std::string::npos);
  EXPECT_NE(refusal("G0 X#5420\n").find("not known offline"), std::string::npos);
  EXPECT_NE(refusal("o1 sub\no1 call\no1 endsub\no1 call\n").find("nested deeper"), std::string::npos);
}

}  // namespace
}  // namespace vc::interpreter
