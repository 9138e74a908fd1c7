// Golden bad inputs: every file in tests/golden/bad_tables (*.csv), tests/golden/bad_machines
// (*.toml), tests/golden/bad_reports (*.csv: CMM reports, read as selftune reads them without
// options), tests/golden/bad_laser_runs and bad_circular_tests (*.csv), tests/golden/bad_acceptance
// (plans, tolerances, diagonal runs, results files) must be refused with a vc::LoadError whose
// text is exactly the content of the file's .expect twin (trimmed), with the source tree's
// absolute path removed so that paths read relative to the repository root:
//     tests/golden/bad_tables/nan_cell.csv:3:4: error: 'nan' is not a finite number
// Adding a case is adding two files. Bad tables whose name starts with "cubic_" are loaded with
// cubic interpolation (the rules that only apply to splines); the others with the defaults.
// Bad machines may reference tables in tests/golden/bad_machines/tables/.
//
// VC_UPDATE_GOLDEN=1 writes the .expect files from the loaders' current messages: read every
// one of them critically before committing (is it the right line and column? does it say what
// is wrong and how to fix it?).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vc/acceptance/diagonal_evaluation.hpp"
#include "vc/acceptance/diagonal_measurements.hpp"
#include "vc/acceptance/evaluation_file.hpp"
#include "vc/acceptance/plan_file.hpp"
#include "vc/acceptance/tolerances.hpp"
#include "vc/identify/iso230_4.hpp"
#include "vc/identify/iso230_2.hpp"
#include "vc/identify/laser_runs.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/shop/cmm.hpp"
#include "vc/tables/load_table.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;

using test::relative_message;
using test::trimmed;

// Loads every `extension` file of `folder` with `load` and compares the refusal with its .expect.
void check_folder(const std::string& folder, const std::string& extension,
                  const std::function<void(const fs::path&)>& load) {
  const fs::path dir = test::source_path(folder);
  const std::vector<fs::path> files = test::files_with_extension(dir, extension);
  ASSERT_FALSE(files.empty()) << "no " << extension << " files in " << dir;
  const bool update = std::getenv("VC_UPDATE_GOLDEN") != nullptr;

  for (const fs::path& file : files) {
    SCOPED_TRACE(folder + "/" + file.filename().string());
    std::string message;
    try {
      load(file);
      ADD_FAILURE() << "accepted a bad file";
      continue;
    } catch (const LoadError& e) {
      message = relative_message(e.what());
    } catch (const std::exception& e) {
      ADD_FAILURE() << "threw something other than vc::LoadError: " << e.what();
      continue;
    }
    fs::path expect = file;
    expect.replace_extension(".expect");
    if (update) std::ofstream(expect) << message << '\n';
    std::ifstream in(expect);
    if (!in) {
      ADD_FAILURE() << "missing " << expect.filename() << "; the loader says:\n" << message;
      continue;
    }
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(message, trimmed(text.str()));
  }

  // Every .expect belongs to a bad file (a renamed or deleted case leaves none behind).
  for (const fs::path& expect : test::files_with_extension(dir, ".expect")) {
    fs::path input = expect;
    input.replace_extension(extension);
    EXPECT_TRUE(fs::exists(input)) << expect.filename() << " has no " << input.filename();
  }
}

TEST(BadFiles, EveryBadTableIsRefusedWithItsMessage) {
  check_folder("tests/golden/bad_tables", ".csv", [](const fs::path& p) {
    tables::TableOptions options;
    if (p.filename().string().rfind("cubic_", 0) == 0) options.interpolation = tables::Interpolation::Cubic;
    tables::load_table(p.string(), options);
  });
}

TEST(BadFiles, EveryBadMachineIsRefusedWithItsMessage) {
  check_folder("tests/golden/bad_machines", ".toml", [](const fs::path& p) { machine::load_machine(p.string()); });
}

