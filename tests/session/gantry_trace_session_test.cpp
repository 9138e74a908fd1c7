// LinuxCNC's own gantry sample, sim/axis/gantry/gantry_mm.ini (trivkins coordinates=xyyz
// kinstype=BOTH: joints 1 and 2 are both Y, Z is joint 3), retrofitted with `volcomp init` (its
// zero-error machine file) and its patch, runs a short program over the machine's travel
// (lines, an arc, rapids, G64 blends) headless (tests/session/headless_sample.py).
// - `volcomp trace --ini`: the trace's joint columns are LinuxCNC's j0..j3; read through the
//   configuration's coordinates=, the perfect session has no tool-tip error and volkins' joints
//   are the core's; read by index (without --ini), the second Y motor is taken for Z.
// - The kinematics type: the same program with the stock module as LinuxCNC's default makes it
//   (no kinstype=: KINEMATICS_IDENTITY), where volkins is KINEMATICS_BOTH: the planned path, the
//   world command at every servo cycle, is the same to the bit (kins/README.md, "The kinematics
//   type").
// Each session costs ~20 s (LinuxCNC's start and ~15 s of program).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>

#include "linuxcnc_run.hpp"
#include "vc/tables/csv.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;

const fs::path kGantry = "/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis/gantry";

// From home (X0 Y0 Z100, Z's upper end) over X to 200, Y to 150, Z down to 5 and back, each axis
// at its 30 mm/s.
const char* const kProgram =
    "G21 G90 G17 G64\nG1 F1800 X40 Y60 Z60\nG2 X120 Y60 I40 J0\nG1 X200 Y150 Z5\n"
    "G0 X0 Y0 Z100\nM2\n";

// A copy of the sample in dir/user with the program; retrofitted (volcomp init, patch) or with
// `kinematics` as its KINEMATICS line; run headless in dir/run. Returns the run folder.
fs::path run_gantry(const fs::path& dir, bool retrofit, const std::string& kinematics = "") {
  const fs::path user = dir / "user", run = dir / "run";
  fs::copy(kGantry, user, fs::copy_options::recursive);
  std::ofstream(user / "travel.ngc") << kProgram;
  if (retrofit) {
    const test::CommandResult init =
        test::run_in(dir, std::string(VC_VOLCOMP) + " init " + (user / "gantry_mm.ini").string() + " -o " +
                              (user / "gantry_mm.toml").string() + " --patch " + (dir / "volkins.patch").string());
    EXPECT_EQ(init.exit_code, 0) << init.out;
    const test::CommandResult patch =
        test::run_in(dir, "patch -p1 -d " + user.string() + " -i " + (dir / "volkins.patch").string());
    EXPECT_EQ(patch.exit_code, 0) << patch.out;
  } else {
    const test::CommandResult set = test::run_in(
        dir, "sed -i 's/^KINEMATICS = .*/KINEMATICS = " + kinematics + "/' " + (user / "gantry_mm.ini").string());
    EXPECT_EQ(set.exit_code, 0) << set.out;
  }
  const test::CommandResult headless = test::run_in(
      dir, "python3 " + test::source_path("tests/session/headless_sample.py") + " " + user.string() +
               " gantry_mm.ini " + run.string() + " --program travel.ngc" + (retrofit ? "" : " --tcp-type -1"));
  EXPECT_EQ(headless.exit_code, 0) << headless.out;
  const test::CommandResult session = test::run_in(run, "linuxcnc gantry_mm.ini", 300);
  std::ifstream result(run / "result.txt");
  std::string first;
  std::getline(result, first);
  EXPECT_EQ(first.rfind("ok", 0), 0u) << "session: " << first << "\n" << session.out;
  return run;
}

// Column `name` of a CSV.
std::vector<double> column(const fs::path& csv, const std::string& name) {
  const std::vector<tables::CsvRow> rows = tables::read_csv_rows(csv.string(), "csv");
  const auto& header = rows.front().cells;
  const auto at = std::find_if(header.begin(), header.end(), [&](const tables::CsvCell& c) { return c.text == name; });
  EXPECT_NE(at, header.end()) << name;
  std::vector<double> v;
  if (at == header.end()) return v;
  for (std::size_t r = 1; r < rows.size(); ++r) v.push_back(std::stod(rows[r].cells[at - header.begin()].text));
  return v;
}

