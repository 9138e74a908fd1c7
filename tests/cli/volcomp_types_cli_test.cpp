// volcomp's --types (predistort, selftune, trace): the compensation types switched offline, run
// as a user runs them. The reference is built without the selection: mill3's machine file with
// the errors of every type but L-POS zeroed, written here from the shipped tables (L-POS of a
// linear axis: its positioning error EXX, EYY, EZZ; ISO/TR 16907 Annex A), so that "--types
// L-POS on mill3" and "all types on that file" must agree.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;

const std::string kMill3 = test::machine_path("mill3");
const std::string kFiles = " --var " + test::source_path("tests/programs/mill3.var") + " --tool-table " +
                           test::source_path("tests/programs/mill3.tbl");

std::vector<std::string> split(const std::string& line, char by) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, by);) cells.push_back(cell);
  return cells;
}

// A copy of mill3's table `name` with only the column `keep` (the others 0). `pole_shift`: z.csv
// was measured off the Z pole (measured_at_mm r = [0, -80, -60] mm), which the loader takes to
// the pole with the table's angular columns (delta_pole = delta - eps x r); without them the
// positioning column is written at the pole here: EZZ - (eps x r)_z = EZZ - EAZ r_y = EZZ + 80 mm
// EAZ (small angles: the exact rotation differs by eps^2 r, 1e-5 um).
void write_one_column_table(const fs::path& to, const std::string& name, const std::string& keep,
                            bool pole_shift = false) {
  std::ifstream in(test::source_path("tables/data/mill3/" + name));
  std::ofstream out(to / name);
  std::vector<std::string> header;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') {
      out << line << '\n';
      continue;
    }
    if (header.empty()) {
      header = split(line, ',');
      out << line << '\n';
      continue;
    }
    const std::vector<std::string> cells = split(line, ',');
    out << cells[0];
    for (std::size_t c = 1; c < cells.size(); ++c) {
      double value = 0.0;
      if (header[c].rfind(keep + "[", 0) == 0) {
        value = std::stod(cells[c]);
        if (pole_shift) {
          const double eaz_rad = std::stod(cells[4]) * M_PI / 648000.0;  // EAZ[arcsec]
          EXPECT_EQ(header[4], "EAZ[arcsec]");
          value += 80.0e3 * eaz_rad;  // um
        }
      }
      char text[40];
      std::snprintf(text, sizeof text, "%.17g", value);
      out << ',' << text;
    }
    out << '\n';
  }
}

// mill3 with its L-POS errors only: the squarenesses (L-SQU) 0, the cross-axis table EZZ(z, y)
// (L-POS and L-SPEC) left out, the tables of x, y and z with their positioning column alone.
std::string write_mill3_l_pos_only(const std::string& test) {
  // A folder per test: CTest runs them side by side, and each rewrites its folder.
  const fs::path dir = fs::temp_directory_path() / ("volcomp_types_mill3_l_pos_" + test);
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_one_column_table(dir, "x.csv", "EXX");
  write_one_column_table(dir, "y.csv", "EYY");
  write_one_column_table(dir, "z.csv", "EZZ", true);
  std::ifstream in(kMill3);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::ofstream out(dir / "mill3_l_pos.toml");
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string line = lines[i];
    if (i + 1 < lines.size() && lines[i + 1].find("z_by_y.csv") != std::string::npos) {
      ++i;  // the cross-axis table's [[tool_chain.tables]] and its file
      continue;
    }
    if (line.find("measured_at_mm") != std::string::npos) continue;
    line = std::regex_replace(line, std::regex("^(E[ABC]0[XYZ]_arcsec) = .*"), "$1 = 0.0");
    line = std::regex_replace(line, std::regex("\"\\.\\./\\.\\./tables/data/mill3/"), "\"");
    out << line << '\n';
  }
  return (dir / "mill3_l_pos.toml").string();
}

