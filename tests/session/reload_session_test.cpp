// A new machine file made active in a running LinuxCNC (volkins.reload, M100; issue 46): one
// headless mill3 session runs job 1 with mill3's file, the test's M101 copies a perturbed file
// (volcomp perturb) over the active one and pulses volkins.reload while the next move runs
// (refused: an axis moves), M100 reloads at rest, and job 2 runs with the new file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>

#include "linuxcnc_run.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/trace/session_trace.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
using machine::Joints;

const std::string kMill3Ini = "kins/configs/mill3/mill3.ini";

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Column `name` of a trace CSV.
std::vector<double> trace_column(const std::string& path, const std::string& name) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  for (std::stringstream h(line); std::getline(h, line, ',');) header.push_back(line);
  const auto at = std::find(header.begin(), header.end(), name) - header.begin();
  EXPECT_LT(at, static_cast<long>(header.size())) << name;
  std::vector<double> values;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (long k = 0; k <= at; ++k) std::getline(row, cell, ',');
    values.push_back(std::stod(cell));
  }
  return values;
}

// Job 1 is the core's correction of the file loaded, job 2 that of the new file (to 1e-6 mm at
// every sample; the ramps included: the trace's gain is the enable's times the reload's); the
// joints stay within the INI's velocity and acceleration at every sample, the reload's ramps
// included; the request while moving is refused (its message, reload-failed, nothing swapped).
TEST(ReloadSession, M100SwapsThePerturbedFileAtRestAndARequestWhileMovingIsRefused) {
  const fs::path dir = test::run_folder("reload_session");
  // mill3's file and tables in one folder (rtapi_app, another uid, reads them there).
  fs::create_directories(dir / "orig");
  const std::string mill3 = text_of(test::machine_path("mill3"));
  for (const char* t : {"x.csv", "y.csv", "z.csv", "z_by_y.csv"})
    fs::copy_file(test::source_path(std::string("tables/data/mill3/") + t), dir / "orig" / t);
  std::ofstream(dir / "orig/mill3.toml") << std::regex_replace(mill3, std::regex("\\.\\./\\.\\./tables/data/mill3/"), "");
  const test::CommandResult perturb = test::run_in(
      dir, std::string(VC_VOLCOMP) + " perturb " + (dir / "orig/mill3.toml").string() + " -o " + (dir / "true").string() +
               " --seed 5");
  ASSERT_EQ(perturb.exit_code, 0) << perturb.out;
  // The active file: mill3's, beside the perturbed one (whose table paths are relative to it).
  std::ofstream(dir / "true/active.toml")
      << std::regex_replace(mill3, std::regex("\\.\\./\\.\\./tables/data/mill3/"), (dir / "orig").string() + "/");
  fs::create_directories(dir / "mcodes");
  std::ofstream(dir / "mcodes/M101") << "#!/bin/bash\ncp " << (dir / "true/mill3.toml").string() << " "
                                     << (dir / "true/active.toml").string()
                                     << "\nsetsid bash -c 'sleep 1; halcmd setp volkins.reload 1' "
                                        "</dev/null >/dev/null 2>&1 &\n";
  fs::permissions(dir / "mcodes/M101", fs::perms::all);
  for (const auto& e : fs::recursive_directory_iterator(dir)) fs::permissions(e.path(), fs::perms::all);
  const machine::Model before = machine::load_machine((dir / "true/active.toml").string());
  const machine::Model after = machine::load_machine((dir / "true/mill3.toml").string());

  const test::CommandResult r = test::run_in(
      dir,
      "bash " + test::source_path("kins/configs/run_headless.sh") + " " + test::source_path(kMill3Ini) + " " +
          (dir / "run").string() + " --kinematics 'volkins machine=" + (dir / "true/active.toml").string() +
          " coordinates=xyz world=axes' --program " + test::source_path("tests/session/programs/mill3_reload.ngc") +
          " --set RS274NGC.USER_M_PATH=../common:" + (dir / "mcodes").string() + " --replace-halfile trace.hal=" +
          test::source_path("tests/session/trace_reload.hal") +
          " --set 'DRIVER.TRACE_COLUMNS=x y z j0 j1 j2 gain tool_offset controller_time correction_length reloads "
          "reload_state reload_failed' --expect-message 'reload refused while an axis moves' --add DRIVER.TIMEOUT=120",
      900);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::string trace_path = (dir / "run/kins/configs/mill3/trace.csv").string();
  const trace::SessionTrace t = trace::read_session_trace(trace_path, before);
  const std::vector<double> reloads = trace_column(trace_path, "reloads"), state = trace_column(trace_path, "reload_state"),
                            failed = trace_column(trace_path, "reload_failed");
  ASSERT_GT(t.size(), 5000u);
  ASSERT_EQ(reloads.size(), t.size());

  // The refused request: reload-failed while the axes move, nothing swapped yet.
  std::size_t refused_moving = 0;
  for (std::size_t k = 1; k < t.size(); ++k)
    refused_moving += failed[k] == 1.0 && reloads[k] == 0.0 && (t.world[k] - t.world[k - 1]).norm() > 0;
  EXPECT_GT(refused_moving, 100u) << "reload-failed while moving";
  // One reload, through the states in order, at rest.
  EXPECT_EQ(reloads.back(), 1.0);
  std::vector<int> sequence;
  for (double s : state)
    if (sequence.empty() || sequence.back() != static_cast<int>(s)) sequence.push_back(static_cast<int>(s));
  // The refused request (1 -> 0 while moving), then M100's (1, 2, 3, 0).
  EXPECT_EQ(sequence, (std::vector<int>{0, 1, 0, 1, 2, 3, 0}));
  EXPECT_EQ(failed.back(), 0.0);
  double moved_while_reloading = 0, joint_speed_reloading = 0;
  std::size_t reloading = 0;
  for (std::size_t k = 1; k < t.size(); ++k)
    if (state[k] == 2.0 || state[k] == 3.0) {  // the ramps
      ++reloading;
      moved_while_reloading = std::max(moved_while_reloading, (t.world[k] - t.world[k - 1]).norm());
      joint_speed_reloading = std::max(joint_speed_reloading, (t.joints[k] - t.joints[k - 1]).cwiseAbs().maxCoeff() / 1e-3);
    }
  EXPECT_EQ(moved_while_reloading, 0.0) << "the commanded position rests during the ramps";
  EXPECT_GT(reloading, 1500u) << "two ramps of ramp-time 1 s";

  // Each sample against the core with the file active then.
  const trace::TraceSummary old_file = trace::check_trace(before, machine::WorldConvention::Axes, t);
  const trace::TraceSummary new_file = trace::check_trace(after, machine::WorldConvention::Axes, t);
  ASSERT_EQ(old_file.samples.size(), new_file.samples.size());
  double job1 = 0, job2 = 0, job2_against_old = 0;
  std::size_t n1 = 0, n2 = 0;
  for (std::size_t i = 0; i < old_file.samples.size(); ++i) {
    const std::size_t k = old_file.samples[i].sample;
    if (reloads[k] == 0.0) {
      job1 = std::max(job1, old_file.samples[i].module_mismatch);
      ++n1;
    } else {
      job2 = std::max(job2, new_file.samples[i].module_mismatch);
      if (t.gain[k] == 1.0) job2_against_old = std::max(job2_against_old, old_file.samples[i].module_mismatch);
      ++n2;
    }
  }
  EXPECT_GT(n1, 2000u);
  EXPECT_GT(n2, 2000u);
  EXPECT_LT(job1, 1e-6) << "mm: job 1 against mill3's file";
  EXPECT_LT(job2, 1e-6) << "mm: job 2 against the new file";
  EXPECT_GT(job2_against_old, 1e-4) << "mm: the new file's correction is not the old one's (the test could fail)";

  // No jump: every sample within the joints' limits, by finite differences at 1 ms.
  for (int j = 0; j < 3; ++j) {
    const std::string section = "JOINT_" + std::to_string(j);
    double v = 0, a = 0;
    for (std::size_t n = 9; n + 1 < t.size(); ++n) {
      v = std::max(v, std::abs(t.joints[n + 1][j] - t.joints[n][j]) / 1e-3);
      a = std::max(a, std::abs(t.joints[n + 1][j] - 2 * t.joints[n][j] + t.joints[n - 1][j]) / 1e-6);
    }
    EXPECT_LE(v, test::ini_value(kMill3Ini, section, "MAX_VELOCITY")) << section;
    EXPECT_LE(a, test::ini_value(kMill3Ini, section, "MAX_ACCELERATION")) << section;
    std::cout << section << ": peak velocity " << v << " mm/s, peak acceleration " << a << " mm/s^2\n";
  }
  std::cout << t.size() << " samples; job 1 module-core " << job1 << " mm (" << n1 << "), job 2 against the new file "
            << job2 << " mm (" << n2 << "), against the old one " << job2_against_old << " mm; " << reloading
            << " samples reloading, joint speed then up to " << joint_speed_reloading << " mm/s; " << refused_moving
            << " samples refused while moving\n";
}

}  // namespace
}  // namespace vc