TEST(BadFiles, EveryBadCmmReportIsRefusedWithItsMessage) {
  check_folder("tests/golden/bad_reports", ".csv", [](const fs::path& p) { shop::read_cmm_points(p.string(), true); });
}

// The instruments' files, read and evaluated as `volcomp identify laser` and `identify circle`
// do: what cannot be read, and what cannot give the evaluation (too few runs, a part of a turn).
TEST(BadFiles, EveryBadLaserRunIsRefusedWithItsMessage) {
  check_folder("tests/golden/bad_laser_runs", ".csv",
               [](const fs::path& p) { identify::evaluate_iso230_2(identify::read_laser_runs(p.string())); });
}

TEST(BadFiles, EveryBadCircularTestIsRefusedWithItsMessage) {
  check_folder("tests/golden/bad_circular_tests", ".csv",
               [](const fs::path& p) { identify::evaluate_circular_test(identify::read_circular_test(p.string())); });
}

// `volcomp acceptance`'s files (tests/golden/bad_acceptance): plans, tolerances, and a diagonal's
// laser runs read against good/plan.toml's diagonal and evaluated as `acceptance evaluate` does.
TEST(BadFiles, EveryBadAcceptancePlanIsRefusedWithItsMessage) {
  check_folder("tests/golden/bad_acceptance/plans", ".toml",
               [](const fs::path& p) { acceptance::read_plan_file(p.string()); });
}

TEST(BadFiles, EveryBadAcceptanceToleranceFileIsRefusedWithItsMessage) {
  check_folder("tests/golden/bad_acceptance/tolerances", ".toml",
               [](const fs::path& p) { acceptance::read_tolerances(p.string()); });
}

TEST(BadFiles, EveryBadDiagonalRunIsRefusedWithItsMessage) {
  const acceptance::Plan plan = acceptance::read_plan(test::source_path("tests/golden/bad_acceptance/good"));
  check_folder("tests/golden/bad_acceptance/runs", ".csv", [&](const fs::path& p) {
    const acceptance::Diagonal& d = plan.diagonals.front();
    acceptance::evaluate_diagonal(d, acceptance::read_diagonal_runs(p.string(), d), 0.5e-3, nullptr);
  });
}

// `acceptance evaluate`'s results files (evaluation_file.hpp), as `volcomp report --acceptance`
// reads them; the good file they are made from is read whole.
TEST(BadFiles, EveryBadAcceptanceResultsFileIsRefusedWithItsMessage) {
  check_folder("tests/golden/bad_acceptance/evaluations", ".csv",
               [](const fs::path& p) { acceptance::read_evaluation(p.string()); });
  const acceptance::Evaluation good =
      acceptance::read_evaluation(test::source_path("tests/golden/bad_acceptance/good/evaluation.csv"));
  ASSERT_EQ(good.rows.size(), 4u);
  EXPECT_EQ(good.rows[2].figure, "R");
  EXPECT_FALSE(good.rows[2].limit);
  EXPECT_EQ(good.rows[3].verdict, "FAIL");
  EXPECT_EQ(acceptance::overall_verdict(good), "FAIL");
  EXPECT_EQ(good.comments.size(), 2u);
}

// The catalogue itself: the machine the bad machines are made from, and the good tables they
// share, load; so each bad machine is bad for the one reason its first line gives.
TEST(BadFiles, TheGoodBaseOfTheBadMachinesLoads) {
  const fs::path dir = test::source_path("tests/golden/bad_machines");
  try {
    const machine::Model m = machine::load_machine((dir / "good/base.toml").string());
    EXPECT_EQ(m.joint_count(), 5);
    EXPECT_EQ(m.tables.size(), 2u);
    EXPECT_TRUE(m.warnings.empty());
  } catch (const LoadError& e) {
    FAIL() << e.what();
  }
  for (const char* name : {"x.csv", "c.csv", "x_by_y.csv"}) {
    SCOPED_TRACE(name);
    EXPECT_NO_THROW(tables::load_table((dir / "tables" / name).string()));
  }
}

}  // namespace
}  // namespace vc
