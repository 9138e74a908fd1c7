// volkins in full headless LinuxCNC sessions (kins/configs/run_headless.sh: linuxcnc with the
// headless driver as display, halsampler's stream read at servo rate). Each trace is checked
// against the core (vc/trace/session_trace.hpp): the joints LinuxCNC sent are its cubic
// interpolation of exactly the joints the core computes for the recorded commands, those
// joints put the real machine's tool on the commanded pose, and without compensation the tool
// is off by the model's volumetric error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <regex>
#include <sstream>

#include "linuxcnc_run.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/trace/session_trace.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
using machine::Joints;
using machine::WorldConvention;

const std::string kMc300Ini = "kins/configs/mc300/mc300.ini";

// Runs a session of `ini` with run_headless.sh options; returns the trace, read for `model`.
trace::SessionTrace run_session(const std::string& name, const std::string& ini, const machine::Model& model,
                                const std::string& options) {
  const fs::path dir = test::run_folder(name);
  const test::CommandResult r = test::run_in(
      dir, "bash " + test::source_path("kins/configs/run_headless.sh") + " " + test::source_path(ini) + " " +
               (dir / "run").string() + " " + options,
      900);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  if (r.exit_code != 0) throw std::runtime_error("session failed: " + r.out);
  const fs::path config = fs::path(ini).parent_path().filename();
  return trace::read_session_trace((dir / "run/kins/configs" / config / "trace.csv").string(), model);
}

struct Extremes {
  double tip_mm = 0, mismatch = 0, pose_mm = 0, pose_rad = 0, pose_mm_faded = 0;
  std::size_t full = 0;
};

Extremes extremes(const trace::TraceSummary& s) {
  Extremes e;
  for (const trace::SampleCheck& c : s.samples) {
    e.tip_mm = std::max(e.tip_mm, c.tip_error_mm.norm());
    e.mismatch = std::max(e.mismatch, c.module_mismatch);
    if (c.full_correction) {
      ++e.full;
      e.pose_mm = std::max(e.pose_mm, c.command_pose_mm);
      e.pose_rad = std::max(e.pose_rad, c.command_pose_rad);
    }
  }
  return e;
}

// The claims of a compensated session, at every sample.
void expect_compensated(const trace::TraceSummary& s, int model_rotaries, const std::string& what) {
  ASSERT_GT(s.samples.size(), 10000u) << what;
  const Extremes e = extremes(s);
  EXPECT_LT(e.mismatch, 1e-9) << what << ": the module's joints differ from the core's";
  EXPECT_LT(e.pose_mm, 1e-6) << what;
  EXPECT_LT(e.pose_rad, 1e-8) << what;
  if (model_rotaries == 2) {
    EXPECT_GT(e.full, s.samples.size() / 3) << what << ": too few samples with the full correction";
  }
  for (const trace::SampleCheck& c : s.samples) {
    if (!c.full_correction) {
      ASSERT_LT(c.command_pose_mm, 1e-6) << what << " sample " << c.sample;
    }
  }
  // What remains at the tool is LinuxCNC's joint smoothing of a corrected path (~1e-5 mm).
  EXPECT_LT(e.tip_mm, 1e-4) << what;
  std::cout << what << ": module-core max " << e.mismatch << ", commanded pose residual max " << e.pose_mm
            << " mm / " << e.pose_rad << " rad, tool tip after LinuxCNC's interpolation max " << e.tip_mm * 1e3
            << " um\n";
}

class Mc300Session : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { model_ = new machine::Model(machine::load_machine(test::machine_path("mc300"))); }
  static void TearDownTestSuite() { delete model_; }
  static machine::Model* model_;
};
machine::Model* Mc300Session::model_ = nullptr;

TEST_F(Mc300Session, CompensationOnPutsTheRealToolOnTheCommandedPose) {
  const trace::SessionTrace t = run_session("mc300_on", kMc300Ini, *model_, "--compensation on");
  expect_compensated(trace::check_trace(*model_, WorldConvention::Axes, t), 2, "mc300 axes, compensation on");
}