// The program's lines without its comments (the header names the files and the types),
// compared number by number to the printed precision (one unit of the last digit either prints).
void expect_same_program(const std::string& a, const std::string& b) {
  const auto body = [](const std::string& text) {
    std::vector<std::string> lines;
    for (const std::string& line : split(text, '\n'))
      if (!line.empty() && line[0] != '(') lines.push_back(line);
    return lines;
  };
  const std::vector<std::string> la = body(a), lb = body(b);
  ASSERT_EQ(la.size(), lb.size());
  const std::regex number("-?[0-9]+(\\.[0-9]*)?");
  int compared = 0;
  for (std::size_t i = 0; i < la.size(); ++i) {
    EXPECT_EQ(std::regex_replace(la[i], number, "#"), std::regex_replace(lb[i], number, "#"))
        << la[i] << " / " << lb[i];
    std::sregex_iterator ia(la[i].begin(), la[i].end(), number), ib(lb[i].begin(), lb[i].end(), number), end;
    for (; ia != end && ib != end; ++ia, ++ib) {
      const std::string ta = ia->str(), tb = ib->str();
      const auto decimals = [](const std::string& t) {
        const auto dot = t.find('.');
        return dot == std::string::npos ? 0 : static_cast<int>(t.size() - dot - 1);
      };
      const double unit = std::pow(10.0, -std::max(decimals(ta), decimals(tb)));
      EXPECT_LE(std::abs(std::stod(ta) - std::stod(tb)), 1.001 * unit)
          << "line " << i << ": " << la[i] << " / " << lb[i];
      ++compared;
    }
  }
  EXPECT_GT(compared, 500);
}

std::string predistort(const std::string& machine, const std::string& output, const std::string& options) {
  fs::remove(output);
  const auto r =
      test::run_volcomp("predistort " + machine + " " + test::source_path("tests/programs/mill3_pocket.ngc") + " -o " +
                        output + kFiles + options);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  return test::file_text(output);
}

// predistort --types L-POS on mill3 writes the program predistort writes for the machine with the
// other types' errors zeroed; its header names the types; all types give another program.
TEST(VolcompTypes, PredistortOfLPosEqualsTheMachineWithTheOtherErrorsZeroed) {
  const std::string l_pos_only = write_mill3_l_pos_only("predistort");
  const fs::path dir = fs::temp_directory_path();
  const std::string selected = predistort(kMill3, (dir / "volcomp_types_selected.ngc").string(), " --types L-POS");
  const std::string zeroed = predistort(l_pos_only, (dir / "volcomp_types_zeroed.ngc").string(), "");
  const std::string all = predistort(kMill3, (dir / "volcomp_types_all.ngc").string(), "");
  expect_same_program(selected, zeroed);
  EXPECT_NE(selected.find("; compensation types: L-POS)"), std::string::npos) << selected.substr(0, 600);
  EXPECT_NE(all.find("; compensation types: all)"), std::string::npos) << all.substr(0, 600);
  EXPECT_NE(selected, all);
}

// The selection is applied after --temperature: with thermal off, a program made for 27 degC is
// the one made at the references (the header says the temperature is not compensated), with
// thermal on it is another.
TEST(VolcompTypes, PredistortWithoutThermalTakesTheTemperaturesBackToTheirReferences) {
  const std::string machine = test::machine_path("mc300_thermal");
  const std::string program = test::source_path("tests/programs/mc300_swarf.ngc");
  const std::string files = " --var " + test::source_path("tests/programs/mc300.var") + " --tool-table " +
                            test::source_path("tests/programs/mc300.tbl") + " -q";
  const std::string no_thermal = " --types L-VOL+,R-VOL+,L-SPEC,R-SPEC";
  const auto run = [&](const std::string& name, const std::string& options) {
    const std::string out = (fs::temp_directory_path() / ("volcomp_types_" + name + ".ngc")).string();
    fs::remove(out);
    const auto r = test::run_volcomp("predistort " + machine + " " + program + " -o " + out + files + options);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    std::string body;
    for (const std::string& line : split(test::file_text(out), '\n'))
      if (line.empty() || line[0] != '(') body += line + '\n';
    return std::make_pair(body, test::file_text(out));
  };
  const auto at_reference = run("reference", no_thermal);
  const auto warm_off = run("warm_off", no_thermal + " --temperature spindle=27");
  const auto warm_on = run("warm_on", " --temperature spindle=27");
  EXPECT_GT(at_reference.first.size(), 10000u);
  EXPECT_EQ(warm_off.first, at_reference.first);
  EXPECT_NE(warm_on.first, at_reference.first);
  EXPECT_NE(warm_off.second.find("spindle 27 degC [not compensated: thermal is off]"), std::string::npos)
      << warm_off.second.substr(0, 600);
  EXPECT_NE(warm_off.second.find("compensation types: L-POS, L-STR, L-SQU, L-ANG, R-POS, R-RAX, R-POR, R-ANG, "
                                 "L-SPEC, R-SPEC, FOR)"),
            std::string::npos)
      << warm_off.second.substr(0, 600);
}

