// The R-test in a real LinuxCNC session (issue 47): a precision sphere on the table of a TRUE
// MC-300 (its B and C lines off by known amounts) and a nest of three displacement sensors in its
// spindle, simulated by the realtime module simrtest (kins/sim) on the joints LinuxCNC feeds back,
// 0.5 um of noise on each sensor every servo period. The program puts the nest on the sphere at
// 9 poses of B and C (the joints the nominal machine needs for that with the 100 mm tool, computed
// here; X Y Z B C commanded as the MC-300's axes world, G43 H1 adding the tool to Z, as its sample
// programs do) and dwells at each. From the trace: each dwell's
// mean reading; `volcomp identify rtest` on the nominal file must find the true location errors
// within 3 of their standard uncertainties. Then the same program with the compensation on,
// first with the nominal file, then with the identified one. Compensated, the machine should be
// the ideal one, so each pose's reading, turned into the part frame by the ideal machine at the
// commanded pose, gives the sphere's centre there (ISO 10791-6's deviation of the sphere's centre
// in the workpiece frame); the test's figure is how far those centres lie from their mean (the
// sphere's place is the set-up's, not an error: the DRO's X-400 Y-160 Z-200 are the uncompensated
// machine's). It moves the way the truth says: large off, smaller on with the nominal file (its
// tables), at the sensors' noise on with the identified one.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <regex>
#include <sstream>

#include "linuxcnc_run.hpp"
#include "session_checks.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/shop/machine_file_writer.hpp"
#include "vc/acceptance/evaluation_file.hpp"
#include "vc/acceptance/plan_file.hpp"
#include "vc/identify/rtest.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
constexpr double kArcsec = M_PI / 648000.0;

double location(const machine::Model& m, int joint, int component) {
  const machine::Axis& a = m.axes[static_cast<std::size_t>(joint)];
  return component < 3 ? a.location_mm[component] : a.location_rad[component - 3];
}

// One still pose of the trace: the commanded joints and the mean reading over its last 400
// samples (um).
struct Pose {
  machine::Joints joints;
  Eigen::Vector3d reading_um;
};

// The poses where the command stands still for at least 600 samples, the sensors in range.
std::vector<Pose> still_poses(const fs::path& trace) {
  const std::vector<double> columns[9] = {
      test::trace_column(trace, "x"),     test::trace_column(trace, "y"),     test::trace_column(trace, "z"),
      test::trace_column(trace, "b"),     test::trace_column(trace, "c"),     test::trace_column(trace, "dx"),
      test::trace_column(trace, "dy"),    test::trace_column(trace, "dz"),    test::trace_column(trace, "in_range")};
  std::vector<Pose> poses;
  const std::size_t n = columns[0].size();
  std::size_t start = 0;
  for (std::size_t k = 1; k <= n; ++k) {
    bool same = k < n;
    for (int c = 0; c < 5 && same; ++c) same = columns[c][k] == columns[c][start];
    if (same) continue;
    if (k - start >= 600) {
      Pose p;
      p.joints = machine::Joints(5);
      for (int c = 0; c < 5; ++c) p.joints[c] = columns[c][start];
      p.reading_um.setZero();
      bool in_range = true;
      for (std::size_t s = k - 400; s < k; ++s) {
        for (int d = 0; d < 3; ++d) p.reading_um[d] += columns[5 + d][s] / 400.0;
        in_range &= columns[8][s] == 1.0;
      }
      if (in_range) poses.push_back(p);
    }
    start = k;
  }
  return poses;
}

