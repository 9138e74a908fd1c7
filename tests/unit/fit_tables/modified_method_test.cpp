// The modified method (seeds/000 sec. 3.3.3.4) against the usual practice, every figure on the
// nonlinear model: better in both M and Delta on the fitted grid, on fresh poses and at a tool
// length not fitted, on every shipped machine (mill3, MC-300, ac_trunnion) with both shipped
// controllers; the issue's MC-300
// targets (tables fitted over L = 0, 100, 200 mm); no drift along the one-tool-length null
// direction; and the linearised model the fit uses agrees with the nonlinear one.
#include <gtest/gtest.h>

#include <algorithm>

#include "test_support.hpp"
#include "vc/fit_tables/study.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::fit_tables {
namespace {

Study study(const machine::Model& model, const std::string& controller, std::vector<double> lengths) {
  StudyOptions o;
  o.tool_lengths_mm = std::move(lengths);
  o.fresh_poses = 1000;
  return run_study(model, load_controller(controller_file(controller)), o);
}

void print(const std::string& title, const Study& s) {
  std::printf("%s\n  L[mm] fitted set    none M/Delta   usual M/Delta  modified M/Delta  full M [um]\n", title.c_str());
  for (const ReportRow& r : s.rows)
    std::printf("  %5.0f  %-3s  %-5s %6.1f %6.1f   %6.1f %6.1f   %6.1f %6.1f   %8.5f\n", r.tool_length_mm,
                r.fitted_length ? "yes" : "no", r.set.c_str(), r.none.max_um, r.none.delta_um, r.usual.max_um,
                r.usual.delta_um, r.modified.max_um, r.modified.delta_um, r.full.max_um);
}

// Every row: modified better than usual in M and Delta, full correction the bound.
void beats_usual_everywhere(const Study& s) {
  bool unfitted = false, fresh = false;
  for (const ReportRow& r : s.rows) {
    SCOPED_TRACE("L = " + std::to_string(r.tool_length_mm) + " mm, " + r.set);
    EXPECT_LT(r.modified.max_um, r.usual.max_um);
    EXPECT_LT(r.modified.delta_um, r.usual.delta_um);
    EXPECT_LT(r.usual.max_um, r.none.max_um);
    EXPECT_LT(r.full.max_um, 1e-3);
    EXPECT_GE(r.modified.max_um, r.full.max_um);
    unfitted = unfitted || !r.fitted_length;
    fresh = fresh || r.set == "fresh";
  }
  EXPECT_TRUE(unfitted);
  EXPECT_TRUE(fresh);
}

// The largest M of a method over the rows of the fitted tool lengths, on one set.
double fitted_max(const Study& s, const std::string& set, Figures ReportRow::*method) {
  double m = 0;
  for (const ReportRow& r : s.rows)
    if (r.fitted_length && r.set == set) m = std::max(m, (r.*method).max_um);
  return m;
}

const ReportRow& row(const Study& s, double length, const std::string& set) {
  for (const ReportRow& r : s.rows)
    if (r.tool_length_mm == length && r.set == set) return r;
  throw std::runtime_error("no row");
}

TEST(FitTablesModifiedMethod, BeatsTheUsualPracticeOnMill3) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  for (const char* controller : {"linuxcnc", "source14"}) {
    SCOPED_TRACE(controller);
    const Study s = study(model, controller, {100});
    print(std::string("mill3, ") + controller + ", fitted at L = 100 mm", s);
    beats_usual_everywhere(s);
  }
}

TEST(FitTablesModifiedMethod, BeatsTheUsualPracticeOnTheAcTrunnion) {
  const machine::Model model = machine::load_machine(test::machine_path("ac_trunnion"));
  for (const char* controller : {"linuxcnc", "source14"}) {
    SCOPED_TRACE(controller);
    const Study s = study(model, controller, {0, 100, 200});
    print(std::string("ac_trunnion, ") + controller + ", fitted at L = 0, 100, 200 mm", s);
    beats_usual_everywhere(s);
  }
}