// A trace of a session whose volkins corrected L-POS only (its joints made by the core with the
// L-POS-only machine file, through LinuxCNC's joint interpolation): `trace --types L-POS` finds
// the module equal to the core; with every type the core's joints differ by the squareness.
TEST(VolcompTypes, TraceWithTheSessionsTypesChecksTheModuleAgainstTheSameSelection) {
  const machine::Model zeroed = machine::load_machine(write_mill3_l_pos_only("trace"));
  const double offset_mm = 100.0;
  const double L = zeroed.correction_length(offset_mm);
  std::vector<machine::Joints> world, p;
  for (int k = 0; k < 40; ++k) {
    machine::Joints w(3);
    w << 100.0 + 0.2 * k, 250.0 - 0.1 * k, -40.0 - 0.15 * k;  // 1 ms cycles at 16 m/min
    machine::Joints q;
    ASSERT_EQ(machine::joints_from_world(zeroed, machine::WorldConvention::Axes, w, L, q), machine::Status::Ok);
    world.push_back(w);
    p.push_back(q);
  }
  const fs::path trace = fs::temp_directory_path() / "volcomp_types_trace.csv";
  {
    std::ofstream out(trace);
    out << "x,y,z,j0,j1,j2,gain,tool_offset,controller_time\n";
    out.precision(17);
    for (std::size_t n = 0; n < world.size(); ++n) {
      const machine::Joints j = n < 3 ? p[n] : machine::Joints((p[n - 3] + 4 * p[n - 2] + p[n - 1]) / 6);
      out << world[n][0] << ',' << world[n][1] << ',' << world[n][2] << ',' << j[0] << ',' << j[1] << ',' << j[2]
          << ",1," << offset_mm << ',' << 1000 * n << '\n';
    }
  }
  const auto mismatch = [](const std::string& out) {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(out, m, std::regex("module against the core \\(joints[^)]*\\): max ([-0-9.e+]+)")))
        << out;
    return m.size() > 1 ? std::stod(m[1].str()) : -1.0;
  };
  const auto with_types = test::run_volcomp("trace " + kMill3 + " " + trace.string() + " --types L-POS");
  ASSERT_EQ(with_types.exit_code, 0) << with_types.out;
  EXPECT_LT(mismatch(with_types.out), 1e-6) << with_types.out;
  EXPECT_NE(with_types.out.find("the core with the types L-POS"), std::string::npos) << with_types.out;
  // The tool tip: the real machine keeps its squareness (um); the L-POS errors are corrected.
  EXPECT_NE(with_types.out.find("of the compensation types corrected (L-POS; the others' errors left out): tool tip "
                                "error max 0.000 um"),
            std::string::npos)
      << with_types.out;
  const auto all = test::run_volcomp("trace " + kMill3 + " " + trace.string());
  ASSERT_EQ(all.exit_code, 0) << all.out;
  EXPECT_GT(mismatch(all.out), 1e-3) << all.out;  // 8 arcsec of EC0X over 200 mm of Y: ~8 um
}

