// Rotary axes' location errors from a probed sphere, on a simulated MC-300 whose B and C lines
// are off (the truth): the probe's measurements are made by solving the true machine for the
// joints that put the tip on the sphere's centre (a Newton solve in this test, not the
// identification's code), with 1 um of noise. The fit must find what the poses can separate
// within 3 of its standard uncertainties, name what they cannot (the C line's shift along
// itself and its turn about itself look like the sphere elsewhere on the table), and refuse a
// plan at one pose. On an AC trunnion and a head-table machine (bc_head) the identified machine
// must explain poses it was not fitted to.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <regex>
#include <sstream>
#include <iostream>
#include <random>

#include "test_support.hpp"
#include "tip_on_point.hpp"
#include "vc/identify/sphere_centres.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::identify {
namespace {

constexpr double kArcsec = M_PI / 648000.0;

void offset(machine::Model& m, char axis, int component, double by) {
  machine::Axis& a = m.axes[static_cast<std::size_t>(m.joint_of(axis))];
  (component < 3 ? a.location_mm[component] : a.location_rad[component - 3]) += by;
  a.real_base = machine::line_placement(a.pole_mm, a.location_mm, a.location_rad);
}

// The joints X Y Z at rotary positions (tilt = b, C = c) that put the true machine's tip on `centre`.
machine::Joints probed(const machine::Model& truth, char tilt, double b, double c, const Eigen::Vector3d& centre,
                       double length) {
  machine::Joints q = machine::Joints::Zero(truth.joint_count());
  q[truth.joint_of(tilt)] = b;
  q[truth.joint_of('C')] = c;
  for (char axis : {'X', 'Y', 'Z'}) {
    const machine::Axis& a = truth.axes[static_cast<std::size_t>(truth.joint_of(axis))];
    q[truth.joint_of(axis)] = (a.travel_min + a.travel_max) / 2;
  }
  return test::tip_on_point(truth, machine::Machine::Real, q, centre, length);
}

std::vector<SpherePose> plan(const machine::Model& truth, const std::vector<double>& bs, const std::vector<double>& cs,
                             unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, 1e-3);  // 1 um
  const Eigen::Vector3d centre(30, -20, 40);
  std::vector<SpherePose> poses;
  for (double b : bs)
    for (double c : cs) {
      SpherePose p;
      p.joints = probed(truth, 'B', b, c, centre, truth.tool_length_mm);
      for (char a : {'X', 'Y', 'Z'}) p.joints[truth.joint_of(a)] += noise(random);
      poses.push_back(p);
    }
  return poses;
}

TEST(SphereCentres, FindsTheRotaryLinesWithinTheirUncertainty) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  machine::Model truth = model;
  offset(truth, 'C', 0, 0.015);         // EX0C +15 um
  offset(truth, 'C', 1, -0.010);        // EY0C -10 um
  offset(truth, 'C', 3, -3 * kArcsec);  // EA0C
  offset(truth, 'C', 4, 4 * kArcsec);   // EB0C
  offset(truth, 'B', 0, -0.012);        // EX0B
  offset(truth, 'B', 2, 0.008);         // EZ0B
  offset(truth, 'B', 5, 6 * kArcsec);   // EC0B
  const std::vector<SpherePose> poses = plan(truth, {0, -30, -60, -90}, {0, 60, 120, 180, 240, 300}, 3);
  const SphereFit fit = identify_from_sphere(model, poses, {}, model.tool_length_mm);
  const auto flagged = [&](const std::string& s) {
    const auto it =
        std::find_if(fit.not_separable.begin(), fit.not_separable.end(), [&](const auto& n) { return n.symbol == s; });
    return it == fit.not_separable.end() ? nullptr : &*it;
  };
  // Along and about C's own line: the sphere elsewhere on the table.
  for (const std::string s : {"EZ0C", "EC0C"}) {
    ASSERT_NE(flagged(s), nullptr) << s;
    ASSERT_FALSE(flagged(s)->with.empty()) << s;
    EXPECT_EQ(flagged(s)->with.front(), "the sphere's position") << s;
  }
  // C's line tilted about Y and B's line turned about itself (Y) are both turns about Y
  // between the bed and the table: only their sum is seen, carried by the one kept.
  const NotSeparable* about_y = flagged("EB0C") ? flagged("EB0C") : flagged("EB0B");
  ASSERT_NE(about_y, nullptr);
  EXPECT_NE(std::find(about_y->with.begin(), about_y->with.end(), about_y->symbol == "EB0C" ? "EB0B" : "EB0C"),
            about_y->with.end());
  EXPECT_GT(fit.rms_before_um, 10.0);
  EXPECT_LT(fit.rms_after_um, 3.0);  // the noise: 1 um in each of x y z
  for (const LocationEstimate& e : fit.estimates) {
    const machine::Axis& a = truth.axes[static_cast<std::size_t>(e.joint)];
    double truth_value = e.component < 3 ? a.location_mm[e.component] : a.location_rad[e.component - 3];
    if (e.symbol == "EB0B" || e.symbol == "EB0C")  // the sum of the pair, less the model's other one
      truth_value += truth.axes[truth.joint_of(e.symbol == "EB0B" ? 'C' : 'B')].location_rad[1] -
                     model.axes[model.joint_of(e.symbol == "EB0B" ? 'C' : 'B')].location_rad[1];
    EXPECT_LE(std::abs(e.value - truth_value), 3 * e.uncertainty)
        << e.symbol << " " << e.value << " +- " << e.uncertainty << " truth " << truth_value;
    EXPECT_GT(e.uncertainty, 0.0);
  }
  EXPECT_GE(fit.estimates.size(), 6u);
}

