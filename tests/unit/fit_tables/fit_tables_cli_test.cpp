// `volcomp fit-tables`: the files it writes read back (the tables.csv values, applied with the
// controller's interpolation, give the report's M on the grid), and bad input leaves nothing
// behind and exits non-zero with a message.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "test_support.hpp"
#include "vc/fit_tables/comp_file.hpp"
#include "vc/fit_tables/sinumerik_file.hpp"
#include "vc/fit_tables/study.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::fit_tables {
namespace {

namespace fs = std::filesystem;

// The rows of a CSV after its '#' lines and header, split at commas.
std::vector<std::vector<std::string>> rows(const fs::path& file, std::vector<std::string>& header) {
  std::ifstream in(file);
  std::vector<std::vector<std::string>> out;
  bool first = true;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    if (line.back() == ',') cells.emplace_back();
    if (first) {
      header = cells;
      first = false;
    } else {
      out.push_back(cells);
    }
  }
  return out;
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t c = 0; c < header.size(); ++c)
    if (header[c] == name) return c;
  throw std::runtime_error("no column " + name);
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("vc_fit_tables_cli_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

// --programs: the part programs' poses (as a stock machine runs them: the tool length from G43)
// are fitted with the grid and judged as the set "programs"; --programs-only fits them alone,
// which is best for that part and leaves the rest of the volume worse (said in the report).
TEST(FitTablesCli, ProgramsAreFittedAndJudged) {
  const std::string common = "fit-tables " + test::machine_path("mc300") + " --controller linuxcnc --tool-lengths 100" +
                             " --fresh 200 --programs " + test::source_path("kins/configs/mc300/nc/sample_part.ngc") +
                             " --var " + test::source_path("kins/configs/mc300/mc300.var") + " --tool-table " +
                             test::source_path("kins/configs/mc300/mc300.tbl");
  struct Figures {
    double programs_usual = 0, programs_modified = 0, programs_none = 0, grid_modified = 0;
    int programs_poses = 0;
  };
  const auto run = [&](const std::string& name, const std::string& extra) {
    const fs::path out = scratch(name);
    const test::CommandResult r = test::run_volcomp(common + extra + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.out;
    std::vector<std::string> h;
    Figures f;
    for (const auto& row : rows(out / "report.csv", h)) {
      const auto value = [&](const char* c) { return std::stod(row[column(h, c)]); };
      if (row[column(h, "set")] == "programs") {
        EXPECT_EQ(row[column(h, "tool_length[mm]")], "100");  // G43 H1: tool 1, 100 mm
        f.programs_none = value("none_M[um]");
        f.programs_usual = value("usual_M[um]");
        f.programs_modified = value("modified_M[um]");
        f.programs_poses = std::stoi(row[column(h, "poses")]);
      } else if (row[column(h, "set")] == "grid" && row[column(h, "tool_length[mm]")] == "100") {
        f.grid_modified = value("modified_M[um]");
      }
    }
    return f;
  };
  const Figures with_grid = run("programs", ""), alone = run("programs_only", " --programs-only");
  EXPECT_GT(with_grid.programs_poses, 1000);
  EXPECT_LT(with_grid.programs_modified, with_grid.programs_usual);
  EXPECT_LT(with_grid.programs_usual, with_grid.programs_none + 1e-9);
  EXPECT_LT(alone.programs_modified, with_grid.programs_modified);  // best for the part ...
  EXPECT_GT(alone.grid_modified, with_grid.grid_modified);          // ... at the volume's cost
  std::cout << "sample part, M (um): none " << with_grid.programs_none << ", usual " << with_grid.programs_usual
            << ", modified with the grid " << with_grid.programs_modified << " (volume " << with_grid.grid_modified
            << "), the part alone " << alone.programs_modified << " (volume " << alone.grid_modified << ")\n";

  const fs::path refused = scratch("programs_only_alone");
  const test::CommandResult r = test::run_volcomp("fit-tables " + test::machine_path("mc300") +
                                                  " --controller linuxcnc --programs-only -o " + refused.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("--programs-only needs --programs"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(refused));
}

TEST(FitTablesCli, WritesFilesThatReadBack) {
  const fs::path out = scratch("mill3");
  const test::CommandResult run = test::run_volcomp("fit-tables " + test::machine_path("mill3") +
                                                    " --controller source14 -o " + out.string() + " --fresh 200");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("M / Delta of the tool-tip error"), std::string::npos) << run.out;

  std::vector<std::string> rh, th;
  const auto report = rows(out / "report.csv", rh);
  const auto tables = rows(out / "tables.csv", th);
  ASSERT_EQ(report.size(), 4u);  // L = 100 (fitted), 150 (not): grid and fresh
  EXPECT_EQ(rh[column(rh, "modified_M[um]")], "modified_M[um]");

  // The values back into x, in the fit's units (mm, or a ratio for a squareness).
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const TableSet set = resolve_tables(load_controller(controller_file("source14")), model);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(set.unknowns);
  ASSERT_EQ(static_cast<int>(tables.size()), set.unknowns);  // no modulo table on mill3: one row per value
  for (const auto& r : tables) {
    const Table& t = set.tables.at(std::stoul(r[column(th, "table")]) - 1);
    const double value = std::stod(r[column(th, "modified")]);
    const std::string unit = r[column(th, "value_unit")];
    x[t.unknown_of_node(std::stoi(r[column(th, "node")]))] =
        unit == "um" ? value * 1e-3 : std::tan(value / 3600.0 * M_PI / 180.0);
    if (t.kind != TableKind::Squareness) {
      EXPECT_NEAR(std::stod(r[column(th, "position")]), t.nodes.at(std::stoul(r[column(th, "node")])), 1e-6);
    }
  }
  GridSpec grid;
  grid.levels = 7;
  grid.tool_lengths_mm = {100};
  const double m = figures(table_errors(model, set, x, grid_poses(model, grid))).max_um;
  EXPECT_NEAR(m, std::stod(report[0][column(rh, "modified_M[um]")]), 1e-3);
  EXPECT_EQ(report[0][column(rh, "set")], "grid");
  fs::remove_all(out.parent_path());
}

// For source14 (a Sinumerik's LEC and CEC): AX_EEC.INI and NC_CEC.INI that the project's reader
// takes back, whose LEC values are the tables.csv values negated (mill3: X Y Z are AX1 AX2 AX3),
// and the commissioning steps on stdout and in sinumerik_setup.txt.
TEST(FitTablesCli, WritesSinumerikFiles) {
  const fs::path out = scratch("mill3_sinumerik");
  const test::CommandResult run = test::run_volcomp("fit-tables " + test::machine_path("mill3") +
                                                    " --controller source14 -o " + out.string() + " --fresh 200");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("the Sinumerik steps"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("MD32700 $MA_ENC_COMP_ENABLE"), std::string::npos) << run.out;
  EXPECT_TRUE(fs::exists(out / "sinumerik_setup.txt"));
  auto text = [&](const char* name) {
    std::ifstream in(out / name);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  const std::vector<SinumerikTable> lec = read_sinumerik_file(text("AX_EEC.INI"), (out / "AX_EEC.INI").string());
  const std::vector<SinumerikTable> cec = read_sinumerik_file(text("NC_CEC.INI"), (out / "NC_CEC.INI").string());
  ASSERT_EQ(lec.size(), 3u);
  EXPECT_EQ(cec.size(), 9u);  // 6 straightness, 3 squareness
  std::vector<std::string> th;
  int compared = 0;
  for (const auto& r : rows(out / "tables.csv", th)) {
    if (r[column(th, "kind")] != "positioning") continue;
    const int axis = std::string("XYZ").find(r[column(th, "input")][0]);
    const SinumerikTable& t = lec.at(static_cast<std::size_t>(axis));
    ASSERT_EQ(t.input_axis, axis);
    const std::size_t node = std::stoul(r[column(th, "node")]);
    EXPECT_NEAR(t.min + node * t.step, std::stod(r[column(th, "position")]), 1e-6);
    EXPECT_NEAR(-t.values.at(node) * 1e3, std::stod(r[column(th, "modified")]), 1e-9);
    ++compared;
  }
  EXPECT_EQ(compared, 21);  // 3 axes x 7 nodes
  fs::remove_all(out.parent_path());
}

// For LinuxCNC: one COMP_FILE per joint (mill3: X Y Z, joints 0 1 2) and the INI lines; the
// files' trims are the tables.csv values.
TEST(FitTablesCli, WritesLinuxcncCompFiles) {
  const fs::path out = scratch("mill3_linuxcnc");
  const test::CommandResult run =
      test::run_volcomp("fit-tables " + test::machine_path("mill3") + " --controller linuxcnc -o " + out.string() +
                        " --fresh 200 --nodes 11");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("[JOINT_2]\nCOMP_FILE = joint_2_z.comp\nCOMP_FILE_TYPE = 1\n"), std::string::npos) << run.out;
  EXPECT_TRUE(fs::exists(out / "linuxcnc_ini_lines.txt"));
  std::vector<std::string> th;
  const auto tables = rows(out / "tables.csv", th);
  for (const char* name : {"joint_0_x.comp", "joint_1_y.comp", "joint_2_z.comp"}) {
    std::ifstream in(out / name);
    std::stringstream text;
    text << in.rdbuf();
    const LinuxcncComp comp = read_linuxcnc_comp(text.str(), 1);
    ASSERT_EQ(comp.nominal.size(), 11u) << name;
    const std::string axis(1, static_cast<char>(std::toupper(name[8])));
    for (const auto& r : tables) {
      if (r[column(th, "input")] != axis) continue;
      const std::size_t node = std::stoul(r[column(th, "node")]);
      EXPECT_NEAR(comp.nominal.at(node), std::stod(r[column(th, "position")]), 1e-6);
      EXPECT_NEAR(comp.forward_trim.at(node) * 1e3, std::stod(r[column(th, "modified")]), 1e-5);
      EXPECT_EQ(comp.forward_trim.at(node), comp.reverse_trim.at(node));
    }
  }
  fs::remove_all(out.parent_path());
}

TEST(FitTablesCli, BadInputWritesNothing) {
  const std::string mill3 = test::machine_path("mill3");
  for (const auto& [arguments, message] : std::vector<std::pair<std::string, std::string>>{
           {"--controller fanuc", "--controller fanuc: no such controller"},
           {"--controller linuxcnc --nodes 300",
            "--nodes 300: the positioning table X of linuxcnc takes 2 .. 256 nodes"},
           {"--controller linuxcnc --tool-lengths 1,x", "--tool-lengths: 'x' is not a number"},
           {"--controller linuxcnc --rotary B=0", "--rotary B: mill3 has no rotary axis B"},
           {"--controller linuxcnc --criterion max", "--criterion max: ls (least squares) or minimax"}}) {
    const fs::path out = scratch("bad");
    const test::CommandResult run = test::run_volcomp("fit-tables " + mill3 + " " + arguments + " -o " + out.string());
    EXPECT_NE(run.exit_code, 0) << arguments;
    EXPECT_NE(run.out.find(message), std::string::npos) << run.out;
    EXPECT_FALSE(fs::exists(out)) << arguments;
  }
  const fs::path out = scratch("mc300");
  const test::CommandResult run = test::run_volcomp("fit-tables " + test::machine_path("mc300") +
                                                    " --controller linuxcnc --rotary B=-200,0 -o " + out.string());
  EXPECT_NE(run.out.find("--rotary B=-200: outside the travel -120 .. 30 deg"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(out.parent_path());
}

// --reversal: laser runs of X in both directions with a known reversal B(x) = 6 + 0.008 x um
// (and a mean deviation the model does not have: the fit corrects the model's mean, the runs
// give only B). The X COMP_FILE's forward column is the fitted value - B/2 and the reverse one
// + B/2 at every node, as LinuxCNC reads them (float); the other joints' columns stay equal;
// the mean of both is the file fitted without the runs.
TEST(FitTablesCli, TheLasersReversalGoesIntoTheForwardAndReverseColumns) {
  const fs::path dir = scratch("reversal");
  fs::create_directories(dir);
  const auto b_mm = [](double x) { return (6.0 + 0.008 * x) * 1e-3; };
  {
    std::ofstream runs(dir / "x_runs.csv");
    runs << "# instrument: test laser\ntarget[mm],run,direction,deviation[um]\n";
    for (const auto& [run, scatter] : std::vector<std::pair<int, double>>{{1, 0.1}, {2, -0.1}, {3, 0.0}})
      for (const int sign : {1, -1})
        for (int k = 0; k <= 10; ++k) {
          const double x = sign > 0 ? 50.0 * k : 500.0 - 50.0 * k;
          runs << x << ',' << run << ',' << (sign > 0 ? '+' : '-') << ','
               << 2.0 * std::sin(x / 80.0) + sign * b_mm(x) * 1e3 / 2 + scatter << '\n';
        }
  }
  const std::string common = "fit-tables " + test::machine_path("mill3") + " --controller linuxcnc --fresh 200";
  const test::CommandResult with =
      test::run_volcomp(common + " --reversal X=" + (dir / "x_runs.csv").string() + " -o " + (dir / "with").string());
  ASSERT_EQ(with.exit_code, 0) << with.out;
  EXPECT_NE(with.out.find("reversal of X from"), std::string::npos) << with.out;
  EXPECT_NE(with.out.find("B = 10.00 um, mean 8.00 um"), std::string::npos) << with.out;
  const test::CommandResult without = test::run_volcomp(common + " -o " + (dir / "without").string());
  ASSERT_EQ(without.exit_code, 0) << without.out;

  for (const char* file : {"joint_0_x.comp", "joint_1_y.comp", "joint_2_z.comp", "usual_practice/joint_0_x.comp"}) {
    SCOPED_TRACE(file);
    const LinuxcncComp c = read_linuxcnc_comp(test::file_text(dir / "with" / file), 1);
    const LinuxcncComp plain = read_linuxcnc_comp(test::file_text(dir / "without" / file), 1);
    ASSERT_EQ(c.nominal, plain.nominal);
    const bool x = std::string(file).find("_x.comp") != std::string::npos;
    for (std::size_t k = 0; k < c.nominal.size(); ++k) {
      const double forward = linuxcnc_comp_value(c, c.nominal[k], true),
                   reverse = linuxcnc_comp_value(c, c.nominal[k], false);
      EXPECT_NEAR(reverse - forward, x ? b_mm(std::clamp(c.nominal[k], 0.0, 500.0)) : 0.0, 1e-7) << c.nominal[k];
      EXPECT_NEAR(0.5 * (forward + reverse), linuxcnc_comp_value(plain, c.nominal[k], true), 1e-7) << c.nominal[k];
    }
  }

  // Refused before anything is written: another controller, an axis the machine lacks, twice.
  for (const auto& [arguments, message] : std::vector<std::pair<std::string, std::string>>{
           {"--controller source14 --reversal X=" + (dir / "x_runs.csv").string(), "--reversal: the tables of"},
           {"--controller linuxcnc --reversal Q=" + (dir / "x_runs.csv").string(), "AXIS one of the machine's (xyz)"},
           {"--controller linuxcnc --reversal X=" + (dir / "x_runs.csv").string() +
                " --reversal x=" + (dir / "x_runs.csv").string(),
            "that axis is given twice"}}) {
    const fs::path out = dir / "refused";
    const test::CommandResult run =
        test::run_volcomp("fit-tables " + test::machine_path("mill3") + " " + arguments + " -o " + out.string());
    EXPECT_NE(run.exit_code, 0) << arguments;
    EXPECT_NE(run.out.find(message), std::string::npos) << run.out;
    EXPECT_FALSE(fs::exists(out)) << arguments;
  }
  fs::remove_all(dir.parent_path());
}

}  // namespace
}  // namespace vc::fit_tables
