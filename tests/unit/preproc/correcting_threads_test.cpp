// Two correcting threads (each takes every other batch of lines and resumes where the batch
// before left the machine) write the program one thread writes: the same lines, the same
// words, numbers equal to the last digit written, across batch boundaries inside a contour,
// after a G28 (machine at an uncorrected position) and across tool length changes.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <sstream>

#include "test_support.hpp"
#include "vc/interpreter/linuxcnc_files.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/predistort.hpp"

namespace vc::predistort {
namespace {

std::string contour(int from, int count) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(4);
  for (int k = from; k < from + count; ++k) {
    const double c = k * 0.05, t = c * M_PI / 180.0;
    out << 'X' << -300 + 60 * std::cos(t) << " Y" << -160 + 60 * std::sin(t) << " Z" << -200 + 5 * std::sin(3 * t)
        << " B" << -35 + 10 * std::sin(2 * t) << " C" << c << '\n';
  }
  return out.str();
}

std::string predistorted(const machine::Model& model, const std::string& program, int threads, Summary& summary) {
  const interpreter::ToolTable tools = interpreter::read_tool_table(test::source_path("tests/programs/mc300.tbl"));
  gcode::Parameters parameters;
  interpreter::read_var_file(test::source_path("tests/programs/mc300.var"), parameters);
  Job job;
  job.model = &model;
  job.setup.file = "contour.ngc";
  job.setup.machine_axes = program_axes(model);
  job.setup.tools = &tools;
  job.setup.var_file = &parameters;
  job.correcting_threads = threads;
  std::istringstream in(program);
  std::ostringstream out;
  summary = predistort(in, out, job);
  return out.str();
}

TEST(CorrectingThreads, TwoWriteWhatOneWrites) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const std::string program = "G21 G90 G17 G94 G54\nG43 H1\nG0 X-300 Y-100 Z-150 B0 C0\nG0 B-35\nG1 F2000\n" +
                              contour(0, 1500) + "G28\nG1 F2000\n" + contour(1500, 1000) + "G49\n" +
                              contour(2500, 1000) + "G43 H1\n" + contour(3500, 1000) + "G0 Z-100\nM30\n";
  Summary one, two;
  const std::string a = predistorted(model, program, 1, one), b = predistorted(model, program, 2, two);
  EXPECT_EQ(one.lines, two.lines);
  EXPECT_EQ(one.translated_lines, two.translated_lines);
  EXPECT_EQ(one.corrector.moves, two.corrector.moves);
  EXPECT_EQ(one.corrector.pieces, two.corrector.pieces);
  EXPECT_GT(two.corrector.corrections, one.corrector.corrections);  // each take-over corrects a move's end again
  EXPECT_EQ(two.written_as_is_moves, 1);                            // the G28
  // Line by line: the same words; numbers within one unit of the last (sixth) decimal.
  std::istringstream la(a), lb(b);
  std::string x, y;
  const std::regex number(R"(-?[0-9]*\.?[0-9]+)");
  int lines = 0, differing = 0;
  while (std::getline(la, x)) {
    ASSERT_TRUE(std::getline(lb, y)) << "two threads wrote fewer lines";
    ++lines;
    if (x == y) continue;
    ++differing;
    EXPECT_EQ(std::regex_replace(x, number, "#"), std::regex_replace(y, number, "#")) << x << "\n" << y;
    std::sregex_iterator i(x.begin(), x.end(), number), j(y.begin(), y.end(), number), end;
    for (; i != end && j != end; ++i, ++j)
      EXPECT_NEAR(std::stod(i->str()), std::stod(j->str()), 1.5e-6) << x << "\n" << y;
  }
  EXPECT_FALSE(std::getline(lb, y)) << "two threads wrote more lines";
  std::printf("%d lines, %d differ in the last digit\n", lines, differing);
  EXPECT_GT(lines, 4500);
}

}  // namespace
}  // namespace vc::predistort