TEST(GantrySession, VolcompTraceReadsTheJointsThroughTheConfiguration) {
  if (!fs::exists(kGantry / "gantry_mm.ini")) GTEST_SKIP() << "LinuxCNC's gantry sample is not installed";
  const fs::path dir = test::run_folder("gantry_trace");
  const fs::path run = run_gantry(dir, true);

  const std::string trace = (run / "trace.csv").string(), machine = (dir / "user/gantry_mm.toml").string();
  const test::CommandResult checked =
      test::run_volcomp("trace " + machine + " " + trace + " --ini " + (run / "gantry_mm.ini").string() + " -o " +
                        (dir / "errors.csv").string());
  ASSERT_EQ(checked.exit_code, 0) << checked.out;
  std::smatch samples, module;
  ASSERT_TRUE(std::regex_search(checked.out, samples, std::regex("\\(([0-9]+) samples checked"))) << checked.out;
  EXPECT_GT(std::stoi(samples[1]), 10000) << checked.out;
  ASSERT_TRUE(
      std::regex_search(checked.out, module, std::regex("module against the core \\(joints, mm or deg\\): max (\\S+)")))
      << checked.out;
  EXPECT_LT(std::stod(module[1]), 1e-9) << checked.out;
  const std::vector<double> e = column(dir / "errors.csv", "e_um");
  const double tip_um = *std::max_element(e.begin(), e.end());
  EXPECT_LT(tip_um, 1e-6) << checked.out;

  // The trace went over the travel: Z down to 5 (j3), X to 200, Y to 150 on both motors (G64's
  // blends cut the corners by microns).
  const std::vector<double> j0 = column(trace, "j0"), j2 = column(trace, "j2"), j3 = column(trace, "j3");
  EXPECT_NEAR(*std::min_element(j3.begin(), j3.end()), 5, 1e-3);
  EXPECT_NEAR(*std::max_element(j0.begin(), j0.end()), 200, 1e-3);
  EXPECT_NEAR(*std::max_element(j2.begin(), j2.end()), 150, 1e-3);

  // By index (no --ini: the machine file's order j0 j1 j2), Z is read from the second Y motor.
  const test::CommandResult by_index =
      test::run_volcomp("trace " + machine + " " + trace + " -o " + (dir / "by_index.csv").string());
  ASSERT_EQ(by_index.exit_code, 0) << by_index.out;
  const std::vector<double> misread = column(dir / "by_index.csv", "e_um");
  const double misread_um = *std::max_element(misread.begin(), misread.end());
  EXPECT_GT(misread_um, 100e3);
  std::cout << "gantry session: " << samples[1] << " samples; with --ini tip error max " << tip_um
            << " um, module against the core " << module[1] << "; by index " << misread_um / 1e3 << " mm\n";
}

// The world command (axis.*.pos-cmd) of each servo cycle from the program's first move on.
std::vector<std::array<double, 3>> world_path(const fs::path& trace) {
  const std::vector<double> x = column(trace, "x"), y = column(trace, "y"), z = column(trace, "z");
  std::vector<std::array<double, 3>> path;
  for (std::size_t k = 0; k < x.size(); ++k) path.push_back({x[k], y[k], z[k]});
  const auto first_move = std::find_if(path.begin(), path.end(), [&](const auto& p) { return p != path.front(); });
  path.erase(path.begin(), first_move - (first_move == path.begin() ? 0 : 1));
  while (path.size() > 1 && path[path.size() - 2] == path.back()) path.pop_back();  // at rest after M2
  return path;
}

TEST(GantrySession, TheStockIdentityKinematicsAndVolkinsPlanTheSamePath) {
  if (!fs::exists(kGantry / "gantry_mm.ini")) GTEST_SKIP() << "LinuxCNC's gantry sample is not installed";
  const fs::path stock = run_gantry(test::run_folder("gantry_stock_identity"), false, "trivkins coordinates=xyyz");
  const fs::path retrofitted = run_gantry(test::run_folder("gantry_volkins_path"), true);
  const auto a = world_path(stock / "trace.csv"), b = world_path(retrofitted / "trace.csv");
  ASSERT_GT(a.size(), 10000u);
  EXPECT_EQ(a.size(), b.size()) << "servo cycles from the first move to rest";
  std::size_t differing = 0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) differing += a[k] != b[k];
  EXPECT_EQ(differing, 0u) << "servo cycles whose world command differs";
  std::cout << "trivkins (KINEMATICS_IDENTITY) vs volkins (KINEMATICS_BOTH): " << a.size() << " vs " << b.size()
            << " servo cycles of motion, " << differing << " differing\n";
}

}  // namespace
}  // namespace vc