// The same on the other kinds of 5-axis machine: an AC trunnion (A tilting the table, C on it)
// and a head-table machine (B swivelling the head, C turning the table). Whatever the poses
// cannot separate, the identified machine must explain the truth: at poses it was not fitted
// to, its tip at the joints that put the true tip on the sphere's centre stays on one point.
struct OtherKind {
  std::string path;
  char tilt;                  // the first rotary axis
  std::vector<double> tilts;  // its probed positions
};

class SphereCentresOn : public ::testing::TestWithParam<OtherKind> {};

TEST_P(SphereCentresOn, TheIdentifiedMachineExplainsPosesItWasNotFittedTo) {
  const OtherKind& kind = GetParam();
  const machine::Model model = machine::load_machine(kind.path);
  machine::Model truth = model;
  offset(truth, 'C', 0, 0.015);
  offset(truth, 'C', 1, -0.010);
  offset(truth, 'C', 3, -3 * kArcsec);
  offset(truth, kind.tilt, 1, 0.012);
  offset(truth, kind.tilt, 2, -0.008);
  offset(truth, kind.tilt, 5, 5 * kArcsec);
  const auto poses_at = [&](const std::vector<double>& tilts, const std::vector<double>& cs, unsigned seed) {
    std::mt19937 random(seed);
    std::normal_distribution<double> noise(0.0, 1e-3);  // 1 um
    std::vector<SpherePose> poses;
    for (double t : tilts)
      for (double c : cs) {
        SpherePose p;
        p.joints = probed(truth, kind.tilt, t, c, Eigen::Vector3d(30, -20, 40), truth.tool_length_mm);
        for (char a : {'X', 'Y', 'Z'}) p.joints[truth.joint_of(a)] += noise(random);
        poses.push_back(p);
      }
    return poses;
  };
  const SphereFit fit =
      identify_from_sphere(model, poses_at(kind.tilts, {0, 60, 120, 180, 240, 300}, 5), {}, model.tool_length_mm);
  EXPECT_GT(fit.rms_before_um, 5.0);
  EXPECT_LT(fit.rms_after_um, 3.0);
  machine::Model identified = model;
  for (const LocationEstimate& e : fit.estimates)
    offset(identified, model.axes[e.joint].letter, e.component, e.value - e.before);
  // Poses between the fitted ones, without noise: the tips' spread about their mean.
  std::vector<double> between;
  for (std::size_t i = 0; i + 1 < kind.tilts.size(); ++i) between.push_back((kind.tilts[i] + kind.tilts[i + 1]) / 2);
  const std::vector<SpherePose> check = [&] {
    std::vector<SpherePose> poses;
    for (double t : between)
      for (double c : {30.0, 150.0, 270.0}) {
        SpherePose p;
        p.joints = probed(truth, kind.tilt, t, c, Eigen::Vector3d(30, -20, 40), truth.tool_length_mm);
        poses.push_back(p);
      }
    return poses;
  }();
  const auto spread_um = [&](const machine::Model& m) {
    std::vector<Eigen::Vector3d> tips;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const SpherePose& p : check) {
      tips.push_back(machine::tool_pose(m, machine::Machine::Real, p.joints, m.tool_length_mm).tip_mm);
      mean += tips.back() / static_cast<double>(check.size());
    }
    double worst = 0;
    for (const Eigen::Vector3d& t : tips) worst = std::max(worst, (t - mean).norm() * 1e3);
    return worst;
  };
  EXPECT_GT(spread_um(model), 10.0);
  EXPECT_LT(spread_um(identified), 2.0) << "nominal " << spread_um(model);
  std::cout << "spread " << spread_um(model) << " -> " << spread_um(identified) << " um\n";
}