// The issue's targets: over the MC-300's whole travel, fitted over L = 0, 100, 200 mm together:
// M of the 14 tables at most 1/3 of the usual practice's, of LinuxCNC's at most 0.6 of it, over
// the fitted lengths and at L = 100 mm alone, on the grid and on fresh poses. (At L = 0 alone
// the ratios are 0.40 and 0.63: one minimax over three lengths leaves M about equal at each,
// while the usual practice's M grows with L.)
TEST(FitTablesModifiedMethod, MeetsTheIssuesTargetsOnTheMc300) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  for (const auto& [controller, ratio] :
       std::vector<std::pair<std::string, double>>{{"source14", 1.0 / 3.0}, {"linuxcnc", 0.6}}) {
    SCOPED_TRACE(controller);
    const Study s = study(model, controller, {0, 100, 200});
    print("MC-300, " + controller + ", fitted at L = 0, 100, 200 mm", s);
    beats_usual_everywhere(s);
    for (const char* set : {"grid", "fresh"}) {
      SCOPED_TRACE(set);
      EXPECT_LT(fitted_max(s, set, &ReportRow::modified), ratio * fitted_max(s, set, &ReportRow::usual));
      EXPECT_LT(row(s, 100, set).modified.max_um, ratio * row(s, 100, set).usual.max_um);
    }
    // The independent study on the same model, at L = 100 mm: none 108 um, usual 96 (LinuxCNC)
    // and 84 (14 tables); fitted over three tool lengths 49-57 / 27-30 um.
    const ReportRow& r = row(s, 100, "grid");
    EXPECT_NEAR(r.none.max_um, 108, 5);
    EXPECT_NEAR(r.usual.max_um, controller == "linuxcnc" ? 96 : 84, 4);
    EXPECT_LT(r.modified.max_um, controller == "linuxcnc" ? 57 : 30);
  }
}

// With one tool length the 14-table problem has a null direction (a constant B offset traded
// for an X(z)/Z(x) rotation and X/Z offsets); the ridge towards the usual practice keeps the
// fit from drifting along it: still better than the usual practice at L = 0 and 200 mm.
TEST(FitTablesModifiedMethod, OneToolLengthDoesNotDriftAlongTheNullDirection) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  StudyOptions o;
  o.tool_lengths_mm = {100};
  o.check_tool_lengths_mm = std::vector<double>{0, 200};
  o.fresh_poses = 500;
  const Study s = run_study(model, load_controller(controller_file("source14")), o);
  print("MC-300, source14, fitted at L = 100 mm only", s);
  for (const ReportRow& r : s.rows) {
    SCOPED_TRACE("L = " + std::to_string(r.tool_length_mm) + " mm, " + r.set);
    EXPECT_LT(r.modified.max_um, 0.6 * r.usual.max_um);
  }
}

// The fit's linear model (e + J c) against the nonlinear tip at q + c, at the fitted values.
TEST(FitTablesModifiedMethod, TheLinearisedModelAgreesWithTheNonlinearOne) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const Controller controller = load_controller(controller_file("source14"));
  const Study s = study(model, "source14", {100});
  GridSpec grid;
  grid.levels = 5;
  grid.tool_lengths_mm = {0, 200};
  const std::vector<Pose> poses = grid_poses(model, grid);
  const LinearSystem system = linearise(model, s.set, poses);
  const std::vector<double> nonlinear = table_errors(model, s.set, s.modified, poses);
  double worst = 0;
  for (int p = 0; p < system.poses(); ++p)
    worst =
        std::max(worst, std::abs(system.residual(p, s.modified).norm() * 1e3 - nonlinear[static_cast<std::size_t>(p)]));
  EXPECT_LT(worst, 0.05);  // um (measured 0.012: a rotary correction's second order, the tables' kinks)
}

TEST(FitTablesModifiedMethod, LeastSquaresAlsoBeatsTheUsualPractice) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  StudyOptions o;
  o.tool_lengths_mm = {0, 100, 200};
  o.fresh_poses = 500;
  o.fit.criterion = Criterion::LeastSquares;
  const Study s = run_study(model, load_controller(controller_file("source14")), o);
  print("MC-300, source14, least squares, fitted at L = 0, 100, 200 mm", s);
  for (const ReportRow& r : s.rows) EXPECT_LT(r.modified.max_um, r.usual.max_um);
}

}  // namespace
}  // namespace vc::fit_tables
