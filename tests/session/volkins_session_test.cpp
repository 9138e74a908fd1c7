// volkins in full headless LinuxCNC sessions (kins/configs/run_headless.sh: linuxcnc with the
// headless driver as display, halsampler's stream read at servo rate). Each trace is checked
// against the core (vc/trace/session_trace.hpp): the joints LinuxCNC sent are its cubic
// interpolation of exactly the joints the core computes for the recorded commands, those
// joints put the real machine's tool on the commanded pose, and without compensation the tool
// is off by the model's volumetric error.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <regex>
#include <set>
#include <sstream>

#include "linuxcnc_run.hpp"
#include "vc/machine/compensation_types.hpp"
#include "vc/machine/held_rotary.hpp"
#include "vc/machine/load_machine.hpp"
#include "session_checks.hpp"
#include "types_by_name.hpp"
#include "vc/trace/session_trace.hpp"

namespace vc {
namespace {

using test::expect_compensated;
using test::Extremes;
using test::extremes;
namespace fs = std::filesystem;
using machine::Joints;
using machine::WorldConvention;

const std::string kMc300Ini = "kins/configs/mc300/mc300.ini";

// Runs a session of `ini` with run_headless.sh options; returns the trace, read for `model`.
trace::SessionTrace run_session(const std::string& name, const std::string& ini, const machine::Model& model,
                                const std::string& options) {
  const fs::path dir = test::run_folder(name);
  const test::CommandResult r = test::run_in(dir,
                                             "bash " + test::source_path("kins/configs/run_headless.sh") + " " +
                                                 test::source_path(ini) + " " + (dir / "run").string() + " " + options,
                                             900);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  if (r.exit_code != 0) throw std::runtime_error("session failed: " + r.out);
  const fs::path config = fs::path(ini).parent_path().filename();
  return trace::read_session_trace((dir / "run/kins/configs" / config / "trace.csv").string(), model);
}

// The core's full correction of a world position for tool length L: joints less nominal joints.
Joints full_correction(const machine::Model& model, const Joints& world, double L) {
  Joints full, nominal;
  machine::joints_from_world(model, WorldConvention::Axes, world, L, full);
  machine::nominal_inverse(model, WorldConvention::Axes, world, L, nominal);
  return full - nominal;
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
    const double L = t.tool_offset_mm[c.sample - 1];
    const machine::VolumetricError e = machine::volumetric_error(*model_, t.joints[c.sample], L);
    ASSERT_LT((c.tip_error_mm - e.position_mm).norm(), 1e-9) << "sample " << c.sample;
    largest = std::max(largest, c.tip_error_mm.norm());
  }
  EXPECT_GT(largest, 0.020);  // tens of um on the MC-300
  EXPECT_LT(largest, 0.200);
  std::cout << "mc300 compensation off: tool tip error max " << largest * 1e3 << " um\n";
}

// Peak joint velocity and acceleration (finite differences at the 1 ms servo period).
std::pair<double, double> joint_peaks(const std::vector<Joints>& q, int j) {
  const double dt = 1e-3;
  double v = 0, a = 0;
  for (std::size_t n = 9; n + 1 < q.size(); ++n) {
    v = std::max(v, std::abs(q[n + 1][j] - q[n][j]) / dt);
    a = std::max(a, std::abs(q[n + 1][j] - 2 * q[n][j] + q[n - 1][j]) / (dt * dt));
  }
  return {v, a};
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
  // LinuxCNC sent, and of what the ramp itself adds to the kinematics' outputs. Cycle k outputs
  // q_k = n_k + g_k D_k (n nominal, D the full correction for the L applied); the ramp adds
  // Delta^2(g D)_k - g_k Delta^2 D_k = (g_k+1 - g_k) D_k+1 + (g_k-1 - g_k) D_k-1 to the second
  // difference, and (g_k+1 - g_k) D_k+1 to the first. The correction's own slope changes (at
  // table nodes) are not the ramp's, whatever the gain when the path crosses them; and LinuxCNC's
  // interpolation, an average with positive weights, cannot make the ramp's share larger.
  ASSERT_EQ(t.correction_length_mm.size(), t.size()) << "the trace records the L applied";
  const double dt = 1e-3;
  std::vector<Joints> correction(t.size());
  for (std::size_t k = 0; k < t.size(); ++k)
    correction[k] = full_correction(*model_, t.world[k], t.correction_length_mm[k]);
  auto ramp_peaks = [&](int j) {
    double v = 0, a = 0;
    for (std::size_t k = 1; k + 1 < t.size(); ++k) {
      const double up = (t.gain[k + 1] - t.gain[k]) * correction[k + 1][j];
      v = std::max(v, std::abs(up) / dt);
      a = std::max(a, std::abs(up + (t.gain[k - 1] - t.gain[k]) * correction[k - 1][j]) / (dt * dt));
    }
    return std::pair{v, a};
  };
  std::size_t tool_changes = 0;
  for (std::size_t n = 1; n < t.size(); ++n) tool_changes += t.tool_offset_mm[n] != t.tool_offset_mm[n - 1];
  EXPECT_GT(tool_changes, 0u) << "the program changes the tool length while the compensation toggles";
  for (int j = 0; j < model_->joint_count(); ++j) {
    const std::string section = "JOINT_" + std::to_string(j);
    const double v_max = test::ini_value(kMc300Ini, section, "MAX_VELOCITY");
    const double a_max = test::ini_value(kMc300Ini, section, "MAX_ACCELERATION");
    const auto [v, a] = joint_peaks(t.joints, j);
    const auto [v_ramp, a_ramp] = ramp_peaks(j);
    EXPECT_LE(v, v_max) << section;
    EXPECT_LE(a, a_max) << section;
    // Within the 5 % the INI leaves between axis and joint limits.
    EXPECT_LE(v_ramp, 0.05 * v_max) << section;
    EXPECT_LE(a_ramp, 0.05 * a_max) << section;
    std::cout << section << ": peak velocity " << v << " (limit " << v_max << ", ramp's share " << v_ramp
              << "), peak acceleration " << a << " (limit " << a_max << ", ramp's share " << a_ramp << ")\n";
  }
}

// Tool length changes in quick succession while the machine moves (G43.1 every ~0.1 s, less
// than the 0.25 s slew: each arrives while L is still on its way to the last one; the program
// keeps the Z joint where it was). Every sample: the joints are the core's for the L volkins
// reports, their acceleration within the INI limits, and what the slew of L itself adds to
// their second difference, D(x_k, L_k+1) - 2 D(x_k, L_k) + D(x_k, L_k-1), within its bound:
// 4 x (the correction's change with L) x (largest change of L) / slew-time^2. A slew that
// restarted at rest stepped the joints' velocity by up to 1.5 x that change / slew-time.
TEST_F(Mc300Session, ToolLengthChangesInQuickSuccessionKeepTheJointsSmooth) {
  const fs::path dir = test::run_folder("mc300_tool_changes_program");
  const std::vector<double> lengths = {100, 60, 130, 80, 20, 150, 40, 110, 70, 140, 30, 100};
  std::ofstream ngc(dir / "tool_changes.ngc");
  ngc << "G21 G90 G17 G40 G49 G54 G94 G64 P0.001\nT1 M6\nG43 H1\nG0 X-300 Y-160 Z-200 B-30 C20\nG1 F4000\n";
  double largest_change = 0.0;
  for (std::size_t i = 0; i < 3 * lengths.size(); ++i) {
    const double L = lengths[i % lengths.size()], before = lengths[(i + lengths.size() - 1) % lengths.size()];
    largest_change = std::max(largest_change, std::abs(L - before));
    // The Z joint stays at -100: the programmed Z is the joint less the tool length.
    ngc << "G43.1 Z" << L << "\nX" << -300 + 2.0 * static_cast<double>(i % 2) << " Z" << -100 - L << "\n";
  }
  ngc << "G4 P1\nM2\n";
  ngc.close();
  const trace::SessionTrace t = run_session("mc300_tool_changes", kMc300Ini, *model_,
                                            "--compensation on --program " + (dir / "tool_changes.ngc").string());
  const trace::TraceSummary s = trace::check_trace(*model_, WorldConvention::Axes, t);
  ASSERT_GT(s.samples.size(), 1000u);
  EXPECT_LT(extremes(s).mismatch, 1e-9) << "the joints are not the core's for the L volkins reports";
  ASSERT_EQ(t.correction_length_mm.size(), t.size());
  // Offsets that arrived while L was still moving to the one before.
  std::size_t changes = 0, during_slew = 0;
  for (std::size_t n = 1; n < t.size(); ++n) {
    if (t.tool_offset_mm[n] == t.tool_offset_mm[n - 1]) continue;
    ++changes;
    during_slew += t.correction_length_mm[n - 1] != model_->correction_length(t.tool_offset_mm[n - 1]);
  }
  EXPECT_GE(changes, 30u);
  EXPECT_GE(during_slew, 20u) << "the offsets should change while L slews";
  const double dt = 1e-3, slew_time = 0.25;
  // At each sample with the full gain around it (not the enable ramp's): the correction of its
  // command for the L before, its own and the one after, what the slew of L alone changes.
  std::vector<std::array<Joints, 3>> by_length(t.size());
  for (std::size_t k = 9; k + 1 < t.size(); ++k)
    if (t.gain[k - 1] == 1.0 && t.gain[k + 1] == 1.0)
      for (std::size_t i = 0; i < 3; ++i)
        by_length[k][i] = full_correction(*model_, t.world[k], t.correction_length_mm[k + i - 1]);
  for (int j = 0; j < model_->joint_count(); ++j) {
    const std::string section = "JOINT_" + std::to_string(j);
    const double a_max = test::ini_value(kMc300Ini, section, "MAX_ACCELERATION");
    double a = 0.0, a_slew = 0.0, per_mm = 0.0;
    for (std::size_t k = 9; k + 1 < t.size(); ++k) {
      a = std::max(a, std::abs(t.joints[k + 1][j] - 2 * t.joints[k][j] + t.joints[k - 1][j]) / (dt * dt));
      if (by_length[k][0].size() == 0) continue;  // the enable ramp's samples
      const double d[3] = {by_length[k][0][j], by_length[k][1][j], by_length[k][2][j]};
      a_slew = std::max(a_slew, std::abs(d[2] - 2 * d[1] + d[0]) / (dt * dt));
      const double dL = t.correction_length_mm[k + 1] - t.correction_length_mm[k];
      if (std::abs(dL) > 1e-6) per_mm = std::max(per_mm, std::abs(d[2] - d[1]) / std::abs(dL));
    }
    const double bound = 4.0 * per_mm * largest_change / (slew_time * slew_time);
    EXPECT_LE(a, a_max) << section;
    // 5 %: the correction's change with L varies along the path; 1e-3 mm/s^2: the solver's tolerance
    // (1e-10 mm) in a second difference at 1 ms, where the change with L is nil (Z, B, C).
    EXPECT_LE(a_slew, bound * 1.05 + 1e-3) << section;
    std::cout << section << ": peak acceleration " << a << " mm/s^2 (limit " << a_max << "), the slew of L's share "
              << a_slew << " (bound " << bound << ", correction's change with L up to " << per_mm * 1e3 << " um/mm)\n";
  }
  std::cout << changes << " tool length changes, " << during_slew << " of them while L slewed\n";
}

void expect_within_joint_limits(const std::vector<Joints>& q, int joints, const std::string& what) {
  for (int j = 0; j < joints; ++j) {
    const std::string section = "JOINT_" + std::to_string(j);
    const auto [v, a] = joint_peaks(q, j);
    EXPECT_LE(v, test::ini_value(kMc300Ini, section, "MAX_VELOCITY")) << what << " " << section;
    EXPECT_LE(a, test::ini_value(kMc300Ini, section, "MAX_ACCELERATION")) << what << " " << section;
    std::cout << what << " " << section << ": peak velocity " << v << ", peak acceleration " << a << "\n";
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
    ngc << (i == 0   ? "G0 "
            : i == 1 ? "G1 F4000 "
                     : "")
        << "X" << w[0] << " Y" << w[1] << " Z" << w[2] << " B" << w[3] << " C" << w[4] << "\n";
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
  // The G43 at rest does not move the joints (the nominal TCP kinematics take the offset at
  // once, as LinuxCNC's own; only the correction's L slews).
  expect_within_joint_limits(t.joints, model_->joint_count(), "tcp");
}

// Switchable kinematics (LinuxCNC 2.9: motion.switchkins-type, M428/M429 remapped as in its
// sample trt configurations): kins/configs/mc300/nc/switchkins.ngc moves in the identity world
// (type 0, world=axes), switches to TCP (type 1), turns B and C about the tool tip, and back,
// four switches in all. Every sample is the core's correction in the world volkins reports
// (the trace's tcp column); at each switch the joints stand still while the world position
// changes to the other world's; the joints' velocity and acceleration stay within the INI.
const std::string kSwitchkinsOptions =
    " --halfile " + test::source_path("kins/configs/common/switchkins.hal") +
    " --add RS274NGC.SUBROUTINE_PATH=../common/remap_subs"
    " --add 'RS274NGC.REMAP=M428 modalgroup=10 ngc=428remap' --add 'RS274NGC.REMAP=M429 modalgroup=10 ngc=429remap'";

TEST_F(Mc300Session, SwitchedKinematicsKeepTheJointsStillAndCorrectBothWorlds) {
  // TCP's X Y Z are the part frame's: the world limits opened for both worlds.
  std::string limits;
  for (const char* axis : {"AXIS_X", "AXIS_Y", "AXIS_Z"})
    limits += std::string(" --set ") + axis + ".MIN_LIMIT=-2000 --set " + axis + ".MAX_LIMIT=2000";
  const trace::SessionTrace t =
      run_session("mc300_switchkins", kMc300Ini, *model_,
                  "--compensation on --program " + test::source_path("kins/configs/mc300/nc/switchkins.ngc") +
                      kSwitchkinsOptions + limits);
  ASSERT_EQ(t.convention.size(), t.size()) << "the trace records volkins.tcp";
  std::size_t tcp = 0, switches = 0;
  for (std::size_t n = 1; n < t.size(); ++n) {
    tcp += t.convention[n] == WorldConvention::Tcp;
    if (t.convention[n] == t.convention[n - 1]) continue;
    ++switches;
    // At rest: the joints stay (to the solvers' tolerance), the world is the other one's.
    EXPECT_LT((t.joints[n] - t.joints[n - 1]).cwiseAbs().maxCoeff(), 1e-9) << "joints jump at sample " << n;
    EXPECT_GT((t.world[n] - t.world[n - 1]).cwiseAbs().maxCoeff(), 1.0) << "the world did not change at " << n;
  }
  EXPECT_EQ(switches, 4u);
  EXPECT_GT(tcp, 1000u);
  EXPECT_GT(t.size() - tcp, 1000u);
  const trace::TraceSummary s = trace::check_trace(*model_, WorldConvention::Axes, t);
  ASSERT_GT(s.samples.size(), 5000u);
  const Extremes e = extremes(s);
  EXPECT_LT(e.mismatch, 1e-9) << "the module's joints differ from the core's";
  EXPECT_LT(e.pose_mm, 1e-6);
  EXPECT_LT(e.tip_mm, 1e-4);
  expect_within_joint_limits(t.joints, model_->joint_count(), "switchkins");
  std::cout << switches << " switches, " << tcp << " TCP samples of " << t.size() << ": module-core max " << e.mismatch
            << ", tool tip after LinuxCNC's interpolation max " << e.tip_mm * 1e3 << " um\n";
}

// A switch while the commanded position moves (motion.switchkins-type set from HAL during the
// sample part's first sweep, not through a remap that waits for rest) is refused: the queued
// moves are in the old world's coordinates, and LinuxCNC's own modules would take the switch
// and run them through the new kinematics. volkins stays in type 0, motion aborts the program
// and stops within the joints' acceleration limits, and the operator is told why.
TEST_F(Mc300Session, ASwitchWhileMovingIsRefusedAndMotionStopsWithinTheJointLimits) {
  const trace::SessionTrace t =
      run_session("mc300_switch_while_moving", kMc300Ini, *model_,
                  "--compensation on --add DRIVER.SCHEDULE=2.0:motion.switchkins-type=1"
                  " --expect-message 'switch to kinematics type 1 refused while the commanded position moves'"
                  " --allow-message 'kinematicsSwitch() FAIL'");  // motion's own report of the refusal
  ASSERT_EQ(t.convention.size(), t.size());
  for (std::size_t n = 0; n < t.size(); ++n) ASSERT_EQ(t.convention[n], WorldConvention::Axes) << "sample " << n;
  // It moved when the switch came and has stopped since: the program was aborted (its first
  // sweep alone lasts longer).
  ASSERT_GT(t.size(), 2000u);
  EXPECT_LT(t.size(), 4000u) << "the program ran on after the refused switch";
  EXPECT_GT((t.joints[1990] - t.joints[1989]).cwiseAbs().maxCoeff(), 1e-3) << "not moving at the switch";
  EXPECT_LT((t.joints.back() - t.joints[t.size() - 2]).cwiseAbs().maxCoeff(), 1e-9) << "not at rest at the end";
  const trace::TraceSummary s = trace::check_trace(*model_, WorldConvention::Axes, t);
  EXPECT_LT(extremes(s).mismatch, 1e-9);
  expect_within_joint_limits(t.joints, model_->joint_count(), "switch while moving");
}

// volcomp check --ini against LinuxCNC itself: a program that runs Y to the end of its travel
// (Y0) at B30 C270, where the correction takes the Y joint ~0.08 mm beyond the axis. With the
// configuration's joint limits (1 mm of room) the check passes and the program runs cleanly;
// with [JOINT_1]MAX_LIMIT = 0 (the axis's own, as a stock configuration has it) the check
// refuses it, and LinuxCNC refuses the program's move there ("Linear move on line 4 would exceed
// joint 1's positive limit": it checks a move's end through the inverse kinematics).
TEST_F(Mc300Session, AJointLimitWithoutRoomForTheCorrectionIsRefusedByTheCheckAndByLinuxCnc) {
  const fs::path dir = test::run_folder("mc300_joint_room");
  const fs::path program = dir / "y_to_the_end.ngc";
  std::ofstream(program) << "G21 G90 G94\nG0 X-1 Y-20 Z-150\nG0 B30 C270\nG1 Y0 F600\nG1 Y-20\nM2\n";
  const auto check = [&](const std::string& name) {
    return test::run_volcomp("check " + test::machine_path("mc300") + " --samples 10 --ini " +
                             (test::run_folder_path(name) / "run/kins/configs/mc300/mc300.ini").string());
  };

  const trace::SessionTrace room =
      run_session("mc300_joint_room_ok", kMc300Ini, *model_, "--compensation on --program " + program.string());
  const test::CommandResult usable = check("mc300_joint_room_ok");
  EXPECT_EQ(usable.exit_code, 0) << usable.out;
  double highest = -1e9;
  for (const Joints& q : room.joints) highest = std::max(highest, q[1]);
  EXPECT_GT(highest, 0.05) << "the program does not take the Y joint beyond its axis's limit";

  const trace::SessionTrace stopped =
      run_session("mc300_joint_room_none", kMc300Ini, *model_,
                  "--compensation on --program " + program.string() +
                      " --set JOINT_1.MAX_LIMIT=0 --expect-message \"would exceed joint 1's positive limit\""
                      " --allow-message 'invalid params in linear command'");
  const test::CommandResult refused = check("mc300_joint_room_none");
  EXPECT_EQ(refused.exit_code, 1) << refused.out;
  EXPECT_NE(refused.out.find("error: joint 1 (Y): the correction takes it to"), std::string::npos) << refused.out;
  EXPECT_LT(stopped.size(), room.size()) << "LinuxCNC ran the program to its end";
  std::cout << "Y joint at the end of the travel: " << highest
            << " mm (axis limit 0); without room, LinuxCNC stopped after " << stopped.size() << " of " << room.size()
            << " samples\n";
}

// Each compensation type switched off alone while the MC-300 runs, one after another
// (volkins.type.<code>.enable from the driver's schedule, ramp-time 0.3 s, 0.6 s off each; the
// program's moves of ~1 s and dwells of 0.5 s put switches into motion and into rest). Wherever
// the switches have been still for four cycles (gains 0 or 1: LinuxCNC's interpolation reaches
// back that far), the joints are the core's correction of the model with only the types that are
// on (its other terms zeroed by keep_only, the terms sorted from their names: types_by_name.hpp,
// not the module's code path) and put that model's tool on the commanded pose; with FOR off the
// tip is still on it and the tool direction keeps the machine's error. At every sample, the
// ramps included, joint velocity and acceleration within the INI's limits.
TEST_F(Mc300Session, EachCompensationTypeSwitchesAloneWithinTheJointLimits) {
  // The types the MC-300's file provides (it has no L-SPEC or R-SPEC terms), in the order of
  // trace_types.hal's types_off column, and FOR.
  const std::vector<std::string> codes{"L-POS", "L-STR", "L-SQU", "L-ANG", "R-POS", "R-RAX", "R-POR", "R-ANG", "FOR"};
  const machine::CompensationTypes provided = machine::compensation_types(*model_);
  std::string schedule;
  for (std::size_t k = 0; k < codes.size(); ++k) {
    ASSERT_TRUE(provided.has(codes[k])) << codes[k];
    std::string pin = codes[k];
    for (char& c : pin) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    std::ostringstream entries;
    entries << " --add 'DRIVER.SCHEDULE=" << 1.0 + 1.2 * k << ":volkins.type." << pin << ".enable=0 " << 1.6 + 1.2 * k
            << ":volkins.type." << pin << ".enable=1'";  // a line each: INI lines end at 255
    schedule += entries.str();
  }
  const trace::SessionTrace t = run_session(
      "mc300_types", kMc300Ini, *model_,
      "--program " + test::source_path("tests/session/programs/mc300_types.ngc") +
          " --replace-halfile trace.hal=" + test::source_path("tests/session/trace_types.hal") +
          " --set 'DRIVER.TRACE_COLUMNS=x y z b c j0 j1 j2 j3 j4 gain tool_offset controller_time correction_length "
          "tcp types_off'" +
          schedule);
  ASSERT_GT(t.size(), 15000u);
  const std::vector<double> types_off = test::trace_column(t.path, "types_off");

  // Which switch is off at each sample, steadily: types_off a power of two 2^k (or 0: all on),
  // the same for five samples (a ramp moves it every cycle) and the enable ramp at 1. -1: all
  // on; -2: a switch on its way or not yet still.
  std::vector<int> off(t.size(), -2);
  std::size_t ramping_moving = 0, ramping_at_rest = 0;
  for (std::size_t n = 4; n + 1 < t.size(); ++n) {
    bool still = t.gain[n] == 1.0;
    for (std::size_t back = 1; back <= 4; ++back) still &= types_off[n - back] == types_off[n];
    int which = -2;
    for (int k = -1; k < static_cast<int>(codes.size()); ++k)
      if (types_off[n] == (k < 0 ? 0.0 : std::ldexp(1.0, k))) which = k;
    if (still && which > -2) off[n] = which;
    if (types_off[n] != types_off[n - 1])
      ++((t.world[n] - t.world[n - 1]).norm() > 0 ? ramping_moving : ramping_at_rest);
  }
  EXPECT_GT(ramping_moving, 200u) << "switches while moving";
  EXPECT_GT(ramping_at_rest, 200u) << "switches at rest";

  for (int j = 0; j < model_->joint_count(); ++j) {
    const std::string section = "JOINT_" + std::to_string(j);
    const auto [v, a] = joint_peaks(t.joints, j);
    EXPECT_LE(v, test::ini_value(kMc300Ini, section, "MAX_VELOCITY")) << section;
    EXPECT_LE(a, test::ini_value(kMc300Ini, section, "MAX_ACCELERATION")) << section;
    std::cout << section << ": peak velocity " << v << ", peak acceleration " << a << "\n";
  }

  const trace::TraceSummary all = trace::check_trace(*model_, WorldConvention::Axes, t);
  for (int k = -1; k < static_cast<int>(codes.size()); ++k) {
    const std::string what = k < 0 ? "every type on" : codes[static_cast<std::size_t>(k)] + " off";
    std::set<std::string> on;
    for (const char* code : test::kBasicCodes)
      if (k < 0 || codes[static_cast<std::size_t>(k)] != code) on.insert(code);
    const bool for_off = k == static_cast<int>(codes.size()) - 1;
    const machine::Model only = test::with_only(*model_, on);
    const trace::TraceSummary s = for_off ? all : trace::check_trace(only, WorldConvention::Axes, t);
    std::size_t samples = 0;
    double mismatch = 0, tip = 0, tip_full_model = 0, direction = 0;
    for (std::size_t i = 0; i < s.samples.size(); ++i) {
      const trace::SampleCheck& c = s.samples[i];
      if (off[c.sample] != k) continue;
      ++samples;
      mismatch = std::max(mismatch, c.module_mismatch);
      tip = std::max(tip, c.tip_error_mm.norm());
      direction = std::max(direction, c.direction_error_rad);
      tip_full_model = std::max(tip_full_model, all.samples[i].tip_error_mm.norm());
    }
    ASSERT_EQ(s.samples.size(), all.samples.size());
    EXPECT_GT(samples, k < 0 ? 2000u : 150u) << what;
    if (!for_off) {
      EXPECT_LT(mismatch, 1e-9) << what << ": the module's joints are not the core's of the model with only the others";
    }
    EXPECT_LT(tip, 1e-4) << what << ": the tool tip of the model with the types on";
    if (for_off) {
      EXPECT_GT(direction, 1e-6) << what << ": the tool direction keeps the machine's error";
    }
    std::cout << what << ": " << samples << " samples, module-core max " << mismatch << ", tip max " << tip * 1e3
              << " um (against the whole file " << tip_full_model * 1e3 << " um), direction max " << direction
              << " rad\n";
  }
}

// 3+2 on the MC-300 with B and C as LinuxCNC's locking indexers (mc300_indexer.hal, as LinuxCNC's
// xyzb_locking_indexer sample simulates one: motion unlocks each for its indexing move, the clamp
// releases 0.3 s later and engages 0.2 s after the move; volkins follows the indexer's pins).
// While a clamp is engaged (the clamp's own signal, recorded) and the commanded B and C stand
// still, their joints do not move at all, although X, Y and Z move and the correction of a free
// B or C would; the tool tip is on the commanded point for the held rotary values (the trace's
// real tip at the recorded joints); the tool direction error is the one the core predicts for
// the joints held where they are (correct_held at the offsets the trace shows); what volkins
// adds to the joints' acceleration (beyond the commanded axes' own) stays within 5 % of the
// INI's limits, as the clamps engage and release too.
// LinuxCNC 2.9 itself starts an indexing move 4 cycles before it asks for the unlock, then waits
// for the clamp: the commanded B moves 0.0075 deg with the clamp engaged and stops at once (its
// acceleration ~2,700 deg/s^2, with trivkins as with volkins). Those cycles are LinuxCNC's.
TEST_F(Mc300Session, ThreePlusTwoWithClampedRotaryAxesHoldsThemAndPutsTheTipOnThePoint) {
  const trace::SessionTrace t = run_session(
      "mc300_3plus2", kMc300Ini, *model_,
      "--program " + test::source_path("tests/session/programs/mc300_3plus2.ngc") + " --halfile " +
          test::source_path("tests/session/mc300_indexer.hal") +
          " --replace-halfile trace.hal=" + test::source_path("tests/session/trace_indexer.hal") +
          " --set 'DRIVER.TRACE_COLUMNS=x y z b c j0 j1 j2 j3 j4 gain tool_offset controller_time correction_length "
          "tcp b_is_unlocked c_is_unlocked' --set 'EMCMOT.EMCMOT=motmod unlock_joints_mask=0x18'"
          " --add AXIS_B.LOCKING_INDEXER_JOINT=3 --add JOINT_3.LOCKING_INDEXER=1"
          " --add AXIS_C.LOCKING_INDEXER_JOINT=4 --add JOINT_4.LOCKING_INDEXER=1");
  ASSERT_GT(t.size(), 5000u);
  const int rotary[2] = {model_->joint_of('B'), model_->joint_of('C')};
  const std::vector<double> unlocked[2] = {test::trace_column(t.path, "b_is_unlocked"),
                                           test::trace_column(t.path, "c_is_unlocked")};
  // Clamped for the last five samples, the commanded B and C still as long.
  auto held_still = [&](std::size_t n) {
    if (n < 4) return false;
    for (std::size_t k = n - 4; k <= n; ++k)
      for (int r = 0; r < 2; ++r)
        if (unlocked[r][k] != 0.0 || t.world[k][rotary[r]] != t.world[n][rotary[r]]) return false;
    return true;
  };
  std::size_t held = 0, releases[2] = {0, 0};
  double moved = 0;
  for (std::size_t n = 1; n < t.size(); ++n) {
    for (int r = 0; r < 2; ++r) releases[r] += unlocked[r][n] == 1.0 && unlocked[r][n - 1] == 0.0;
    if (!held_still(n)) continue;
    ++held;
    for (int j : rotary) moved = std::max(moved, std::abs(t.joints[n][j] - t.joints[n - 1][j]));
  }
  EXPECT_GE(releases[0], 4u) << "B's indexing moves";
  EXPECT_GE(releases[1], 4u) << "C's indexing moves";
  EXPECT_GT(held, t.size() / 3);
  EXPECT_EQ(moved, 0.0) << "a clamped joint moved";

  const trace::TraceSummary s = trace::check_trace(*model_, WorldConvention::Axes, t);
  double tip = 0, predicted = 0, predicted_at_rest = 0, direction = 0;
  std::size_t at_rest = 0;
  for (const trace::SampleCheck& check : s.samples) {
    const std::size_t n = check.sample;
    tip = std::max(tip, check.tip_error_mm.norm());
    if (!held_still(n)) continue;
    machine::HeldRotary holding;
    for (int j : rotary) {
      holding.offset_deg[static_cast<std::size_t>(j)] = t.joints[n][j] - t.world[n][j];
      holding.release[static_cast<std::size_t>(j)] = 0.0;
    }
    const machine::Correction core = machine::correct_held(*model_, model_->reference_conditions(), t.world[n],
                                                           t.correction_length_mm[n], 1.0, holding, t.joints[n]);
    ASSERT_EQ(core.status, machine::Status::Ok) << n;
    // At rest (the whole command still for five cycles) LinuxCNC's interpolation is the command.
    bool rest = true;
    for (std::size_t k = n - 4; k < n; ++k) rest &= t.world[k] == t.world[n];
    (rest ? predicted_at_rest : predicted) =
        std::max(rest ? predicted_at_rest : predicted, std::abs(core.residual_rad - check.direction_error_rad));
    at_rest += rest;
    direction = std::max(direction, check.direction_error_rad);
  }
  EXPECT_LT(tip, 1e-4) << "the tool tip";
  EXPECT_GT(at_rest, 500u);
  EXPECT_LT(predicted_at_rest, 1e-10) << "the direction error left at rest, against the core's prediction";
  EXPECT_LT(predicted, 1e-6) << "the same while X, Y, Z move (LinuxCNC's interpolation of the joints)";
  EXPECT_GT(direction, 1e-6) << "held joints leave a direction error";
  // Joint velocity and acceleration within the INI's limits, but for the cycles around LinuxCNC's
  // own step of a commanded rotary axis (its acceleration beyond the axis's limit).
  const double dt = 1e-3;
  std::vector<bool> linuxcncs(t.size(), false);
  std::size_t excluded = 0;
  const double axis_limit[2] = {test::ini_value(kMc300Ini, "AXIS_B", "MAX_ACCELERATION"),
                                test::ini_value(kMc300Ini, "AXIS_C", "MAX_ACCELERATION")};
  for (std::size_t n = 1; n + 1 < t.size(); ++n)
    for (int r = 0; r < 2; ++r) {
      const int j = rotary[r];
      const double a = std::abs(t.world[n + 1][j] - 2 * t.world[n][j] + t.world[n - 1][j]) / (dt * dt);
      if (a > 1.05 * axis_limit[r])
        for (std::size_t k = n > 6 ? n - 6 : 0; k < std::min(t.size(), n + 7); ++k) linuxcncs[k] = true;
    }
  for (bool b : linuxcncs) excluded += b;
  EXPECT_LT(excluded, 200u) << "LinuxCNC's steps are a few cycles at each indexing move";
  for (int j = 0; j < model_->joint_count(); ++j) {
    const std::string section = "JOINT_" + std::to_string(j);
    double v = 0, a = 0;
    for (std::size_t n = 9; n + 1 < t.size(); ++n) {
      if (linuxcncs[n]) continue;
      v = std::max(v, std::abs(t.joints[n + 1][j] - t.joints[n][j]) / dt);
      a = std::max(a, std::abs(t.joints[n + 1][j] - 2 * t.joints[n][j] + t.joints[n - 1][j]) / (dt * dt));
    }
    EXPECT_LE(v, test::ini_value(kMc300Ini, section, "MAX_VELOCITY")) << section;
    EXPECT_LE(a, test::ini_value(kMc300Ini, section, "MAX_ACCELERATION")) << section;
    std::cout << section << ": peak velocity " << v << ", peak acceleration " << a << "\n";
  }
  std::cout << "3+2, B and C clamped and still in " << held << " of " << t.size()
            << " samples, largest joint step there " << moved << " deg; tool tip after LinuxCNC's interpolation max "
            << tip * 1e3 << " um; direction error left max " << direction * 1e6
            << " urad, against the core's prediction " << predicted_at_rest << " rad at rest (" << at_rest
            << " samples), " << predicted << " rad moving\n";
}

// The thermal example (machines/data/mc300_thermal.toml) in a session whose HAL ramps both
// temperature inputs while the sample program runs (kins/configs/mc300/mc300_thermal.ini,
// thermal.hal), with a spindle sensor that reads NaN, then 40 degC (beyond its range), for a
// while. At every sample: the module's filter, replicated here from the recorded readings; the
// joints are the core's at the filtered temperatures the module reports (to 1e-9 mm) and put the
// real tool on the commanded pose (1e-6 mm); the thermal share of the joints agrees with the
// example tables interpolated by hand; a faulty reading holds the last good value with the
// fault pin raised, and the joints run on smoothly.
TEST(Mc300ThermalSession, JointsFollowTheRampedTemperaturesAndAFaultySensorIsHeld) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300_thermal"));
  const trace::SessionTrace t = run_session("mc300_thermal", "kins/configs/mc300/mc300_thermal.ini", model, "");
  const fs::path csv = fs::temp_directory_path() / "volcomp-test-runs/mc300_thermal/run/kins/configs/mc300/trace.csv";
  const std::size_t count = t.size();
  const int coolant = model.temperature_of("coolant"), spindle = model.temperature_of("spindle");
  const std::vector<double>& coolant_filtered = t.temperature_degC[static_cast<std::size_t>(coolant)];
  const std::vector<double>& spindle_filtered = t.temperature_degC[static_cast<std::size_t>(spindle)];
  ASSERT_EQ(coolant_filtered.size(), count);
  ASSERT_EQ(spindle_filtered.size(), count);
  const std::vector<double> coolant_read = test::trace_column(csv, "coolant_sensor");
  const std::vector<double> spindle_read = test::trace_column(csv, "spindle_sensor");
  const std::vector<double> fault = test::trace_column(csv, "temperature_fault");
  ASSERT_EQ(spindle_read.size(), count);

  // The filter, replicated: first order, dt = 1 ms, tau = 0.5 s (thermal.hal); a reading that is
  // not a number or outside min_degC..max_degC is not taken, and the fault pin says so.
  const double dt = 1e-3, tau = 0.5;
  const auto valid = [&](int input, double reading) {
    const machine::TemperatureInput& in = model.temperatures[static_cast<std::size_t>(input)];
    return std::isfinite(reading) && reading >= in.min_degC && reading <= in.max_degC;
  };
  std::size_t nan_samples = 0, out_of_range_samples = 0;
  for (std::size_t k = 1; k < count; ++k) {
    const auto next = [&](double previous, int input, double reading) {
      return valid(input, reading) ? previous + (reading - previous) * dt / (tau + dt) : previous;
    };
    ASSERT_NEAR(coolant_filtered[k], next(coolant_filtered[k - 1], coolant, coolant_read[k]), 1e-12) << "sample " << k;
    ASSERT_NEAR(spindle_filtered[k], next(spindle_filtered[k - 1], spindle, spindle_read[k]), 1e-12) << "sample " << k;
    const bool faulty = !valid(coolant, coolant_read[k]) || !valid(spindle, spindle_read[k]);
    ASSERT_EQ(fault[k], faulty ? 1.0 : 0.0) << "sample " << k;
    if (faulty) {
      ASSERT_EQ(spindle_filtered[k], spindle_filtered[k - 1]) << "held, sample " << k;
    }
    nan_samples += std::isnan(spindle_read[k]);
    out_of_range_samples += spindle_read[k] > 28.0;
  }
  EXPECT_GT(nan_samples, 400u);  // the schedule's 0.6 s and 0.5 s
  EXPECT_GT(out_of_range_samples, 400u);
  const double coolant_top = *std::max_element(coolant_filtered.begin(), coolant_filtered.end());
  const double spindle_top = *std::max_element(spindle_filtered.begin(), spindle_filtered.end());
  EXPECT_GT(coolant_top, 24.5);
  EXPECT_GT(spindle_top, 26.5);

  // The joints are the core's at those temperatures and correct the warm machine.
  expect_compensated(trace::check_trace(model, WorldConvention::Axes, t), 2, "mc300 thermal example, ramped");

  // The thermal share of the joints: the recorded joints minus the core's at the reference
  // temperatures (through LinuxCNC's interpolation), against the example tables by hand: X, Y and
  // Z move by EXX, EYY and -EZZ (u = -x, -y, +z), up to the machine's own slopes and angles times
  // the thermal shift (~1e-4 x 0.06 mm; thermal_table_test measures 5e-6 mm at B = C = 0); not
  // the same computation.
  std::vector<Joints> cold(count);
  for (std::size_t k = 0; k < count; ++k)
    machine::joints_from_world(model, WorldConvention::Axes, t.world[k], t.correction_length_mm[k],
                               machine::Applied{t.gain[k], nullptr}, cold[k]);
  double hand_worst = 0, z_top = 0, step_worst = 0, acceleration_worst = 0, temperature_step = 0;
  for (std::size_t n = 1; n < count; ++n)
    temperature_step = std::max({temperature_step, std::abs(spindle_filtered[n] - spindle_filtered[n - 1]),
                                 std::abs(coolant_filtered[n] - coolant_filtered[n - 1])});
  std::vector<Joints> thermal(count);
  for (std::size_t n = 3; n < count; ++n) {
    thermal[n] = t.joints[n] - trace::interpolated(cold, n);
    const double x = t.joints[n][0], y = t.joints[n][1], tc = coolant_filtered[n - 2], ts = spindle_filtered[n - 2];
    const double per_coolant = tc <= 19   ? (0.4167 / 1) * (19 - tc)
                               : tc <= 25 ? -2.5 * (tc - 19) / 6
                                          : -2.5 - 0.4167 * (tc - 25);
    const double per_y_coolant = tc <= 19   ? 0.35 * (19 - tc)
                                 : tc <= 25 ? -2.1 * (tc - 19) / 6
                                            : -2.1 - 0.35 * (tc - 25);
    const double ezz = ts <= 19 ? 6.7 * (19 - ts) : -60.3 * (ts - 19) / 9;  // um
    const Eigen::Vector3d hand(1e-3 * per_coolant * x / -600, 1e-3 * per_y_coolant * y / -320, -1e-3 * ezz);
    hand_worst = std::max(hand_worst, (thermal[n].head<3>() - hand).cwiseAbs().maxCoeff());
    z_top = std::max(z_top, thermal[n][2]);
    if (n >= 5) {
      step_worst = std::max(step_worst, (thermal[n] - thermal[n - 1]).cwiseAbs().maxCoeff());
      acceleration_worst = std::max(
          acceleration_worst, (thermal[n] - 2 * thermal[n - 1] + thermal[n - 2]).cwiseAbs().maxCoeff() / (dt * dt));
    }
  }
  EXPECT_GT(z_top, 0.050) << "the spindle's growth reached the Z joint";
  EXPECT_LT(hand_worst, 2e-5);
  // Smooth through the ramps and both faults: the thermal share moves per cycle only as far as
  // the filtered temperatures do (at most 6.7 um/K, z_spindle.csv's rate: no jump when a fault
  // starts or ends), and its acceleration stays within the 5 % the INI leaves between axis and
  // joint limits.
  EXPECT_LT(step_worst, 6.7e-3 * temperature_step * 1.01);
  EXPECT_LT(acceleration_worst, 0.05 * test::ini_value(kMc300Ini, "JOINT_2", "MAX_ACCELERATION"));
  std::cout << "mc300 thermal: coolant up to " << coolant_top << " degC, spindle up to " << spindle_top
            << " degC (filtered); faulty readings held for " << nan_samples << " (NaN) + " << out_of_range_samples
            << " (40 degC) samples; thermal share of Z up to " << z_top * 1e3 << " um; against the tables by hand "
            << hand_worst * 1e3 << " um; largest step per cycle " << step_worst * 1e3 << " um (filtered temperature "
            << temperature_step << " K), acceleration " << acceleration_worst << " mm/s^2\n";
}

TEST(Mill3Session, CompensationOnPutsTheRealToolOnTheCommandedPose) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const trace::SessionTrace t = run_session("mill3_on", "kins/configs/mill3/mill3.ini", model, "");
  expect_compensated(trace::check_trace(model, WorldConvention::Axes, t), 0, "mill3, compensation on");
}

// A gantry (kins/configs/mill3/mill3_gantry.ini, coordinates=xyyz: joints 1 and 2 are Y's two
// motors): both Y joints get the core's corrected Y at every sample, and the tool is on the path.
TEST(Mill3Session, AGantrysTwoYJointsBothGetTheCorrectedY) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const std::string ini = "kins/configs/mill3/mill3_gantry.ini";
  const trace::SessionTrace t = run_session("mill3_gantry", ini, model, "");
  expect_compensated(trace::check_trace(model, WorldConvention::Axes, t), 0, "mill3 gantry, compensation on");
  const std::vector<double> y2 =
      test::trace_column(fs::temp_directory_path() / "volcomp-test-runs/mill3_gantry/run/kins/configs/mill3/trace.csv", "y2");
  ASSERT_EQ(y2.size(), t.size());
  for (std::size_t n = 0; n < t.size(); ++n) ASSERT_EQ(y2[n], t.joints[n][1]) << "sample " << n;
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