INSTANTIATE_TEST_SUITE_P(Kinds, SphereCentresOn,
                         ::testing::Values(OtherKind{test::machine_path("ac_trunnion"), 'A', {0, -30, -60, -90}},
                                           OtherKind{test::source_path("tests/unit/machines/data/bc_head.toml"),
                                                     'B',
                                                     {-60, -30, 0, 30, 60}}));

// The uncertainty is honest: over 100 noise draws, the truth lies within 2 standard
// uncertainties of the estimate in about 95 % of the cases (every estimate of every draw).
TEST(SphereCentres, UncertaintyCoversTheTruthAsItSays) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  machine::Model truth = model;
  offset(truth, 'C', 0, 0.015);  // (only errors among those identified: an error left out would bias the rest)
  offset(truth, 'C', 3, 4 * kArcsec);
  offset(truth, 'B', 2, 0.008);
  int within = 0, total = 0;
  for (unsigned seed = 0; seed < 100; ++seed) {
    const SphereFit fit =
        identify_from_sphere(model, plan(truth, {0, -45, -90}, {0, 90, 180, 270}, 100 + seed),
                             {"EX0C", "EY0C", "EA0C", "EX0B", "EZ0B", "EA0B", "EC0B"}, model.tool_length_mm);
    for (const LocationEstimate& e : fit.estimates) {
      const machine::Axis& a = truth.axes[static_cast<std::size_t>(e.joint)];
      const double t = e.component < 3 ? a.location_mm[e.component] : a.location_rad[e.component - 3];
      within += std::abs(e.value - t) <= 2 * e.uncertainty;
      ++total;
    }
  }
  const double share = static_cast<double>(within) / total;
  std::cout << "truth within 2 standard uncertainties: " << within << " of " << total << "\n";
  EXPECT_GT(share, 0.90) << within << " of " << total;
  EXPECT_LT(share, 0.99) << within << " of " << total;
}