TEST_F(Mc300Session, CompensationOffLeavesTheModelsVolumetricError) {
  const trace::SessionTrace t = run_session("mc300_off", kMc300Ini, *model_, "--compensation off");
  const trace::TraceSummary s = trace::check_trace(*model_, WorldConvention::Axes, t);
  ASSERT_GT(s.samples.size(), 10000u);
  double largest = 0;
  for (const trace::SampleCheck& c : s.samples) {
    ASSERT_EQ(c.module_mismatch, 0.0) << "sample " << c.sample << ": joints are not the nominal ones";
    const double L = t.tool_length_mm[c.sample - 1];
    const machine::VolumetricError e = machine::volumetric_error(*model_, t.joints[c.sample], L);
    ASSERT_LT((c.tip_error_mm - e.position_mm).norm(), 1e-9) << "sample " << c.sample;
    largest = std::max(largest, c.tip_error_mm.norm());
  }
  EXPECT_GT(largest, 0.020);  // tens of um on the MC-300
  EXPECT_LT(largest, 0.200);
  std::cout << "mc300 compensation off: tool tip error max " << largest * 1e3 << " um\n";
}

// INI value of [section] key.
double ini_value(const std::string& ini, const std::string& section, const std::string& key) {
  std::ifstream in(test::source_path(ini));
  std::string line, current;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '[') current = line.substr(1, line.find(']') - 1);
    std::smatch m;
    if (current == section && std::regex_match(line, m, std::regex(key + R"(\s*=\s*(\S+)\s*)")))
      return std::stod(m[1]);
  }
  throw std::runtime_error("no [" + section + "] " + key + " in " + ini);
}

TEST_F(Mc300Session, TogglingWhileMovingStaysWithinJointLimits) {
  const trace::SessionTrace t = run_session("mc300_toggle", kMc300Ini, *model_, "--compensation toggle");
  const trace::TraceSummary s = trace::check_trace(*model_, WorldConvention::Axes, t);
  ASSERT_GT(s.samples.size(), 10000u);
  const Extremes e = extremes(s);
  EXPECT_LT(e.mismatch, 1e-9) << "the ramp is not what the core computes";
  // The ramp ran while the program moved: intermediate gains, and both ends.
  std::size_t ramping = 0, off = 0, on = 0;
  for (double g : t.gain) {
    ramping += g > 0.0 && g < 1.0;
    off += g == 0.0;
    on += g == 1.0;
  }
  EXPECT_GT(ramping, 2000u);
  EXPECT_GT(off, 100u);
  EXPECT_GT(on, 100u);
  // Velocity and acceleration by finite differences at the servo period, at every sample, tool
  // changes included (volkins slews L after a G43 instead of stepping the joints): of the joints
  // LinuxCNC sent, and of the ramp's share (the joints minus those of the full correction for
  // the L applied, both through LinuxCNC's interpolation).
  ASSERT_EQ(t.correction_length_mm.size(), t.size()) << "the trace records the L applied";
  const double dt = 1e-3;
  std::vector<Joints> full(t.size()), ramp_share(t.size());
  for (std::size_t k = 0; k < t.size(); ++k)
    machine::joints_from_world(*model_, WorldConvention::Axes, t.world[k], t.correction_length_mm[k], full[k]);
  for (std::size_t n = 8; n < t.size(); ++n) ramp_share[n] = t.joints[n] - trace::interpolated(full, n);
  std::size_t tool_changes = 0;
  for (std::size_t n = 1; n < t.size(); ++n) tool_changes += t.tool_length_mm[n] != t.tool_length_mm[n - 1];
  EXPECT_GT(tool_changes, 0u) << "the program changes the tool length while the compensation toggles";
  auto peaks = [&](const std::vector<Joints>& q, int j) {
    double v = 0, a = 0;
    for (std::size_t n = 9; n + 1 < q.size(); ++n) {
      v = std::max(v, std::abs(q[n + 1][j] - q[n][j]) / dt);
      a = std::max(a, std::abs(q[n + 1][j] - 2 * q[n][j] + q[n - 1][j]) / (dt * dt));
    }
    return std::pair{v, a};
  };
  for (int j = 0; j < model_->joint_count(); ++j) {
    const std::string section = "JOINT_" + std::to_string(j);
    const double v_max = ini_value(kMc300Ini, section, "MAX_VELOCITY");
    const double a_max = ini_value(kMc300Ini, section, "MAX_ACCELERATION");
    const auto [v, a] = peaks(t.joints, j);
    const auto [v_ramp, a_ramp] = peaks(ramp_share, j);
    EXPECT_LE(v, v_max) << section;
    EXPECT_LE(a, a_max) << section;
    // Within the 5 % the INI leaves between axis and joint limits (it contains the correction's
    // own slope changes at table nodes, scaled by 1 - gain).
    EXPECT_LE(v_ramp, 0.05 * v_max) << section;
    EXPECT_LE(a_ramp, 0.05 * a_max) << section;
    std::cout << section << ": peak velocity " << v << " (limit " << v_max << ", ramp's share " << v_ramp
              << "), peak acceleration " << a << " (limit " << a_max << ", ramp's share " << a_ramp << ")\n";
  }
}