// selftune --compensated --types: the part cut with volkins correcting L-POS only (simulated with
// the L-POS-only file as the compensation) is what the model predicts with those types, so the
// model strategy finds nothing left to explain; taken as cut with every type, it finds the
// squarenesses. Pre-distorted, the model strategy's next program is made for the types given;
// with the local strategy --types would change nothing: refused.
TEST(VolcompTypes, SelftuneTakesThePartAsCutWithTheTypesGiven) {
  const std::string l_pos_only = write_mill3_l_pos_only("selftune");
  const fs::path dir = fs::temp_directory_path() / "volcomp_types_selftune";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string program = test::source_path("tests/programs/selftune/part_a.ngc");
  const std::string path = (dir / "part_a_path.csv").string(), report = (dir / "part_a_report.csv").string();
  auto r = test::run_volcomp("simulate " + kMill3 + " " + program + " -o " + path + kFiles + " --compensation " +
                             l_pos_only);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  r = test::run_volcomp("measure " + path + " " + test::source_path("tests/programs/selftune/part_a_points.csv") +
                        " -o " + report);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto unexplained = [&](const std::string& types) {
    const auto s =
        test::run_volcomp("selftune " + kMill3 + " " + program + " " + report + kFiles +
                          " --compensated --strategy model --tables-out " + (dir / "tuned").string() + types);
    EXPECT_EQ(s.exit_code, 0) << s.out;
    std::smatch m;
    EXPECT_TRUE(std::regex_search(s.out, m, std::regex("unexplained by the model RMS ([0-9.]+) um"))) << s.out;
    return std::make_pair(m.size() > 1 ? std::stod(m[1].str()) : -1.0, s.out);
  };
  const auto [with_types, out] = unexplained(" --types L-POS");
  EXPECT_LT(with_types, 0.01) << out;
  EXPECT_NE(out.find("load it in volkins with the same compensation types on (L-POS)"), std::string::npos) << out;
  const auto [all, all_out] = unexplained("");
  EXPECT_GT(all, 1.0) << all_out;

  // Pre-distorted PROGRAM, model strategy: the next program is pre-distorted with the tuned
  // tables for the types given, as predistort --types makes it from the tuned machine file.
  const std::string next = (dir / "next.ngc").string(), again = (dir / "again.ngc").string();
  r = test::run_volcomp("selftune " + kMill3 + " " + program + " " + report + kFiles +
                        " --strategy model --tables-out " + (dir / "tuned_next").string() + " -o " + next +
                        " --types L-POS");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  r = test::run_volcomp("predistort " + (dir / "tuned_next" / "mill3.toml").string() + " " + program + " -o " + again +
                        kFiles + " --types L-POS");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  expect_same_program(test::file_text(next), test::file_text(again));
  EXPECT_NE(test::file_text(next).find("; compensation types: L-POS)"), std::string::npos);

  fs::remove(next);
  r = test::run_volcomp("selftune " + kMill3 + " " + program + " " + report + kFiles + " -o " + next +
                        " --types L-POS");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--types L-POS changes nothing here"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(next));
}

// A list with a code that is no type is refused by each command before it writes: the reason
// from the core, exit 2, no output.
TEST(VolcompTypes, ABadListIsRefusedWithTheCodeItCannotRead) {
  const fs::path out = fs::temp_directory_path() / "volcomp_types_refused.out";
  const std::string program = test::source_path("tests/programs/mill3_pocket.ngc");
  const std::string trace = (fs::temp_directory_path() / "volcomp_types_refused_trace.csv").string();
  std::ofstream(trace) << "x,y,z,j0,j1,j2,gain,tool_offset,controller_time\n";
  const std::vector<std::string> commands = {
      "predistort " + kMill3 + " " + program + " -o " + out.string() + kFiles,
      "selftune " + kMill3 + " " + program + " " + test::source_path("tests/programs/selftune/part_a_points.csv") +
          " -o " + out.string() + kFiles + " --compensated",
      "trace " + kMill3 + " " + trace + " -o " + out.string(),
  };
  for (const std::string& command : commands) {
    fs::remove(out);
    const auto r = test::run_volcomp(command + " --types L-POS,L-PSO");
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.out;
    EXPECT_NE(r.out.find("--types L-POS,L-PSO: 'L-PSO' is no compensation type: give L-POS, L-STR"), std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(out)) << command;
  }
}

}  // namespace
}  // namespace vc