// Through the command line: a CSV of probed centres in, a machine file with the values out.
TEST(SphereCentres, CommandLineWritesAMachineFileThatLoads) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  machine::Model truth = model;
  offset(truth, 'C', 0, 0.020);  // EX0C +20 um
  std::ostringstream csv;
  csv << "x,y,z,b,c\n";
  for (const SpherePose& p : plan(truth, {0, -45, -90}, {0, 90, 180, 270}, 9)) {
    for (int j = 0; j < model.joint_count(); ++j) csv << (j ? "," : "") << std::setprecision(12) << p.joints[j];
    csv << '\n';
  }
  const auto dir = std::filesystem::temp_directory_path() / ("vc_sphere_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string centres = (dir / "centres.csv").string();
  std::ofstream(centres) << csv.str();
  const auto r = test::run_volcomp("identify sphere " + test::machine_path("mc300") + " " + centres +
                                   " --deviations EX0C,EY0C,EA0C --machine-out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("3 of 3 location errors identified"), std::string::npos) << r.out;
  const machine::Model written = machine::load_machine((dir / "out" / "mc300.toml").string());
  EXPECT_NEAR(written.axes[written.joint_of('C')].location_mm[0], 0.020, 0.002);
  // The standard uncertainty printed goes into the written line's comment, in the key's unit
  // (EX0C_mm: mm), where the report's "where from" shows it.
  std::smatch printed, in_file;
  ASSERT_TRUE(
      std::regex_search(r.out, printed, std::regex(R"(EX0C = [-0-9.]+ um \+- ([0-9.]+) um \(standard uncertainty)")))
      << r.out;
  const std::string text = test::file_text(dir / "out" / "mc300.toml");
  ASSERT_TRUE(std::regex_search(text, in_file, std::regex(R"(EX0C_mm = .*\+- ([0-9.]+) mm \(standard uncertainty\))")))
      << text;
  EXPECT_NEAR(std::stod(in_file[1]) * 1e3, std::stod(printed[1]), 0.006);
  std::filesystem::remove_all(dir);
}

// The probing loop without the machine: probe-plan's program runs clean in LinuxCNC's own
// interpreter; a log as that program writes it, of probe trips on the true machine's sphere
// (5 per pose, 25 mm sphere, 2 mm ball), gives the centres and the location errors back; a
// log with the wrong sphere diameter or of another machine is refused with its line.
TEST(SphereCentres, ProbePlanAndItsLogCloseTheLoop) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const auto dir = std::filesystem::temp_directory_path() / ("vc_probe_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string program = (dir / "plan.ngc").string();
  auto r = test::run_volcomp("probe-plan " + test::machine_path("mc300") +
                             " --centre -300,-160,-200 --grid B=0,-45,-90 --grid C=0,90,180,270 -o " + program);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::string rs274 =
      "cd " + dir.string() + " && HOME=" + dir.string() + " rs274 -g plan.ngc < /dev/null > rs274.out 2>&1";
  EXPECT_EQ(std::system(rs274.c_str()), 0);
  std::ifstream rs274_out(dir / "rs274.out");
  const std::string canon((std::istreambuf_iterator<char>(rs274_out)), std::istreambuf_iterator<char>());
  EXPECT_EQ(canon.find("rror"), std::string::npos) << canon.substr(0, 2000);
  EXPECT_NE(canon.find("STRAIGHT_PROBE"), std::string::npos);

  machine::Model truth = model;
  offset(truth, 'C', 0, 0.015);
  offset(truth, 'C', 3, 4 * kArcsec);
  offset(truth, 'B', 2, 0.008);
  const double reach = (25.0 + 2.0) / 2;
  const auto write_log = [&](const std::string& name, double reach_written, const std::string& axes) {
    std::ofstream log(dir / name);
    log << "# volcomp probe log: sphere_diameter_mm 25.0000 ball_diameter_mm 2.0000 probe_length_mm 100.0000 axes "
        << axes << "\n";
    int pose = 0;
    for (const SpherePose& p : plan(truth, {0, -45, -90}, {0, 90, 180, 270}, 21)) {
      ++pose;
      const Eigen::Vector3d c(p.joints[0], p.joints[1], p.joints[2]);
      for (const Eigen::Vector3d& d : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0, 0),
                                       Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, -1, 0)}) {
        // Where the true machine's ball touches the sphere on the joints' line c + s d (the
        // linear axes' errors make s differ from the reach by up to a few um).
        const Eigen::Vector3d sphere = machine::tool_pose(truth, machine::Machine::Real, p.joints, 100.0).tip_mm;
        const auto gap = [&](double s) {
          // (built from zeros: a copy of p.joints made GCC warn falsely under the profile)
          machine::Joints q = machine::Joints::Zero(p.joints.size());
          q += p.joints;
          q.head<3>() += s * d;
          return (machine::tool_pose(truth, machine::Machine::Real, q, 100.0).tip_mm - sphere).norm() - reach_written;
        };
        double s = reach_written;
        for (int step = 0; step < 20; ++step) s -= gap(s) / ((gap(s + 1e-4) - gap(s - 1e-4)) / 2e-4);
        const Eigen::Vector3d trip = c + s * d;  // (G54 offsets zero)
        log << "POINT " << pose << std::fixed << std::setprecision(6) << " " << p.joints[3] << " " << p.joints[4] << " "
            << trip.x() << " " << trip.y() << " " << trip.z() << " 0.000000 0.000000 0.000000\n";
      }
    }
    return (dir / name).string();
  };
  r = test::run_volcomp("identify sphere " + test::machine_path("mc300") + " " + write_log("good.txt", reach, "xyzbc") +
                        " --deviations EX0C,EY0C,EA0C,EX0B,EZ0B,EA0B,EC0B --machine-out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  // The trips lie on the sphere in the part frame: with the model's linear axes taken into
  // account they fit it to the noise of the centres' solve (in the joints: 1.7 um off).
  EXPECT_NE(r.out.find("probe log: 12 poses, sphere 25 mm, ball 2 mm; the points lie within 0.0"), std::string::npos)
      << r.out;
  const machine::Model written = machine::load_machine((dir / "out" / "mc300.toml").string());
  EXPECT_NEAR(written.axes[written.joint_of('C')].location_mm[0], truth.axes[truth.joint_of('C')].location_mm[0],
              0.002);
  EXPECT_NEAR(written.axes[written.joint_of('B')].location_mm[2], truth.axes[truth.joint_of('B')].location_mm[2],
              0.002);

  r = test::run_volcomp("identify sphere " + test::machine_path("mc300") + " " +
                        write_log("wrong.txt", reach + 0.5, "xyzbc"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("off the sphere of diameter"), std::string::npos) << r.out;
  r = test::run_volcomp("identify sphere " + test::machine_path("mc300") + " " +
                        write_log("other.txt", reach, "xyzac"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("other.txt:1: error: the log is of a machine with axes xyzac"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

TEST(SphereCentres, APlanAtOnePoseIsRefusedNotFitted) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const std::vector<SpherePose> poses = plan(model, {-30}, {120}, 4);
  std::vector<SpherePose> three(3, poses.front());
  EXPECT_THROW(
      {
        try {
          identify_from_sphere(model, three, {}, model.tool_length_mm);
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find("cannot identify any"), std::string::npos) << e.what();
          throw;
        }
      },
      std::runtime_error);
}

}  // namespace
}  // namespace vc::identify
