// The modified method on a real LinuxCNC (issue 35): the MC-300 with LinuxCNC's own trivkins, no
// volkins, and the joints' COMP_FILEs that `volcomp fit-tables` wrote
// (kins/configs/mc300/mc300_stock.ini, its stock_tables/). The sample part runs headless three
// times: without the tables, with the usual practice's, with the modified method's. The tool-tip
// error along each run comes from the recorded motor commands (LinuxCNC added the tables' values
// to the joints itself) through the real MC-300 model (vc/trace/session_trace.hpp); the fit's
// prediction comes from the fit's own tables and interpolation (vc/fit_tables) at the nominal
// joints: the two must agree to 0.1 um at every sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <regex>
#include <sstream>

#include "linuxcnc_run.hpp"
#include "vc/fit_tables/comp_file.hpp"
#include "vc/fit_tables/comp_file_replay.hpp"
#include "vc/fit_tables/controller.hpp"
#include "vc/fit_tables/study.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/trace/session_trace.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
using machine::Joints;

const std::string kStockIni = "kins/configs/mc300/mc300_stock.ini";
const std::string kTables = "kins/configs/mc300/stock_tables";
const char kAxes[] = "xyzbc";

std::string comp_file_name(int joint) { return "joint_" + std::to_string(joint) + "_" + kAxes[joint] + ".comp"; }

class StockTablesSession : public ::testing::Test {
 protected:
  // The fit the shipped tables come from (their INI comment's command line).
  static void SetUpTestSuite() {
    model_ = new machine::Model(machine::load_machine(test::machine_path("mc300")));
    fit_tables::StudyOptions o;
    o.tool_lengths_mm = {0, 100, 200};
    study_ = new fit_tables::Study(
        fit_tables::run_study(*model_, fit_tables::load_controller(fit_tables::controller_file("linuxcnc")), o));
  }
  static void TearDownTestSuite() {
    delete study_;
    delete model_;
  }

  // One headless session of the stock configuration; its trace checked against the model.
  static trace::TraceSummary run(const std::string& name, const std::string& options, trace::SessionTrace& t) {
    const fs::path dir = test::run_folder(name);
    const test::CommandResult r =
        test::run_in(dir,
                     "bash " + test::source_path("kins/configs/run_headless.sh") + " " + test::source_path(kStockIni) +
                         " " + (dir / "run").string() + " " + options,
                     900);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    if (r.exit_code != 0) throw std::runtime_error("session failed: " + r.out);
    t = trace::read_session_trace((dir / "run/kins/configs/mc300/trace.csv").string(), *model_);
    EXPECT_FALSE(t.with_volkins);
    return trace::check_trace(*model_, machine::WorldConvention::Axes, t);
  }

  // What the simulated controller predicts, |tip error| (um) at each checked sample: the tables
  // in `folder` as LinuxCNC reads them (float values) replayed on the session's nominal joints
  // (fit_tables::replay_comp_files: LinuxCNC's rules, period by period). `settled`: per checked
  // sample, whether every joint's correction is its table's value.
  static std::vector<double> simulated_um(const trace::SessionTrace& t, const trace::TraceSummary& s,
                                          const std::string& folder, std::vector<bool>& settled) {
    std::vector<fit_tables::LinuxcncComp> comps;
    std::vector<fit_tables::JointLimits> limits;
    for (int j = 0; j < 5; ++j) {
      comps.push_back(folder.empty()
                          ? fit_tables::LinuxcncComp{}
                          : fit_tables::read_linuxcnc_comp(test::file_text(fs::path(folder) / comp_file_name(j)), 1));
      const std::string section = "JOINT_" + std::to_string(j);
      const double home = test::ini_value(kStockIni, section, "HOME");  // HOME_OFFSET: not set, 0
      limits.push_back({test::ini_value(kStockIni, section, "MAX_VELOCITY"),
                        test::ini_value(kStockIni, section, "MAX_ACCELERATION"),
                        home > 0   ? 1
                        : home < 0 ? -1
                                   : 0});
    }
    fit_tables::CompReplay replay = fit_tables::replay_comp_files(*model_, t, s, comps, limits, 1e-3);
    settled = std::move(replay.settled);
    return std::move(replay.tip_error_um);
  }

  // The fit's own prediction (its TableSet and interpolation, values x) at the same nominal joints.
  static std::vector<double> fitted_um(const trace::SessionTrace& t, const trace::TraceSummary& s,
                                       const Eigen::VectorXd& x) {
    std::vector<fit_tables::Pose> poses;
    for (const trace::SampleCheck& c : s.samples)
      poses.push_back(
          {trace::interpolated(t.world, c.sample), model_->correction_length(t.tool_offset_mm[c.sample - 1])});
    return fit_tables::table_errors(*model_, study_->set, x, poses);
  }

  static double max_um(const trace::TraceSummary& s) {
    double m = 0;
    for (const trace::SampleCheck& c : s.samples) m = std::max(m, c.tip_error_mm.norm() * 1e3);
    return m;
  }

  static machine::Model* model_;
  static fit_tables::Study* study_;
};
machine::Model* StockTablesSession::model_ = nullptr;
fit_tables::Study* StockTablesSession::study_ = nullptr;

