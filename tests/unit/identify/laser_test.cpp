// Laser runs and their ISO 230-2 evaluation: a case worked by hand, a simulated axis whose
// positioning error the evaluation must recover within the noise, the suspicious runs it must
// find (a reversed sign, another unit, a disturbed run), and bad files refused with
// file:line:column.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "test_support.hpp"
#include "vc/identify/iso230_2.hpp"
#include "vc/identify/laser_runs.hpp"
#include "vc/tables/load_table.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::identify {
namespace {

namespace fs = std::filesystem;

std::string write(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("vc_laser_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << text;
  return p.string();
}

TEST(Iso230_2, CaseWorkedByHand) {
  // Two targets, two runs each way (um): target 0: up 1, 3; down -1, 1; target 100: up 2, 2;
  // down 0, 4. By hand: means up 2, 2, down 0, 2, bidirectional 1, 2; s up sqrt2, 0, down
  // sqrt2, 2 sqrt2; B_i 2, 0; R_i max(4 sqrt2 + 2, 4 sqrt2, 4 sqrt2) = 7.657,
  // max(4 sqrt2, 0, 8 sqrt2) = 11.314; E = 2 - 0; M = 2 - 1; A = (2 + 4 sqrt2) - (2 - 4 sqrt2) = 11.314.
  const std::string path = write("hand.csv",
                                 "target[mm],run,direction,deviation[um]\n"
                                 "0,1,+,1\n100,1,+,2\n100,1,-,0\n0,1,-,-1\n"
                                 "0,2,up,3\n100,2,up,2\n100,2,down,4\n0,2,down,1\n");
  const Iso230_2 e = evaluate_iso230_2(read_laser_runs(path));
  const double r2 = std::sqrt(2.0);
  ASSERT_EQ(e.targets.size(), 2u);
  EXPECT_NEAR(e.targets[0].mean_up, 2e-3, 1e-12);
  EXPECT_NEAR(e.targets[0].mean_down, 0.0, 1e-12);
  EXPECT_NEAR(e.targets[1].mean, 2e-3, 1e-12);
  EXPECT_NEAR(e.targets[1].s_down, 2 * r2 * 1e-3, 1e-12);
  EXPECT_NEAR(e.reversal, 2e-3, 1e-12);
  EXPECT_NEAR(e.mean_reversal, 1e-3, 1e-12);
  EXPECT_NEAR(e.targets[0].r, (4 * r2 + 2) * 1e-3, 1e-12);
  EXPECT_NEAR(e.repeatability, 8 * r2 * 1e-3, 1e-12);
  EXPECT_NEAR(e.repeatability_up, 4 * r2 * 1e-3, 1e-12);
  EXPECT_NEAR(e.systematic, 2e-3, 1e-12);
  EXPECT_NEAR(e.systematic_up, 0.0, 1e-12);
  EXPECT_NEAR(e.range, 1e-3, 1e-12);
  EXPECT_NEAR(e.accuracy, 8 * r2 * 1e-3, 1e-12);
  EXPECT_NEAR(e.accuracy_up, 4 * r2 * 1e-3, 1e-12);
}

// A simulated X axis: EXX(x) = 3 um sin(x / 150 mm) + 10 um/m x, a reversal of 1.5 um, laser
// noise 0.5 um + 0.5 um/m (issue 20), five runs each way over 0..600 mm every 50 mm.
double truth_um(double x) { return 3.0 * std::sin(x / 150.0) + 0.010 * x; }

std::string simulated_runs(unsigned seed,
                           const std::function<double(int run, bool up, double x, double v)>& edit = {}) {
  std::mt19937 random(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::ostringstream csv;
  csv << "# instrument: simulated laser, 0.5 um + 0.5 um/m\n# temperature_degC: 20.1\n# measured_at_mm: 0, 0, -120\n"
      << "target[mm],run,direction,deviation[um]\n";
  for (int run = 1; run <= 5; ++run)
    for (bool up : {true, false})
      for (int k = 0; k <= 12; ++k) {
        const double x = 50.0 * (up ? k : 12 - k);
        double v = truth_um(x) + (up ? 0.75 : -0.75) + (0.5 + 0.5e-3 * x) * unit(random);
        if (edit) v = edit(run, up, x, v);
        csv << x << ',' << run << ',' << (up ? '+' : '-') << ',' << v << '\n';
      }
  return csv.str();
}

TEST(Iso230_2, RecoversASimulatedAxisWithinTheNoise) {
  const LaserRuns runs = read_laser_runs(write("sim.csv", simulated_runs(7)));
  EXPECT_TRUE(suspicious_runs(runs).empty());
  const Iso230_2 e = evaluate_iso230_2(runs);
  EXPECT_EQ(e.runs_up, 5);
  ASSERT_EQ(e.targets.size(), 13u);
  for (const TargetStatistics& t : e.targets) {
    const double sigma_of_mean = (0.5 + 0.5e-3 * t.target) / std::sqrt(10.0);  // 10 readings
    EXPECT_NEAR(t.mean * 1e3, truth_um(t.target), 3.5 * sigma_of_mean) << t.target;
  }
  EXPECT_NEAR(e.mean_reversal * 1e3, 1.5, 0.6);  // 13 reversal values of sigma ~0.55 um
  EXPECT_GT(e.repeatability * 1e3, 2.0);         // 4 s >= 2 um, plus the reversal
  EXPECT_LT(e.repeatability * 1e3, 8.0);
  ASSERT_EQ(runs.metadata.size(), 3u);
  EXPECT_EQ(runs.metadata[2].first, "measured_at_mm");
  EXPECT_EQ(runs.metadata[2].second, "0, 0, -120");
}

TEST(Iso230_2, FindsRunsThatDisagreeAndWhy) {
  const auto flagged = [](const std::function<double(int, bool, double, double)>& edit) {
    return suspicious_runs(read_laser_runs(write("bad.csv", simulated_runs(7, edit))));
  };
  auto reversed = flagged([](int run, bool up, double, double v) { return run == 3 && up ? -v : v; });
  ASSERT_EQ(reversed.size(), 1u);
  EXPECT_EQ(reversed[0].run, RunKey(3, Direction::Up));
  EXPECT_NE(reversed[0].reason.find("sign reversed"), std::string::npos) << reversed[0].reason;
  auto nanometres = flagged([](int run, bool up, double, double v) { return run == 2 && !up ? 1000 * v : v; });
  ASSERT_EQ(nanometres.size(), 1u);
  EXPECT_NE(nanometres[0].reason.find("another unit"), std::string::npos) << nanometres[0].reason;
  auto disturbed = flagged([](int run, bool up, double x, double v) { return run == 4 && up && x > 200 ? v + 6 : v; });
  ASSERT_EQ(disturbed.size(), 1u);
  EXPECT_NE(disturbed[0].reason.find("stands off"), std::string::npos) << disturbed[0].reason;
  // Left out, the evaluation is that of the four good runs.
  const LaserRuns runs = read_laser_runs(
      write("bad.csv", simulated_runs(7, [](int run, bool up, double, double v) { return run == 3 && up ? -v : v; })));
  const Iso230_2 e = evaluate_iso230_2(runs, {RunKey(3, Direction::Up)});
  EXPECT_EQ(e.runs_up, 4);
  EXPECT_EQ(e.runs_down, 5);
}

TEST(LaserRuns, WideLayoutReadsAsTheLongOne) {
  const LaserRuns wide = read_laser_runs(write("wide.csv",
                                               "target[mm],1+[um],1-[um],run2+[um],run2-[um]\n"
                                               "0,1,-1,3,1\n100,2,0,2,4\n"));
  const LaserRuns by_row = read_laser_runs(write("long.csv",
                                                 "target[mm],run,direction,deviation[um]\n"
                                                 "0,1,+,1\n100,1,+,2\n100,1,-,0\n0,1,-,-1\n"
                                                 "0,2,up,3\n100,2,up,2\n100,2,down,4\n0,2,down,1\n"));
  const Iso230_2 a = evaluate_iso230_2(wide), b = evaluate_iso230_2(by_row);
  ASSERT_EQ(a.targets.size(), b.targets.size());
  for (std::size_t i = 0; i < a.targets.size(); ++i) EXPECT_DOUBLE_EQ(a.targets[i].mean, b.targets[i].mean);
  EXPECT_DOUBLE_EQ(a.accuracy, b.accuracy);
}

TEST(LaserRuns, BadFilesAreRefusedWithTheirPlace) {
  const auto message = [](const std::string& text) -> std::string {
    try {
      evaluate_iso230_2(read_laser_runs(write("refused.csv", text)));
    } catch (const std::exception& e) {
      return e.what();
    }
    return "not refused";
  };
  EXPECT_NE(message("target[mm],run,direction,deviation[um]\n0,1,sideways,1\n")
                .find("refused.csv:2:5: error: direction 'sideways'"),
            std::string::npos);
  EXPECT_NE(message("target[mm],run,direction,deviation[furlong]\n").find("refused.csv:1:"), std::string::npos);
  EXPECT_NE(message("target,run,direction,deviation[um]\n0,1,+,1\n").find("the target needs its unit"),
            std::string::npos);
  EXPECT_NE(message("target[mm],run,direction,deviation[um]\n0,1,+,1\n0,1,-,1\n100,1,+,1\n100,1,-,1\n")
                .find("at least 2 runs in each direction"),
            std::string::npos);
  EXPECT_NE(message("target[mm],1+[um],1-[um],2+[um],2-[um]\n0,1,1,1,1\n100,1,1,,1\n")
                .find("run 2+ has no reading at target 100"),
            std::string::npos);
  EXPECT_NE(message("target[mm],run,direction,deviation[um]\n0,1,+,1\n0,1,+,2\n")
                .find("refused.csv:3: error: run 1+ reads target 0 again"),
            std::string::npos);
}

}  // namespace
}  // namespace vc::identify