// The TCP convention: the program gives the tool tip in the part frame (G43 adds the tool
// length to Z, as for LinuxCNC's own TCP kinematics). The program is the 5-axis contour of
// sample_part.ngc, converted with the ideal machine.
TEST_F(Mc300Session, TcpConventionPutsTheRealToolOnTheCommandedPose) {
  const fs::path dir = test::run_folder("mc300_tcp_program");
  const double L = 100.0;
  std::ofstream ngc(dir / "tcp_contour.ngc");
  ngc << std::fixed << std::setprecision(6);
  ngc << "G21 G90 G17 G40 G49 G54 G94 G64 P0.001\nT1 M6\nG43 H1\n";
  for (int i = 0; i <= 90; ++i) {
    const double t = i / 90.0, pi = 3.14159265358979323846;
    Joints q(5);
    q << -360 + 60 * std::cos(2 * pi * t), -160 + 60 * std::sin(2 * pi * t), -100 - 40 * std::sin(pi * t),
        -60 * std::sin(pi * t), 360 * t;
    const Joints w = machine::nominal_forward(*model_, WorldConvention::Tcp, q, L);
    ngc << (i == 0 ? "G0 " : i == 1 ? "G1 F4000 " : "") << "X" << w[0] << " Y" << w[1] << " Z" << w[2] << " B"
        << w[3] << " C" << w[4] << "\n";
  }
  ngc << "M2\n";
  ngc.close();
  const std::string kins = "\"volkins machine=../../../machines/data/mc300.toml coordinates=xyzbc world=tcp\"";
  // World limits are the part frame's, not the axes': opened up for this program.
  std::string limits;
  for (const char* axis : {"AXIS_X", "AXIS_Y", "AXIS_Z"})
    limits += std::string(" --set ") + axis + ".MIN_LIMIT=-2000 --set " + axis + ".MAX_LIMIT=2000";
  const trace::SessionTrace t =
      run_session("mc300_tcp", kMc300Ini, *model_,
                  "--kinematics " + kins + limits + " --program " + (dir / "tcp_contour.ngc").string());
  expect_compensated(trace::check_trace(*model_, WorldConvention::Tcp, t), 2, "mc300 tcp, compensation on");
}

TEST(Mill3Session, CompensationOnPutsTheRealToolOnTheCommandedPose) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const trace::SessionTrace t = run_session("mill3_on", "kins/configs/mill3/mill3.ini", model, "");
  expect_compensated(trace::check_trace(model, WorldConvention::Axes, t), 0, "mill3, compensation on");
}

// A HAL file without `addf volkins.update` (a stock configuration that loads volkins and
// forgets the function): the machine is still corrected, in full from the start, volkins.gain
// says so at every sample, and the operator is told what is missing (the headless driver
// fails the session unless that message comes).
TEST(Mill3Session, WithoutTheUpdateFunctionTheCorrectionIsAppliedInFullAndSaidSo) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const trace::SessionTrace t =
      run_session("mill3_no_update", "kins/configs/mill3/mill3.ini", model,
                  "--without-update --expect-message 'volkins.update has not run before the kinematics'");
  for (std::size_t n = 0; n < t.size(); ++n) ASSERT_EQ(t.gain[n], 1.0) << "sample " << n;
  expect_compensated(trace::check_trace(model, WorldConvention::Axes, t), 0, "mill3 without volkins.update");
}

}  // namespace
}  // namespace vc