// The shipped tables are the fit's output, not stale: each node as the fit computes it now.
TEST_F(StockTablesSession, ShippedTablesAreTheFitsTables) {
  const auto expect_files = [&](const fs::path& folder, const Eigen::VectorXd& x, const std::string& what) {
    const std::vector<fit_tables::LinuxcncCompFile> fitted = fit_tables::linuxcnc_comp_files(*model_, study_->set, x);
    ASSERT_EQ(fitted.size(), 5u);
    for (const fit_tables::LinuxcncCompFile& f : fitted) {
      const fit_tables::LinuxcncComp shipped = fit_tables::read_linuxcnc_comp(test::file_text(folder / f.file_name), 1);
      const fit_tables::LinuxcncComp now = fit_tables::read_linuxcnc_comp(f.text, 1);
      ASSERT_EQ(shipped.nominal, now.nominal) << what << " " << f.file_name;
      for (std::size_t i = 0; i < now.nominal.size(); ++i)
        EXPECT_NEAR(shipped.forward_trim[i], now.forward_trim[i], 1e-9)
            << what << " " << f.file_name << " node " << i << ": regenerate with the command in " << kStockIni;
    }
  };
  expect_files(test::source_path(kTables), study_->modified, "modified");
  expect_files(test::source_path(kTables) + "/usual_practice", study_->usual, "usual practice");
}

TEST_F(StockTablesSession, SamplePartRunsAsTheFitPredictsAndBeatsTheUsualPractice) {
  trace::SessionTrace none_trace, usual_trace, modified_trace;
  const trace::TraceSummary none = run("stock_none", "--without-comp-files", none_trace);
  std::string usual_files;
  for (int j = 0; j < 5; ++j)
    usual_files += " --set JOINT_" + std::to_string(j) + ".COMP_FILE=stock_tables/usual_practice/" + comp_file_name(j);
  const trace::TraceSummary usual = run("stock_usual", usual_files, usual_trace);
  const trace::TraceSummary modified = run("stock_modified", "", modified_trace);

  const auto expect_as_predicted = [&](const trace::SessionTrace& t, const trace::TraceSummary& s,
                                       const std::string& folder, const Eigen::VectorXd& x, const std::string& what) {
    EXPECT_GT(s.samples.size(), 10000u) << what;
    std::vector<bool> settled;
    const std::vector<double> simulated = simulated_um(t, s, folder, settled);
    const std::vector<double> fitted = fitted_um(t, s, x);
    EXPECT_EQ(simulated.size(), s.samples.size()) << what;
    double worst_simulated = 0, worst_fitted = 0, shifted = 0;
    std::size_t unsettled = 0;
    for (std::size_t i = 0; i < std::min(simulated.size(), s.samples.size()); ++i) {
      const double session = s.samples[i].tip_error_mm.norm() * 1e3;
      worst_simulated = std::max(worst_simulated, std::abs(session - simulated[i]));
      if (settled[i]) worst_fitted = std::max(worst_fitted, std::abs(session - fitted[i]));
      unsettled += !settled[i];
      shifted = std::max(shifted, s.samples[i].module_mismatch);
    }
    EXPECT_LT(worst_simulated, 0.1) << what
                                    << ": the session's tool-tip error differs from the simulated controller's (um)";
    EXPECT_LT(worst_fitted, 0.1) << what << ": the session's tool-tip error differs from the fit's prediction (um)";
    EXPECT_LT(unsettled, s.samples.size() / 2) << what;
    std::cout
        << what << ": tool tip max " << max_um(s) << " um; the session against the simulated controller max "
        << worst_simulated << " um, against the fit's prediction max " << worst_fitted << " um (the "
        << s.samples.size() - unsettled << " samples where every joint has its table's value; " << unsettled
        << " not: a joint that has not moved since LinuxCNC started has no correction yet); joints moved by the tables max "
        << shifted << " (mm or deg)\n";
    return shifted;
  };
  // Without tables the joints are the nominal ones; with them LinuxCNC moved them.
  const std::string tables = test::source_path(kTables);
  EXPECT_EQ(expect_as_predicted(none_trace, none, "", Eigen::VectorXd::Zero(study_->modified.size()), "no tables"),
            0.0);
  EXPECT_GT(expect_as_predicted(usual_trace, usual, tables + "/usual_practice", study_->usual, "usual practice"), 1e-3);
  EXPECT_GT(expect_as_predicted(modified_trace, modified, tables, study_->modified, "modified method"), 1e-3);

  EXPECT_LT(max_um(modified), 0.6 * max_um(none));
  EXPECT_LT(max_um(modified), max_um(usual));

  // What the main job shows: volcomp trace --comp-files replays each table set on the session
  // without tables; its largest error is the session's with those tables.
  for (const auto& [folder, session] : {std::pair{tables, &modified}, std::pair{tables + "/usual_practice", &usual}}) {
    const test::CommandResult r =
        test::run_volcomp("trace " + test::machine_path("mc300") + " " +
                          (test::run_folder_path("stock_none") / "run/kins/configs/mc300/trace.csv").string() +
                          " --comp-files " + folder + " --ini " + test::source_path(kStockIni));
    ASSERT_EQ(r.exit_code, 0) << r.out;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m,
                                  std::regex("replayed as LinuxCNC applies them .*: tool tip error: max ([0-9.]+) um")))
        << r.out;
    EXPECT_NEAR(std::stod(m[1]), max_um(*session), 0.01) << folder;
  }
}

}  // namespace
}  // namespace vc
