// The R-test (identify rtest): a simulated nest of three sensors on a true machine whose rotary
// lines are off. The commanded joints are the nominal machine's for the nest on the sphere's
// centre (compensation off, a Newton solve of this test's own); the readings come from the true
// machine's 4x4 chain. Converted back (rtest_centres), the readings give joints at which the true
// machine's tip (the forward's other code path) sits on the sphere, and the joints this test's own
// solver finds; identified, the MC-300's location errors come back within 3 of their standard
// uncertainties. On every kind of machine: the table-table MC-300, the AC trunnion and a head
// (bc_head: the nest turns with the spindle, its frame with it).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <random>

#include "test_support.hpp"
#include "tip_on_point.hpp"
#include "vc/identify/rtest.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::identify {
namespace {

namespace fs = std::filesystem;
constexpr double kArcsec = M_PI / 648000.0;

void offset(machine::Model& m, char axis, int component, double by) {
  machine::Axis& a = m.axes[static_cast<std::size_t>(m.joint_of(axis))];
  (component < 3 ? a.location_mm[component] : a.location_rad[component - 3]) += by;
  a.real_base = machine::line_placement(a.pole_mm, a.location_mm, a.location_rad);
}

machine::Model load(const std::string& name) {
  return machine::load_machine(name == "bc_head" ? test::source_path("tests/unit/machines/data/bc_head.toml")
                                                 : test::machine_path(name));
}

// The R-test's poses: every combination of the two rotary axes' positions, the nest commanded
// onto the sphere by the nominal kinematics; the readings on `truth`.
std::vector<RTestReading> run_rtest(const machine::Model& nominal, const machine::Model& truth,
                                    const std::vector<double>& tilts, const std::vector<double>& turns,
                                    const Eigen::Vector3d& centre, double noise_mm, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<int> rotary;
  for (int j = 0; j < nominal.joint_count(); ++j)
    if (nominal.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Rotary) rotary.push_back(j);
  std::vector<RTestReading> readings;
  for (double tilt : tilts)
    for (double turn : turns) {
      machine::Joints q(nominal.joint_count());
      for (int j = 0; j < nominal.joint_count(); ++j)
        q[j] = (nominal.axes[static_cast<std::size_t>(j)].travel_min + nominal.axes[static_cast<std::size_t>(j)].travel_max) / 2;
      q[rotary[0]] = tilt;
      q[rotary[1]] = turn;
      RTestReading r;
      r.joints = test::tip_on_point(nominal, machine::Machine::Ideal, q, centre, nominal.tool_length_mm);
      r.deviation_mm = rtest_reading(truth, r.joints, nominal.tool_length_mm, centre, noise_mm, &rng);
      r.line = static_cast<int>(readings.size()) + 2;
      readings.push_back(r);
    }
  return readings;
}

machine::Model lines_off(const machine::Model& model) {
  machine::Model truth = model;
  std::vector<int> rotary;
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Rotary) rotary.push_back(j);
  const char first = model.axes[static_cast<std::size_t>(rotary[0])].letter;
  const char second = model.axes[static_cast<std::size_t>(rotary[1])].letter;
  offset(truth, second, 0, 0.015);
  offset(truth, second, 1, -0.010);
  offset(truth, second, 3, -3 * kArcsec);
  offset(truth, first, 0, -0.012);
  offset(truth, first, 2, 0.008);
  offset(truth, first, 5, 6 * kArcsec);
  return truth;
}

class RTest : public ::testing::TestWithParam<std::string> {};