class RTestSession : public ::testing::Test {
 protected:
  // The program (dir/rtest.ngc or `program`), the sensors' HAL file (the sphere where the nest is
  // at the joints `centre`) and the trace, in `dir`; the session run with `file` compensating (or
  // off); the still poses.
  std::vector<Pose> run(const fs::path& dir, const std::string& name, const std::string& compensation_file,
                        fs::path program = {}, const std::string& centre = "-400,-160,-200") {
    if (program.empty()) program = dir / "rtest.ngc";
    const fs::path hal = dir / (name + "_trace.hal");
    std::ofstream(hal) << "# The MC-300 trace with the R-test's sensors (simrtest on the true machine)\n"
                       << "loadrt simrtest machine=" << truth_file_ << " centre=" << centre << " noise_um=0.5 seed=5\n"
                       << "addf simrtest.update servo-thread 1\n"
                       << "net j0 => simrtest.joint.0\nnet j1 => simrtest.joint.1\nnet j2 => simrtest.joint.2\n"
                       << "net j3 => simrtest.joint.3\nnet j4 => simrtest.joint.4\n"
                       << "loadrt sampler depth=8000 cfg=fffffffffffffffb\nsetp sampler.0.enable 0\n"
                       << "net x-cmd axis.x.pos-cmd => sampler.0.pin.0\nnet y-cmd axis.y.pos-cmd => sampler.0.pin.1\n"
                       << "net z-cmd axis.z.pos-cmd => sampler.0.pin.2\nnet b-cmd axis.b.pos-cmd => sampler.0.pin.3\n"
                       << "net c-cmd axis.c.pos-cmd => sampler.0.pin.4\n"
                       << "net j0 => sampler.0.pin.5\nnet j1 => sampler.0.pin.6\nnet j2 => sampler.0.pin.7\n"
                       << "net j3 => sampler.0.pin.8\nnet j4 => sampler.0.pin.9\n"
                       << "net vc-gain => sampler.0.pin.10\nnet vc-tool-offset => sampler.0.pin.11\n"
                       << "net rtest-dx simrtest.dx-um => sampler.0.pin.12\n"
                       << "net rtest-dy simrtest.dy-um => sampler.0.pin.13\n"
                       << "net rtest-dz simrtest.dz-um => sampler.0.pin.14\n"
                       << "net rtest-in-range simrtest.in-range => sampler.0.pin.15\n"
                       << "addf sampler.0 servo-thread\n";
    std::string options = " --program " + program.string() + " --replace-halfile trace.hal=" +
                          hal.string() +
                          " --set 'DRIVER.TRACE_COLUMNS=x y z b c j0 j1 j2 j3 j4 gain tool_offset dx dy dz in_range'";
    if (compensation_file.empty()) {
      options += " --compensation off";
    } else {
      options += " --kinematics 'volkins machine=" + compensation_file + "'";
    }
    const test::CommandResult r =
        test::run_in(dir, "bash " + test::source_path("kins/configs/run_headless.sh") + " " +
                              test::source_path("kins/configs/mc300/mc300.ini") + " " + (dir / name).string() + options,
                     900);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    return still_poses(dir / name / "kins/configs/mc300/trace.csv");
  }

  std::string truth_file_;
};

