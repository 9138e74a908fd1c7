// Every error each instrument on a line can measure, on every shipped machine, tool side and
// workpiece side (issue 48): a true machine is the machine file with that error changed (a
// table added over the axis); the laser's readings are simulated here, on the true machine's
// forward model, with a reading written out in this file (not identify's code path): the
// tool-side optic against the part, along the axis's own ideal motion for its positioning,
// along the part frame's axes otherwise, rotations from the rotation matrices' skew parts.
// identify (laser_into_machine) writes the file that reads them; checked on what it wrote:
// - the written file reads the truth's readings at every target, within 1e-3 of their size;
// - the written file's error of the axis (its own motion, in its frame: what the tables hold)
//   equals the truth's at every target, within 1e-3 of the change: the sign of a table axis.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <string>

#include "simulated_laser.hpp"
#include "test_support.hpp"
#include "vc/identify/laser_into_machine.hpp"
#include "vc/identify/laser_line.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/shop/machine_file_writer.hpp"

namespace vc::identify {
namespace {

namespace fs = std::filesystem;
using machine::Machine;

// The axis's own error of `component` at `target` (its frame: what the tables hold).
double axis_error(const machine::Model& model, const test::LaserLine& line, double target) {
  machine::Joints q = line.at;
  q[line.joint] = target;
  machine::AxisErrors e;
  machine::axis_errors(model, line.joint, q, e, false);
  return line.error.component < 3 ? e.delta_mm[line.error.component] : e.eps_rad[line.error.component - 3];
}

class LaserLineOnEveryMachine : public ::testing::TestWithParam<std::string> {};

TEST_P(LaserLineOnEveryMachine, IdentifiedFileReadsTheTruthAndHoldsItsError) {
  const std::string name = GetParam();
  const machine::Model model = machine::load_machine(test::machine_path(name));
  const fs::path folder = fs::temp_directory_path() / ("vc_laser_line_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  int cases = 0;
  for (int j = 0; j < model.joint_count(); ++j) {
    const machine::Axis& axis = model.axes[static_cast<std::size_t>(j)];
    const bool rotary = axis.type == machine::AxisType::Rotary;
    const int own = static_cast<int>(std::string("XYZABC").find(axis.letter));
    for (int c = 0; c < 6; ++c) {
      if (rotary && c != own) continue;  // of a rotary axis, its positioning (an angular reference)
      test::LaserLine line{j,
                           {c, axis.letter, false},
                           machine::Joints::Zero(model.joint_count()),
                           Eigen::Vector3d(15, -25, -model.tool_length_mm)};
      for (int k = 0; k < model.joint_count(); ++k) {
        const machine::Axis& a = model.axes[static_cast<std::size_t>(k)];
        line.at[k] = a.type == machine::AxisType::Rotary ? 0.0 : 0.3 * a.travel_min + 0.7 * a.travel_max;
      }
      const std::string what = name + " " + line.error.name();
      SCOPED_TRACE(what);
      // 11 targets over the travel (a rotary table's full turn), the truth's change at them.
      const bool turn = rotary && axis.travel_max - axis.travel_min >= 360.0;
      const double lo = turn ? 0.0 : axis.travel_min, hi = turn ? 360.0 : axis.travel_max;
      const double size = c < 3 ? 6e-3 : 25e-6;  // 6 um, 25 urad
      tables::GridVariable grid;
      grid.axis = axis.letter;
      grid.rotary = rotary;
      grid.periodic = turn;
      std::vector<double> change;
      for (int k = 0; k <= 10; ++k) {
        const double t = k / 10.0;
        grid.nodes.push_back(lo + (hi - lo) * t);
        change.push_back(size * (std::sin(2 * M_PI * t + 0.5) - std::sin(0.5) + (turn ? 0.0 : 0.6 * t)));
      }
      const shop::ExtraTable extra{
          j, "truth.csv",
          tables::ErrorTable("truth.csv", {grid}, {{line.error, {}}}, change, tables::Interpolation::Linear)};
      const machine::Model truth = machine::load_machine(
          shop::write_machine_with_tables(model, (folder / (line.error.name() + "_truth")).string(), {extra}, "truth"));

      LaserLineRuns runs;
      runs.setup = {j, line.error, line.at, line.point};
      runs.targets = grid.nodes;
      runs.reference = Reference::None;  // the simulated truth is the machine's own reading
      for (const double t : runs.targets) {
        runs.readings.push_back(test::simulated_reading(truth, line, t));
        runs.noise.push_back(0.0);
      }
      const LaserIntoMachine result = laser_into_machine(model, runs, (folder / line.error.name()).string(), "test");
      const machine::Model written = machine::load_machine(result.written);
      double largest = 0, file_off = 0;
      for (std::size_t k = 0; k < runs.targets.size(); ++k) largest = std::max(largest, std::abs(runs.readings[k]));
      for (std::size_t k = 0; k < runs.targets.size(); ++k) {
        const double t = runs.targets[k];
        EXPECT_NEAR(test::simulated_reading(written, line, t), runs.readings[k], 1e-3 * largest) << "at " << t;
        EXPECT_NEAR(axis_error(written, line, t), axis_error(truth, line, t), 1e-3 * size) << "at " << t;
        file_off = std::max(file_off, std::abs(test::simulated_reading(model, line, t) - runs.readings[k]));
      }
      EXPECT_GT(file_off, 0.5 * size);  // the file did not read the truth before: the checks can fail
      ++cases;
    }
  }
  EXPECT_EQ(cases, 6 * (model.joint_count() - model.rotary_count()) + model.rotary_count());
  fs::remove_all(folder);
}

INSTANTIATE_TEST_SUITE_P(Shipped, LaserLineOnEveryMachine,
                         ::testing::Values("mc300", "mill3", "ac_trunnion", "knee_mill", "mc300_thermal"));

}  // namespace
}  // namespace vc::identify