// Without noise the readings, converted on the true machine, are the joints that put its real
// tip on the sphere: the sign and frame of every sensor (the readings are tens of um).
TEST_P(RTest, ReadingsConvertedOnTheTruthPutItsTipOnTheSphere) {
  const machine::Model model = load(GetParam());
  const machine::Model truth = lines_off(model);
  const Eigen::Vector3d centre(30, -20, 40);
  const std::vector<RTestReading> readings = run_rtest(model, truth, {-60, -30, 0}, {0, 90, 180, 270}, centre, 0, 1);
  const std::vector<SpherePose> poses = rtest_centres(truth, readings, truth.tool_length_mm);
  double largest_reading = 0, tip = 0, joints = 0, along_tool = 0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    largest_reading = std::max(largest_reading, readings[k].deviation_mm.norm());
    // The sensor along the spindle's axis (dz) reads the centre's offset along the real tool
    // direction (the forward's tool_pose, not the 4x4 chain the reading comes from).
    const machine::ToolPose real =
        machine::tool_pose(truth, machine::Machine::Real, readings[k].joints, truth.tool_length_mm);
    along_tool = std::max(along_tool, std::abs(readings[k].deviation_mm.z() - (centre - real.tip_mm).dot(real.direction)));
    tip = std::max(tip, (machine::tool_pose(truth, machine::Machine::Real, poses[k].joints, truth.tool_length_mm).tip_mm -
                         centre).norm());
    const machine::Joints own = test::tip_on_point(truth, machine::Machine::Real, readings[k].joints, centre, truth.tool_length_mm);
    joints = std::max(joints, (own - poses[k].joints).cwiseAbs().maxCoeff());
  }
  EXPECT_GT(largest_reading, 0.005) << "the lines off show in the readings";
  EXPECT_LT(tip, 1e-9);
  EXPECT_LT(joints, 1e-9);
  EXPECT_LT(along_tool, 1e-12);
  std::cout << GetParam() << ": readings up to " << largest_reading * 1e3 << " um; converted, the true tip within "
            << tip << " mm of the sphere\n";
}

INSTANTIATE_TEST_SUITE_P(Machines, RTest, ::testing::Values("mc300", "ac_trunnion", "bc_head"),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

// With 1 um of sensor noise the MC-300's lines come back within 3 standard uncertainties, each
// uncertainty under 2 um or 2 arcsec: through the command line, the readings file written as an
// R-test's software would.
TEST(RTestIdentify, FindsTheRotaryLinesWithinTheirUncertainty) {
  const machine::Model model = load("mc300");
  const machine::Model truth = lines_off(model);
  const std::vector<RTestReading> readings =
      run_rtest(model, truth, {0, -30, -60, -90}, {0, 90, 180, 270}, {30, -20, 40}, 1e-3, 7);
  const fs::path dir = fs::temp_directory_path() / ("vc_rtest_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    std::ofstream csv(dir / "rtest.csv");
    csv << "x,y,z,b,c,dx[um],dy[um],dz[um]\n" << std::setprecision(12);
    for (const RTestReading& r : readings) {
      for (int j = 0; j < 5; ++j) csv << r.joints[j] << ',';
      csv << r.deviation_mm.x() * 1e3 << ',' << r.deviation_mm.y() * 1e3 << ',' << r.deviation_mm.z() * 1e3 << '\n';
    }
  }
  const std::vector<std::string> symbols{"EX0C", "EY0C", "EA0C", "EX0B", "EZ0B", "EA0B", "EC0B"};
  const SphereFit fit = identify_from_sphere(
      model, rtest_centres(model, read_rtest_readings((dir / "rtest.csv").string(), model), model.tool_length_mm),
      symbols, model.tool_length_mm);
  ASSERT_EQ(fit.estimates.size(), symbols.size());
  for (const LocationEstimate& e : fit.estimates) {
    const machine::Axis& a = truth.axes[static_cast<std::size_t>(e.joint)];
    const double t = e.component < 3 ? a.location_mm[e.component] : a.location_rad[e.component - 3];
    EXPECT_LE(std::abs(e.value - t), 3 * e.uncertainty) << e.symbol;
    EXPECT_LT(e.uncertainty, e.component < 3 ? 2e-3 : 2 * kArcsec) << e.symbol;
    EXPECT_GT(e.uncertainty, 0.0) << e.symbol;
  }
  const auto r = test::run_volcomp("identify rtest " + test::machine_path("mc300") + " " + (dir / "rtest.csv").string() +
                                   " --deviations EX0C,EY0C,EA0C,EX0B,EZ0B,EA0B,EC0B --machine-out " +
                                   (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("7 of 7 location errors identified"), std::string::npos) << r.out;
  const machine::Model written = machine::load_machine((dir / "out/mc300.toml").string());
  EXPECT_NEAR(written.axes[written.joint_of('C')].location_mm[0], truth.axes[truth.joint_of('C')].location_mm[0], 0.003);

  // A readings file without dz: refused with its file and line, nothing written.
  std::ofstream(dir / "bad.csv") << "x,y,z,b,c,dx[um],dy[um]\n0,0,0,0,0,1,2\n";
  const auto bad = test::run_volcomp("identify rtest " + test::machine_path("mc300") + " " + (dir / "bad.csv").string() +
                                     " --machine-out " + (dir / "bad_out").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.out;
  EXPECT_NE(bad.out.find("bad.csv:1"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("missing column dz[um]"), std::string::npos) << bad.out;
  EXPECT_FALSE(fs::exists(dir / "bad_out"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vc::identify