TEST_F(RTestSession, IdentifiesTheTrueLinesAndTheirCompensationTakesTheReadingsToTheNoise) {
  const fs::path dir = test::run_folder("rtest_session");
  const fs::path src = test::stage_sources(dir);
  const std::string nominal_file = (src / "machines/data/mc300.toml").string();
  const machine::Model model = machine::load_machine(nominal_file);
  const int b = model.joint_of('B'), c = model.joint_of('C');
  const std::vector<shop::LocationValue> changes = {{c, 0, 0.015},  {c, 1, -0.010}, {c, 3, -3 * kArcsec},
                                                    {b, 0, -0.012}, {b, 2, 0.008},  {b, 5, 6 * kArcsec}};
  std::vector<shop::LocationValue> truth_values;
  for (const shop::LocationValue& v : changes)
    truth_values.push_back({v.joint, v.component, location(model, v.joint, v.component) + v.value});
  truth_file_ = shop::write_machine_with_tables(model, (dir / "true").string(), {}, "session test: B and C lines off",
                                                truth_values);
  const machine::Model truth = machine::load_machine(truth_file_);

  // The program: the nominal machine's joints for the nest on the sphere (where the true machine
  // puts the nest at X-400 Y-160 Z-200, B0 C0, read off the DRO at the set-up), dwells of 0.8 s.
  const double L = model.tool_length_mm;
  machine::Joints q0(5);
  q0 << -400, -160, -200, 0, 0;
  const Eigen::Vector3d sphere = machine::tool_pose(model, machine::Machine::Ideal, q0, L).tip_mm;
  std::ofstream program(dir / "rtest.ngc");
  program << "(R-test: the nest on the sphere at 9 poses of B and C, the nominal joints)\nG21 G90 G94 G40\n"
          << "T1 M6\nG43 H1 (the 100 mm tool: the nest's centre)\n";
  int poses = 0;
  for (double bv : {0.0, -45.0, -90.0})
    for (double cv : {0.0, 120.0, 240.0}) {
      machine::Joints world(5), q;
      world << sphere.x(), sphere.y(), sphere.z(), bv, cv;
      ASSERT_EQ(machine::nominal_inverse(model, machine::WorldConvention::Tcp, world, L, q), machine::Status::Ok);
      program << std::fixed << std::setprecision(6) << "G0 X" << q[0] << " Y" << q[1] << " Z" << q[2] - L << " B"
              << q[3] << " C" << q[4] << "\nG4 P0.8\n";
      ++poses;
    }
  program << "M2\n";
  program.close();

  // Compensation off: the readings, identified on the nominal file.
  const std::vector<Pose> off = run(dir, "off", "");
  ASSERT_EQ(off.size(), static_cast<std::size_t>(poses));
  {
    std::ofstream csv(dir / "rtest.csv");
    csv << "x,y,z,b,c,dx[um],dy[um],dz[um]\n" << std::setprecision(12);
    for (const Pose& p : off)
      csv << p.joints[0] << ',' << p.joints[1] << ',' << p.joints[2] << ',' << p.joints[3] << ',' << p.joints[4] << ','
          << p.reading_um.x() << ',' << p.reading_um.y() << ',' << p.reading_um.z() << '\n';
  }
  const test::CommandResult r =
      test::run_volcomp("identify rtest " + nominal_file + " " + (dir / "rtest.csv").string() +
                        " --deviations EX0C,EY0C,EA0C,EX0B,EZ0B,EA0B,EC0B --machine-out " + (dir / "identified").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::cout << r.out;
  EXPECT_NE(r.out.find("7 of 7 location errors identified"), std::string::npos) << r.out;
  const std::regex row(R"(\s+(E[XYZABC]0[BC]) = (-?[0-9.]+) (um|arcsec) \+- ([0-9.]+) (um|arcsec) .*)");
  const std::map<std::string, std::pair<int, int>> where = {{"EX0C", {c, 0}}, {"EY0C", {c, 1}}, {"EA0C", {c, 3}},
                                                            {"EX0B", {b, 0}}, {"EZ0B", {b, 2}}, {"EA0B", {b, 3}},
                                                            {"EC0B", {b, 5}}};
  std::istringstream out(r.out);
  int found = 0;
  for (std::string line; std::getline(out, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    ++found;
    const auto [joint, component] = where.at(m[1]);
    const double scale = component < 3 ? 1e3 : 1 / kArcsec;
    const double value = std::stod(m[2]), uncertainty = std::stod(m[4]), t = location(truth, joint, component) * scale;
    EXPECT_GT(uncertainty, 0.0) << m[1];
    EXPECT_LE(std::abs(value - t), 3 * uncertainty) << m[1] << " " << value << " +- " << uncertainty << ", truth " << t;
  }
  EXPECT_EQ(found, 7) << r.out;

  // Compensation on, nominal file, then identified file: the sphere's centres in the part frame
  // (the ideal machine at the commanded pose, the reading turned by it), their largest distance
  // from their mean.
  const auto largest = [&](const std::vector<Pose>& ps) {
    std::vector<Eigen::Vector3d> centres;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Pose& p : ps) {
      // The recorded axes are the joints the program commanded (G43's 100 mm in Z included).
      const Eigen::Isometry3d nest = machine::part_T_tool(model, machine::Machine::Ideal, p.joints, L);
      centres.push_back(nest.translation() + nest.linear() * p.reading_um * 1e-3);
      mean += centres.back() / static_cast<double>(ps.size());
    }
    double m = 0;
    for (const Eigen::Vector3d& centre : centres) m = std::max(m, (centre - mean).norm() * 1e3);
    return m;
  };
  const std::vector<Pose> nominal_on = run(dir, "nominal_on", nominal_file);
  const std::vector<Pose> identified_on = run(dir, "identified_on", (dir / "identified/mc300.toml").string());
  ASSERT_EQ(nominal_on.size(), off.size());
  ASSERT_EQ(identified_on.size(), off.size());
  std::cout << "R-test, the sphere's centre in the part frame, largest distance from its mean over " << poses
            << " poses: compensation off " << largest(off)
            << " um, on with the nominal file " << largest(nominal_on) << " um, on with the identified file "
            << largest(identified_on) << " um\n";
  EXPECT_GT(largest(off), 10.0);
  EXPECT_GT(largest(nominal_on), 10.0) << "the nominal file does not know the lines";
  EXPECT_LT(largest(identified_on), 0.3 * largest(nominal_on));
  EXPECT_LT(largest(identified_on), 0.5) << "the sensors' noise, 0.5 um a sample, averaged over 400";
}

// `volcomp acceptance plan`'s R-test (rtest/rtest.ngc, unchanged) in a session on the true MC-300,
// compensation off: it runs clean, dwells at each planned pose at the plan's joints, and the
// sensors read there what `acceptance simulate` says they read (its own code path: identify's
// rtest_reading on the true file), within their averaged noise; `acceptance evaluate` of the
// session's readings gives simulate's figures.
TEST_F(RTestSession, ThePlansRTestRunsAndItsSensorsReadWhatSimulateSays) {
  const fs::path dir = test::run_folder("rtest_plan_session");
  const fs::path src = test::stage_sources(dir);
  const std::string nominal_file = (src / "machines/data/mc300.toml").string();
  const machine::Model model = machine::load_machine(nominal_file);
  const int b = model.joint_of('B'), c = model.joint_of('C');
  truth_file_ = shop::write_machine_with_tables(
      model, (dir / "true").string(), {}, "session test: B and C lines off",
      {{c, 0, location(model, c, 0) + 0.015}, {b, 0, location(model, b, 0) - 0.012}});
  const std::string plan = (dir / "plan").string();
  test::CommandResult r = test::run_volcomp("acceptance plan " + nominal_file + " -o " + plan +
                                            " --diagonals none --axis-runs none --circles none --rtest-steps 6"
                                            " --dwell 0.8 --feed 3000");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const acceptance::Plan p = acceptance::read_plan(plan);
  std::vector<machine::Joints> planned;
  for (const acceptance::RTestSequence& q : p.rtest.sequences) planned.insert(planned.end(), q.poses.begin(), q.poses.end());
  ASSERT_GE(planned.size(), 6u);
  std::ostringstream centre;
  centre << std::setprecision(12) << p.rtest.sphere_joints_mm.x() << ',' << p.rtest.sphere_joints_mm.y() << ','
         << p.rtest.sphere_joints_mm.z();
  const std::vector<Pose> session = run(dir, "plan_off", "", dir / "plan" / acceptance::kRTestProgram, centre.str());
  ASSERT_EQ(session.size(), planned.size());
  r = test::run_volcomp("acceptance simulate " + plan + " --true " + truth_file_ + " -o " + (dir / "simulated").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::vector<identify::RTestReading> simulated =
      identify::read_rtest_readings((dir / "simulated" / acceptance::kRTestMeasurements).string(), model);
  ASSERT_EQ(simulated.size(), planned.size());
  fs::create_directories(dir / "session_readings");
  std::ofstream csv(dir / "session_readings" / acceptance::kRTestMeasurements);
  csv << "x,y,z,b,c,dx[um],dy[um],dz[um]\n" << std::setprecision(12);
  double largest = 0;
  for (std::size_t k = 0; k < planned.size(); ++k) {
    EXPECT_LT((session[k].joints - planned[k]).cwiseAbs().maxCoeff(), 1e-6) << "pose " << k + 1;
    largest = std::max(largest, (session[k].reading_um - simulated[k].deviation_mm * 1e3).norm());
    for (int j = 0; j < 5; ++j) csv << session[k].joints[j] << ',';
    csv << session[k].reading_um.x() << ',' << session[k].reading_um.y() << ',' << session[k].reading_um.z() << '\n';
  }
  csv.close();
  std::cout << "the plan's R-test in LinuxCNC: " << planned.size() << " poses, the sensors against simulate's readings "
            << largest << " um at most\n";
  EXPECT_LT(largest, 0.2) << "the sensors' noise, 0.5 um a sample averaged over 400";
  // The figures of both, through evaluate.
  std::map<std::string, acceptance::Evaluation> results;
  for (const char* name : {"simulated", "session_readings"}) {
    r = test::run_volcomp("acceptance evaluate " + plan + " --measurements " + (dir / name).string() + " --machine " +
                          nominal_file + " -o " + (dir / (std::string(name) + "_report")).string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    results[name] = acceptance::read_evaluation((dir / (std::string(name) + "_report.csv")).string());
  }
  ASSERT_EQ(results["simulated"].rows.size(), results["session_readings"].rows.size());
  for (std::size_t k = 0; k < results["simulated"].rows.size(); ++k) {
    const acceptance::EvaluationRow &a = results["simulated"].rows[k], &s = results["session_readings"].rows[k];
    EXPECT_EQ(a.test + a.figure, s.test + s.figure);
    EXPECT_NEAR(a.value, s.value, 0.3) << a.test << " " << a.figure;
    if (a.figure == "D") std::cout << a.test << ": D " << s.value << " um in LinuxCNC, " << a.value << " um simulated\n";
  }
}

}  // namespace
}  // namespace vc
