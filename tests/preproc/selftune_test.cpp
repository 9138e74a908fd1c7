// Self-tuning proved on a virtual shop (issue: "Self-tuning from the first part").
//
// The true machine is mill3 with every table off by a smooth 20-50 % (volcomp perturb): the
// model the shop believes in (machines/data/mill3.toml) is what was measured, the machine is
// what it really is. Part 1 is the original program pre-distorted with the model; the part
// is machined on the true machine (volcomp simulate), measured by the virtual CMM with 1 um
// noise (volcomp measure), and the next program derived from the report (volcomp selftune).
// The form error of each part (largest |deviation| over the CMM plan, measured without
// noise) is the figure of merit. Everything goes through the volcomp command line, as a
// shop would run it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <sstream>

#include "test_support.hpp"
#include "vc/shop/cmm.hpp"
#include "vc/shop/first_part.hpp"
#include "vc/shop/tool_path.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;

constexpr double kNoiseUm = 1.0;

std::string source(const std::string& relative) { return test::source_path(relative); }

std::string run_ok(const std::string& args) {
  const test::CommandResult r = test::run_volcomp(args);
  EXPECT_EQ(r.exit_code, 0) << "volcomp " << args << "\n" << r.out;
  return r.out;
}

// A part's form error (measured without noise): largest |deviation|, peak to valley, RMS.
struct Form {
  double largest_um = 0, pv_um = 0, rms_um = 0;
};

// Machines `program` on `true_machine` (volcomp simulate with `files`: --var, --tool-table,
// --world) and measures it at the points of `plan`: the report with noise (its seed) for the
// tuning, and the form error without noise.
Form test_part(const std::string& true_machine, const std::string& files, const std::string& program,
               const std::string& plan, const std::string& report, unsigned seed) {
  const std::string tool_path = report + ".path.csv";  // (beside the report: the program may be a source file)
  run_ok("simulate " + true_machine + " " + program + " -o " + tool_path + files);
  run_ok("measure " + tool_path + " " + plan + " -o " + report + " --noise " + std::to_string(kNoiseUm) + " --seed " +
         std::to_string(seed));
  run_ok("measure " + tool_path + " " + plan + " -o " + report + ".exact.csv");
  const std::vector<shop::CmmPoint> exact = shop::read_cmm_points(report + ".exact.csv", true);
  const shop::FormError f = shop::form_error(exact);
  double low = 1e300, high = -1e300;
  for (const shop::CmmPoint& p : exact) low = std::min(low, *p.deviation_mm), high = std::max(high, *p.deviation_mm);
  return {f.largest_mm * 1e3, (high - low) * 1e3, f.rms_mm * 1e3};
}

class VirtualShop : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("vc_selftune_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    run("perturb " + test::machine_path("mill3") + " -o " + path("true") + " --seed 11");
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string path(const std::string& name) { return (dir_ / name).string(); }
  static std::string run(const std::string& args) { return run_ok(args); }
  static std::string files() {
    return " --var " + source("tests/programs/mill3.var") + " --tool-table " + source("tests/programs/mill3.tbl");
  }
  static std::string part(const std::string& name) { return source("tests/programs/selftune/" + name); }

  static double machine_and_measure(const std::string& program, const std::string& plan, const std::string& report,
                                    unsigned seed) {
    return test_part(path("true/mill3.toml"), files(), program, plan, report, seed).largest_um;
  }

  static fs::path dir_;
};
fs::path VirtualShop::dir_;

TEST_F(VirtualShop, LocalStrategyTakesThePartsFormErrorToTheNoise) {
  const std::string plan = part("part_a_points.csv");
  run("predistort " + test::machine_path("mill3") + " " + part("part_a.ngc") + " -o " + path("local_p1.ngc") + files());
  std::vector<double> form;
  for (int i = 1; i <= 3; ++i) {
    const std::string program = path("local_p" + std::to_string(i) + ".ngc");
    const std::string report = path("local_r" + std::to_string(i) + ".csv");
    form.push_back(machine_and_measure(program, plan, report, static_cast<unsigned>(i)));
    std::cout << "local strategy, part " << i << ": form error " << form.back() << " um\n";
    if (i < 3)
      std::cout << run("selftune " + test::machine_path("mill3") + " " + program + " " + report + " -o " +
                       path("local_p" + std::to_string(i + 1) + ".ngc") + files());
  }
  EXPECT_GT(form[0], 5.0) << "the true machine should differ enough from the model to need tuning";
  for (int i = 1; i < 3; ++i)
    EXPECT_LE(form[static_cast<std::size_t>(i)], std::max(0.1 * form[0], 2 * kNoiseUm)) << "part " << i + 1;
}

TEST_F(VirtualShop, ModelStrategyTunesTablesThatCarryOverToADifferentPart) {
  const std::string plan = part("part_a_points.csv");
  const std::string p0 = part("part_a.ngc");
  run("predistort " + test::machine_path("mill3") + " " + p0 + " -o " + path("model_p1.ngc") + files());
  std::string machine = test::machine_path("mill3");
  std::vector<double> form;
  for (int i = 1; i <= 3; ++i) {
    const std::string program = path("model_p" + std::to_string(i) + ".ngc");
    const std::string report = path("model_r" + std::to_string(i) + ".csv");
    form.push_back(machine_and_measure(program, plan, report, static_cast<unsigned>(10 + i)));
    std::cout << "model strategy, part " << i << ": form error " << form.back() << " um\n";
    if (i < 3) {
      const std::string tables = path("tables" + std::to_string(i));
      std::cout << run("selftune " + machine + " " + program + " " + report + " -o " +
                       path("model_p" + std::to_string(i + 1) + ".ngc") + " --strategy model --nominal " + p0 +
                       " --tables-out " + tables + files());
      machine = tables + "/mill3.toml";
    }
  }
  EXPECT_GT(form[0], 5.0);
  for (int i = 1; i < 3; ++i)
    EXPECT_LE(form[static_cast<std::size_t>(i)], std::max(0.1 * form[0], 2 * kNoiseUm)) << "part " << i + 1;

  // A different part, pre-distorted with the measured tables and with the tuned ones.
  const std::string plan_b = part("part_b_points.csv");
  run("predistort " + test::machine_path("mill3") + " " + part("part_b.ngc") + " -o " + path("b_model.ngc") + files());
  run("predistort " + machine + " " + part("part_b.ngc") + " -o " + path("b_tuned.ngc") + files());
  const double before = machine_and_measure(path("b_model.ngc"), plan_b, path("b_model.csv"), 21);
  const double after = machine_and_measure(path("b_tuned.ngc"), plan_b, path("b_tuned.csv"), 22);
  std::cout << "part B: form error " << before << " um with the measured tables, " << after
            << " um with the tuned ones (" << 100 * (1 - after / before) << " % better)\n";
  EXPECT_LE(after, 0.3 * before);
}

// Rewrites a report with `change(point)` added to each deviation (um).
template <typename Change>
std::string disturbed(const std::string& report, const std::string& out, Change change) {
  std::vector<shop::CmmPoint> points = shop::read_cmm_points(report, true);
  for (shop::CmmPoint& p : points) *p.deviation_mm += change(p) * 1e-3;
  std::ofstream file(out);
  shop::write_cmm_report(file, points, {"disturbed for the test"});
  return out;
}

TEST_F(VirtualShop, DwellMarksAndVibrationWavesAreFlaggedOrFilteredNotTuned) {
  const std::string plan = part("part_a_points.csv");
  run("predistort " + test::machine_path("mill3") + " " + part("part_a.ngc") + " -o " + path("dwell_p1.ngc") + files());
  const std::string clean = path("dwell_r1.csv");
  machine_and_measure(path("dwell_p1.ngc"), plan, clean, 31);
  // A dwell mark: two neighbouring points cut 15 um deep where the tool stood under load;
  // a vibration trace: 1.5 um at a wavelength of 0.75 mm (15-17 Hz at 720 mm/min, seeds/000 ch. V).
  const std::vector<shop::CmmPoint> points = shop::read_cmm_points(clean, true);
  const std::string mark_a = points.at(3).id, mark_b = points.at(4).id;
  const std::string report = disturbed(clean, path("dwell_disturbed.csv"), [&](const shop::CmmPoint& p) {
    const double dwell = (p.id == mark_a || p.id == mark_b) ? -15.0 : 0.0;
    return dwell + 1.5 * std::sin(2 * M_PI * (p.nominal.x() + p.nominal.y()) / 0.75);
  });
  const std::string summary = run("selftune " + test::machine_path("mill3") + " " + path("dwell_p1.ngc") + " " +
                                  report + " -o " + path("dwell_p2.ngc") + files());
  std::cout << summary;
  EXPECT_NE(summary.find("outlier " + mark_a + " "), std::string::npos);
  EXPECT_NE(summary.find("outlier " + mark_b + " "), std::string::npos);
  EXPECT_NE(summary.find(" 2 outliers left out"), std::string::npos);
  run("selftune " + test::machine_path("mill3") + " " + path("dwell_p1.ngc") + " " + clean + " -o " +
      path("dwell_clean_p2.ngc") + files());
  const double with = machine_and_measure(path("dwell_p2.ngc"), plan, path("dwell_r2.csv"), 32);
  const double without = machine_and_measure(path("dwell_clean_p2.ngc"), plan, path("dwell_clean_r2.csv"), 32);
  std::cout << "part 2 form error: " << with << " um from the disturbed report, " << without
            << " um from the clean one\n";
  EXPECT_LE(with, without + 1.0);
}

TEST_F(VirtualShop, ReportsThatDoNotFitTheProgramAreRefused) {
  run("predistort " + test::machine_path("mill3") + " " + part("part_a.ngc") + " -o " + path("fit_p1.ngc") + files());
  run("predistort " + test::machine_path("mill3") + " " + part("part_b.ngc") + " -o " + path("fit_b.ngc") + files());
  const std::string report_a = path("fit_r1.csv"), report_b = path("fit_rb.csv");
  machine_and_measure(path("fit_p1.ngc"), part("part_a_points.csv"), report_a, 41);
  machine_and_measure(path("fit_b.ngc"), part("part_b_points.csv"), report_b, 42);
  const std::string next = path("fit_p2.ngc");
  // Part B's report against part A's program: points where A cuts nothing.
  test::CommandResult r = test::run_volcomp("selftune " + test::machine_path("mill3") + " " + path("fit_p1.ngc") + " " +
                                            report_b + " -o " + next + files());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("report points lie on a surface"), std::string::npos) << r.out;  // too few: refused
  EXPECT_NE(r.out.find("for this program?"), std::string::npos) << r.out;  // the cause tested: not spindle, tool, unit
  EXPECT_NE(r.out.find(report_b), std::string::npos) << r.out;
  // Deviations in um under a header that says mm.
  std::string text;
  {
    std::ifstream in(report_a);
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  const std::string wrong = path("fit_wrong_unit.csv");
  std::ofstream(wrong) << text.replace(text.find("deviation[um]"), 13, "deviation[mm]");
  r = test::run_volcomp("selftune " + test::machine_path("mill3") + " " + path("fit_p1.ngc") + " " + wrong + " -o " +
                        next + files());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("is the unit in the report's header right?"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(next));
  // The right report with its coordinates written in inches under a header that says mm: most
  // points land on the cuts once read as inches, and the message says so.
  {
    std::istringstream in(text);
    std::ostringstream inches;
    std::vector<bool> in_mm;  // the header's columns in mm
    const auto split = [](const std::string& row) {
      std::vector<std::string> cells;
      std::stringstream cs(row);
      for (std::string c; std::getline(cs, c, ',');) cells.push_back(c);
      return cells;
    };
    for (std::string row; std::getline(in, row);) {
      if (!in_mm.empty() && !row.empty() && row[0] != '#') {
        std::vector<std::string> cells = split(row);
        for (std::size_t i = 0; i < cells.size() && i < in_mm.size(); ++i)
          if (in_mm[i]) cells[i] = std::to_string(std::stod(cells[i]) / 25.4);
        row.clear();
        for (std::size_t i = 0; i < cells.size(); ++i) row += (i ? "," : "") + cells[i];
      } else if (row.find("x[mm]") != std::string::npos) {
        for (const std::string& c : split(row)) in_mm.push_back(c.find("[mm]") != std::string::npos);
      }
      inches << row << "\n";
    }
    std::ofstream(path("fit_inches.csv")) << inches.str();
  }
  r = test::run_volcomp("selftune " + test::machine_path("mill3") + " " + path("fit_p1.ngc") + " " +
                        path("fit_inches.csv") + " -o " + next + files());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("read as inches"), std::string::npos) << r.out;
  // The right report, but a program that never starts the spindle: nothing is cut, and the
  // message says why rather than blaming the report.
  std::string program;
  {
    std::ifstream in(path("fit_p1.ngc"));
    std::stringstream s;
    s << in.rdbuf();
    program = s.str();
  }
  const std::size_t m3 = program.find("S8000 M3");
  ASSERT_NE(m3, std::string::npos);
  std::ofstream(path("fit_no_spindle.ngc")) << program.replace(m3, 8, "S8000");
  r = test::run_volcomp("selftune " + test::machine_path("mill3") + " " + path("fit_no_spindle.ngc") + " " + report_a +
                        " -o " + next + files());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("the program cuts nothing: no feed move runs with the spindle on"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(next));
}

// The report as CMM software exports it (cmm_export.hpp): a preamble, a units line in inches,
// semicolons and decimal commas, the columns in another order with their usual names, the
// actual point and the deviation (sign stated) beside tolerances. Written from our report to
// 7 decimals of an inch (2.5 nm), it must give the same next program as our CSV.
std::string as_cmm_export(const std::vector<shop::CmmPoint>& points, const std::string& out) {
  std::ofstream file(out);
  file << "Part: part A, first part\nUnits: inch\n"
       << "Point Name;X Nom;Y Nom;Z Nom;X Act;Y Act;Z Act;I;J;K;Dev;Tol+;Tol-\n";
  const auto number = [](double v, int decimals) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
    std::string text = buffer;
    std::replace(text.begin(), text.end(), '.', ',');
    return text;
  };
  for (const shop::CmmPoint& p : points) {
    const Eigen::Vector3d actual = p.nominal + *p.deviation_mm * p.normal;
    file << '"' << p.id << '"';
    for (int a = 0; a < 3; ++a) file << ';' << number(p.nominal[a] / 25.4, 7);
    for (int a = 0; a < 3; ++a) file << ';' << number(actual[a] / 25.4, 7);
    for (int a = 0; a < 3; ++a) file << ';' << number(p.normal[a], 9);
    file << ';' << number(*p.deviation_mm / 25.4, 7) << ";0,001;-0,001\n";
  }
  return out;
}

// The numbers of a program, in order (words' values and comments' numbers alike).
std::vector<double> numbers_of(const std::string& program) {
  std::ifstream in(program);
  std::vector<double> numbers;
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t start = text.find_first_of("-0123456789", at);
    if (start == std::string::npos) break;
    std::size_t used = 1;
    if (std::isdigit(static_cast<unsigned char>(text[start + (text[start] == '-')])))
      numbers.push_back(std::stod(text.substr(start, 40), &used));
    at = start + used;
  }
  return numbers;
}

TEST_F(VirtualShop, ACmmExportInInchesGivesTheSamePartAsOurCsv) {
  const std::string plan = part("part_a_points.csv");
  run("predistort " + test::machine_path("mill3") + " " + part("part_a.ngc") + " -o " + path("export_p1.ngc") +
      files());
  const std::string ours = path("export_r1.csv");
  const double part1 = machine_and_measure(path("export_p1.ngc"), plan, ours, 51);
  const std::string exported = as_cmm_export(shop::read_cmm_points(ours, true), path("export_r1.txt"));
  const std::string tune = "selftune " + test::machine_path("mill3") + " " + path("export_p1.ngc") + " ";
  run(tune + ours + " -o " + path("export_ours_p2.ngc") + files());
  // Without the options the file needs, it is refused and nothing is written.
  const test::CommandResult r = test::run_volcomp(tune + exported + " -o " + path("export_p2.ngc") + files());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find(exported + ":4:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("has a comma: give --decimal-comma"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(path("export_p2.ngc")));
  const std::string summary = run(tune + exported + " -o " + path("export_p2.ngc") + files() +
                                  " --decimal-comma --deviation-sign actual-minus-nominal");
  std::cout << summary;
  EXPECT_NE(summary.find("read as a CMM export, semicolon-separated, header on line 3"), std::string::npos) << summary;
  EXPECT_NE(summary.find("[inch]"), std::string::npos) << summary;
  // The same program, to the last digit or one more (the report's inches round at 2.5 nm).
  const std::vector<double> a = numbers_of(path("export_ours_p2.ngc")), b = numbers_of(path("export_p2.ngc"));
  ASSERT_EQ(a.size(), b.size());
  double largest = 0;
  for (std::size_t i = 0; i < a.size(); ++i) largest = std::max(largest, std::abs(a[i] - b[i]));
  EXPECT_LE(largest, 2e-4);
  const double ours2 = machine_and_measure(path("export_ours_p2.ngc"), plan, path("export_ours_r2.csv"), 52);
  const double export2 = machine_and_measure(path("export_p2.ngc"), plan, path("export_r2.csv"), 52);
  std::cout << "part 1 " << part1 << " um; part 2 from our CSV " << ours2 << " um, from the CMM export in inches "
            << export2 << " um (programs differ by at most " << largest << " mm)\n";
  EXPECT_NEAR(export2, ours2, 0.05);
}

// A report always has points near edges or on faces the program does not cut: they are left
// out and listed with the reason, and the part is tuned from the others.
TEST_F(VirtualShop, PointsOnNoCutSurfaceAreLeftOutWithTheReason) {
  run("predistort " + test::machine_path("mill3") + " " + part("part_a.ngc") + " -o " + path("extra_p1.ngc") + files());
  const std::string report = path("extra_r1.csv");
  machine_and_measure(path("extra_p1.ngc"), part("part_a_points.csv"), report, 43);
  std::string text;
  {
    std::ifstream in(report);
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  // Two more points: one far outside the part, one 5 mm above the top face (uncut air).
  const std::size_t header = text.find("id,");
  ASSERT_NE(header, std::string::npos);
  const std::string columns = text.substr(header, text.find('\n', header) - header);
  ASSERT_EQ(columns.rfind("id,x[mm],y[mm],z[mm],i,j,k,", 0), 0u) << columns;
  const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  text += "EXTRA_FAR,900,0,-5,1,0,0,0.0\nEXTRA_AIR,0,0,5,0,0,1,0.0\n";
  const std::string extended = path("extra_r1_more.csv");
  std::ofstream(extended) << text;
  const test::CommandResult r =
      test::run_volcomp("selftune " + test::machine_path("mill3") + " " + path("extra_p1.ngc") + " " + extended +
                        " -o " + path("extra_p2.ngc") + files());
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("2 points left out, on no surface the program cuts"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("left out EXTRA_FAR (report line " + std::to_string(lines + 1) + "): outside the region"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("left out EXTRA_AIR (report line " + std::to_string(lines + 2) + "): no cut reaches it"),
            std::string::npos)
      << r.out;
  EXPECT_TRUE(fs::exists(path("extra_p2.ngc")));
}

// The 5-axis proof (issue 22): the MC-300 (table-table, a full-turn C), run in the tcp world,
// the true machine = the model with every table and location error off by 20-50 %; a 3+2
// pocket at B-45 C120 (tests/programs/selftune/make_parts_5axis.py: floor and walls, 166
// points). Targets at 1 um noise: part 2 RMS <= 0.7 um and peak-to-valley <= 3 um.
class VirtualShop5Axis : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("vc_selftune5_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    run_ok("perturb " + test::machine_path("mc300") + " -o " + path("true") + " --seed 5");
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static std::string path(const std::string& name) { return (dir_ / name).string(); }
  static std::string files() {
    return " --world tcp --var " + source("tests/programs/mc300.var") + " --tool-table " +
           source("tests/programs/mc300.tbl");
  }
  static std::string part(const std::string& name) { return source("tests/programs/selftune/" + name); }
  static Form measured(const std::string& program, const std::string& plan, const std::string& report, unsigned seed) {
    return test_part(path("true/mc300.toml"), files(), program, plan, report, seed);
  }
  static fs::path dir_;
};
fs::path VirtualShop5Axis::dir_;

TEST_F(VirtualShop5Axis, BothStrategiesTakeA32PocketToTheNoise) {
  const std::string plan = part("pocket_32_a_points.csv"), p0 = part("pocket_32_a.ngc");
  run_ok("predistort " + test::machine_path("mc300") + " " + p0 + " -o " + path("p1.ngc") + files());
  const Form part1 = measured(path("p1.ngc"), plan, path("r1.csv"), 1);
  std::cout << "3+2 pocket, part 1 (pre-distorted with the model): PV " << part1.pv_um << " um, RMS " << part1.rms_um
            << " um\n";
  EXPECT_GT(part1.pv_um, 10.0) << "the true machine should differ enough from the model to need tuning";

  std::cout << run_ok("selftune " + test::machine_path("mc300") + " " + path("p1.ngc") + " " + path("r1.csv") + " -o " +
                      path("local_p2.ngc") + files());
  const Form local = measured(path("local_p2.ngc"), plan, path("local_r2.csv"), 2);
  std::cout << "local strategy, part 2: PV " << local.pv_um << " um, RMS " << local.rms_um << " um\n";
  EXPECT_LE(local.rms_um, 0.7);
  EXPECT_LE(local.pv_um, 3.0);

  std::cout << run_ok("selftune " + test::machine_path("mc300") + " " + path("p1.ngc") + " " + path("r1.csv") + " -o " +
                      path("model_p2.ngc") + " --strategy model --nominal " + p0 + " --tables-out " + path("tuned") +
                      files());
  const Form model = measured(path("model_p2.ngc"), plan, path("model_r2.csv"), 3);
  std::cout << "model strategy, part 2: PV " << model.pv_um << " um, RMS " << model.rms_um << " um\n";
  EXPECT_LE(model.rms_um, 0.7);
  EXPECT_LE(model.pv_um, 3.0);

  // Another pocket at another pose (B-25 C235): raw, with the shipped model, with the tuned one.
  const std::string plan_b = part("pocket_32_b_points.csv"), b0 = part("pocket_32_b.ngc");
  run_ok("predistort " + test::machine_path("mc300") + " " + b0 + " -o " + path("b_model.ngc") + files());
  run_ok("predistort " + path("tuned/mc300.toml") + " " + b0 + " -o " + path("b_tuned.ngc") + files());
  const Form raw = measured(b0, plan_b, path("b_raw.csv"), 4);
  const Form shipped = measured(path("b_model.ngc"), plan_b, path("b_model.csv"), 5);
  const Form tuned = measured(path("b_tuned.ngc"), plan_b, path("b_tuned.csv"), 6);
  std::cout << "pocket B: PV raw " << raw.pv_um << " um, with the shipped model " << shipped.pv_um
            << " um, with the tables tuned on pocket A " << tuned.pv_um << " um\n";
  EXPECT_LT(tuned.pv_um, shipped.pv_um);  // one pose's part says little about another pose (see the README)
}

// A 5-axis swarf part: a conical pocket (wall tilted 40 deg) cut by the tool's side lying on
// the wall while C turns 360 deg, and its floor (make_parts_5axis.py, 189 points). The model
// strategy tunes tables and location errors that serve other parts: the 3+2 pocket at another
// pose and a cone of another angle.
TEST_F(VirtualShop5Axis, SwarfPartTunesTablesThatCarryOverToOtherParts) {
  const std::string plan = part("cone_a_points.csv"), p0 = part("cone_a.ngc");
  run_ok("predistort " + test::machine_path("mc300") + " " + p0 + " -o " + path("cone_p1.ngc") + files());
  const Form part1 = measured(path("cone_p1.ngc"), plan, path("cone_r1.csv"), 11);
  std::cout << "swarf cone, part 1 (pre-distorted with the model): PV " << part1.pv_um << " um, RMS " << part1.rms_um
            << " um\n";
  std::cout << run_ok("selftune " + test::machine_path("mc300") + " " + path("cone_p1.ngc") + " " +
                      path("cone_r1.csv") + " -o " + path("cone_model_p2.ngc") + " --strategy model --nominal " + p0 +
                      " --tables-out " + path("cone_tuned") + files());
  const Form model = measured(path("cone_model_p2.ngc"), plan, path("cone_model_r2.csv"), 12);
  std::cout << "model strategy, part 2: PV " << model.pv_um << " um, RMS " << model.rms_um << " um\n";
  EXPECT_LE(model.rms_um, 0.7);
  EXPECT_LE(model.pv_um, 3.0);

  // The local strategy: the cone's error changes along the wall with C (the cuts' tool
  // frames turn): the window's angle keeps to the cuts of nearby C. Its tilt here (some 30
  // urad, 0.3 um over the wall's height) is within the noise of the few points near each
  // piece: the printout says where it was turned.
  std::cout << run_ok("selftune " + test::machine_path("mc300") + " " + path("cone_p1.ngc") + " " +
                      path("cone_r1.csv") + " -o " + path("cone_local_p2.ngc") + files());
  const Form local = measured(path("cone_local_p2.ngc"), plan, path("cone_local_r2.csv"), 13);
  std::cout << "local strategy, part 2: PV " << local.pv_um << " um, RMS " << local.rms_um << " um\n";
  EXPECT_LE(local.rms_um, 0.7);
  EXPECT_LE(local.pv_um, 3.0);

  for (const std::string other : {"pocket_32_b", "cone_b"}) {
    const std::string plan_b = part(other + "_points.csv"), b0 = part(other + ".ngc");
    run_ok("predistort " + test::machine_path("mc300") + " " + b0 + " -o " + path(other + "_model.ngc") + files());
    run_ok("predistort " + path("cone_tuned/mc300.toml") + " " + b0 + " -o " + path(other + "_tuned.ngc") + files());
    const Form raw = measured(b0, plan_b, path(other + "_raw.csv"), 14);
    const Form shipped = measured(path(other + "_model.ngc"), plan_b, path(other + "_model.csv"), 15);
    const Form tuned = measured(path(other + "_tuned.ngc"), plan_b, path(other + "_tuned.csv"), 16);
    std::cout << other << ": PV raw " << raw.pv_um << " um, with the shipped model " << shipped.pv_um
              << " um, with the tables tuned on the cone " << tuned.pv_um << " um ("
              << 100 * (1 - tuned.pv_um / raw.pv_um) << " % below raw, " << 100 * (1 - tuned.pv_um / shipped.pv_um)
              << " % below the shipped model)\n";
    // Issue 22's targets (the cone of another angle meets them by a small margin: with
    // another noise draw it ended at 89.8 % below raw).
    EXPECT_LE(tuned.pv_um, 0.3 * shipped.pv_um) << other;
    EXPECT_LE(tuned.pv_um, 0.1 * raw.pv_um) << other;
  }
}

// How a swarf wall leans: the mean deviation of its lowest row of points minus its highest
// (WALL points of make_parts_5axis.py's cones, measured without noise), um.
double wall_lean_um(const std::string& exact_report) {
  std::map<double, std::pair<double, int>> rows;  // z -> sum, count
  for (const shop::CmmPoint& p : shop::read_cmm_points(exact_report, true))
    if (p.id.rfind("WALL", 0) == 0) {
      auto& row = rows[std::round(p.nominal.z() * 1e3) / 1e3];
      row.first += *p.deviation_mm;
      ++row.second;
    }
  if (rows.size() < 2) return 0.0;
  const auto mean = [](const std::pair<double, int>& r) { return r.first / r.second; };
  return (mean(rows.begin()->second) - mean(rows.rbegin()->second)) * 1e3;
}

// The tool-axis correction of the local strategy (issue 22): the true machine's spindle
// tilted by 50" and -40" (310 urad), which the model does not know: on the swarf cone the
// wall then leans with the height on the tool (about 2 um over its rows), which no shift of
// the tip takes off. The local strategy turns the tool axis (B and C) where the points tell
// the tilt; with --no-tilt the lean stays.
TEST_F(VirtualShop5Axis, LocalStrategyTurnsTheToolOnASwarfWall) {
  run_ok("perturb " + test::machine_path("mc300") + " -o " + path("tilted") + " --seed 5");
  {
    const std::string file = path("tilted/mc300.toml");
    std::ifstream in(file);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t spindle = text.find("[spindle]");
    ASSERT_NE(spindle, std::string::npos);
    text.insert(text.find("\n[", spindle) + 1, "[spindle.location]\nEA0S_arcsec = 50.0\nEB0S_arcsec = -40.0\n");
    std::ofstream(file) << text;
  }
  const auto measured_on_tilted = [&](const std::string& program, const std::string& report, unsigned seed) {
    return test_part(path("tilted/mc300.toml"), files(), program, part("cone_a_points.csv"), report, seed);
  };
  run_ok("predistort " + test::machine_path("mc300") + " " + part("cone_a.ngc") + " -o " + path("lean_p1.ngc") +
         files());
  const Form part1 = measured_on_tilted(path("lean_p1.ngc"), path("lean_r1.csv"), 21);
  const double lean1 = wall_lean_um(path("lean_r1.csv.exact.csv"));
  std::cout << "tilted spindle, part 1: PV " << part1.pv_um << " um, RMS " << part1.rms_um << " um, wall lean " << lean1
            << " um\n";
  ASSERT_GT(std::abs(lean1), 1.5) << "the tilted spindle should lean the wall";

  const std::string tilt_run = run_ok("selftune " + test::machine_path("mc300") + " " + path("lean_p1.ngc") + " " +
                                      path("lean_r1.csv") + " -o " + path("lean_tilt_p2.ngc") + files());
  std::cout << tilt_run;
  EXPECT_EQ(tilt_run.find("tool axis: turned on 0 pieces"), std::string::npos);
  const Form tilted = measured_on_tilted(path("lean_tilt_p2.ngc"), path("lean_tilt_r2.csv"), 22);
  const double lean2 = wall_lean_um(path("lean_tilt_r2.csv.exact.csv"));
  std::cout << "local strategy, part 2: PV " << tilted.pv_um << " um, RMS " << tilted.rms_um << " um, wall lean "
            << lean2 << " um\n";

  run_ok("selftune " + test::machine_path("mc300") + " " + path("lean_p1.ngc") + " " + path("lean_r1.csv") + " -o " +
         path("lean_tip_p2.ngc") + " --no-tilt" + files());
  const Form tip_only = measured_on_tilted(path("lean_tip_p2.ngc"), path("lean_tip_r2.csv"), 22);
  const double lean_tip = wall_lean_um(path("lean_tip_r2.csv.exact.csv"));
  std::cout << "local strategy --no-tilt, part 2: PV " << tip_only.pv_um << " um, RMS " << tip_only.rms_um
            << " um, wall lean " << lean_tip << " um\n";

  EXPECT_GT(std::abs(lean_tip), 0.7 * std::abs(lean1)) << "a shift of the tip leaves the lean";
  // Most of it: the tilt is shrunk by its noise, and each piece's comes from some 25 points
  // at 1 um noise (with noise seeds 11, 31, 41, 51 the lean left was 0.05-0.57 um).
  EXPECT_LT(std::abs(lean2), 0.4 * std::abs(lean1)) << "turning the tool takes most of it off";
  EXPECT_LT(tilted.rms_um, tip_only.rms_um);
  EXPECT_LE(tilted.rms_um, 0.7);
}

// The head-table case (issue 22): bc_head, the test machine whose B turns the head (a rotary
// axis in the tool chain) and C the table, on a turned fixture
// (tests/unit/machines/data/bc_head.toml), run in the tcp world; the true machine = the model
// with every table and location error off by 20-50 %. A 3+2 pocket at B-40 C60
// (make_parts_5axis.py: head_pocket_a, 60 x 40 x 8, 166 points). Targets at 1 um noise: part 2
// RMS <= 0.7 um and peak-to-valley <= 3 um with either strategy.
class VirtualShopHeadTable : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("vc_selftune_head_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    run_ok("perturb " + machine() + " -o " + path("true") + " --seed 5");
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static std::string machine() { return source("tests/unit/machines/data/bc_head.toml"); }
  static std::string path(const std::string& name) { return (dir_ / name).string(); }
  static std::string files() {
    return " --world tcp --var " + source("tests/programs/mc300.var") + " --tool-table " +
           source("tests/programs/mc300.tbl");
  }
  static Form measured(const std::string& program, const std::string& plan, const std::string& report, unsigned seed) {
    return test_part(path("true/bc_head.toml"), files(), program, plan, report, seed);
  }
  static fs::path dir_;
};
fs::path VirtualShopHeadTable::dir_;

TEST_F(VirtualShopHeadTable, BothStrategiesTakeA32PocketToTheNoise) {
  const std::string plan = source("tests/programs/selftune/head_pocket_a_points.csv");
  const std::string p0 = source("tests/programs/selftune/head_pocket_a.ngc");
  const Form raw = measured(p0, plan, path("r0.csv"), 1);
  run_ok("predistort " + machine() + " " + p0 + " -o " + path("p1.ngc") + files());
  const Form part1 = measured(path("p1.ngc"), plan, path("r1.csv"), 1);
  std::cout << "bc_head 3+2 pocket: raw PV " << raw.pv_um << " um, RMS " << raw.rms_um
            << " um; part 1 (pre-distorted with the model): PV " << part1.pv_um << " um, RMS " << part1.rms_um
            << " um\n";
  EXPECT_GT(part1.pv_um, 5.0) << "the true machine should differ enough from the model to need tuning";

  std::cout << run_ok("selftune " + machine() + " " + path("p1.ngc") + " " + path("r1.csv") + " -o " +
                      path("local_p2.ngc") + files());
  const Form local = measured(path("local_p2.ngc"), plan, path("local_r2.csv"), 2);
  std::cout << "local strategy, part 2: PV " << local.pv_um << " um, RMS " << local.rms_um << " um\n";
  EXPECT_LE(local.rms_um, 0.7);
  EXPECT_LE(local.pv_um, 3.0);

  const std::string summary =
      run_ok("selftune " + machine() + " " + path("p1.ngc") + " " + path("r1.csv") + " -o " + path("model_p2.ngc") +
             " --strategy model --nominal " + p0 + " --tables-out " + path("tuned") + files());
  std::cout << summary;
  EXPECT_NE(summary.find("EX0B = "), std::string::npos) << "the head's location errors are among the unknowns";
  const Form model = measured(path("model_p2.ngc"), plan, path("model_r2.csv"), 3);
  std::cout << "model strategy, part 2: PV " << model.pv_um << " um, RMS " << model.rms_um << " um\n";
  EXPECT_LE(model.rms_um, 0.7);
  EXPECT_LE(model.pv_um, 3.0);
  EXPECT_EQ(test::run_volcomp("check " + path("tuned/bc_head.toml")).exit_code, 0);

  // Another pocket at another pose (B30 C200, 50 x 50 x 6): raw, with the shipped model, with the tuned one.
  const std::string plan_b = source("tests/programs/selftune/head_pocket_b_points.csv");
  const std::string b0 = source("tests/programs/selftune/head_pocket_b.ngc");
  run_ok("predistort " + machine() + " " + b0 + " -o " + path("b_model.ngc") + files());
  run_ok("predistort " + path("tuned/bc_head.toml") + " " + b0 + " -o " + path("b_tuned.ngc") + files());
  const Form b_raw = measured(b0, plan_b, path("b_raw.csv"), 4);
  const Form b_shipped = measured(path("b_model.ngc"), plan_b, path("b_model.csv"), 5);
  const Form b_tuned = measured(path("b_tuned.ngc"), plan_b, path("b_tuned.csv"), 6);
  std::cout << "pocket B: PV raw " << b_raw.pv_um << " um, with the shipped model " << b_shipped.pv_um
            << " um, with the tables tuned on pocket A " << b_tuned.pv_um << " um\n";
  EXPECT_LT(b_tuned.pv_um, b_shipped.pv_um);  // one pose's part says little about another pose (see the README)
}

// The 5-axis side contour on the head-table machine (issue 22): a 70 x 50 pocket with R15
// corners whose walls are drafted 35 deg, cut by the tool's side lying on them, the head
// tilted to B35 while the table turns C through 360 deg (the linear axes carry the tool along
// the straight walls, C turns in the corners), and its floor cut by the vertical tool
// (make_parts_5axis.py: head_draft_a). The head's B tilts the tool in the C frame, not the
// part as the MC-300's table B does: C faces each wall to the tool (C = the wall's azimuth +
// 15 deg, the fixture's turn), so every swarf wall is touched on the machine's +x side and
// none shows an error along the machine's y; beside the pocket a slot whose vertical walls
// face the machine's y, cut by the tool's side with the head leaning B20 along it (C15);
// and a small 3+2 pocket at B35 C105, whose floor (the flat end at the swarf's B) shows the
// errors along the tilted tool that neither the swarf walls nor the vertical floor show, and
// whose walls face the machine's y at another C than the slot's; and a swarf ring (a conical
// pocket of 20 deg, 12 mm radius at its foot, 8 deep, B20 while C turns 360 deg) round
// X-50 Y-25, 56 mm from the C axis where the pocket's centre is 22 mm from it: the swarf
// walls' error round a turn of C is the table's (the same at any radius) plus the linear
// axes' change over the circle the feature's centre runs round the C axis (its radius), which
// one radius cannot tell apart. The pocket's walls at 2 heights, its floor on a 15 x 9 grid:
// 351 points. The model strategy's tables carried to parts of another shape: the 3+2 pocket
// at another pose (head_pocket_b) and a cone of 22 deg elsewhere on the part (head_cone_b).
TEST_F(VirtualShopHeadTable, SwarfContourTunesTablesThatCarryOverToOtherParts) {
  const std::string plan = source("tests/programs/selftune/head_draft_a_points.csv");
  const std::string p0 = source("tests/programs/selftune/head_draft_a.ngc");

  // The program's kinematics, independently of the generator: run on the model compensated
  // by itself (the ideal machine), the tool axis on the pocket's walls is their line of
  // steepest slope, (sin 35 n, cos 35) with n the pocket's outward normal in the plane at the
  // tip (a rounded rectangle round X20 Y10: straight walls at |x - 20| = 35, |y - 10| = 25,
  // corners of R15); in the slot (y < -40) it leans along the slot, (sin 20, 0, cos 20); in
  // the 3+2 pocket (x < -45) it stands at B35 C105: R_z(105 - 15) (sin 35, 0, cos 35); on the
  // ring round X-50 Y-25 (within 20 mm of it) it is the generatrix of its cone of 20 deg.
  run_ok("simulate " + machine() + " " + p0 + " -o " + path("draft_ideal.csv") + " --compensation " + machine() +
         files());
  int on_wall = 0, in_slot = 0, in_pocket = 0, on_ring = 0;
  double worst = 0;
  const double tilt = 35 * M_PI / 180, lean = 20 * M_PI / 180, ring = 20 * M_PI / 180;
  for (const shop::PathSample& s : shop::read_tool_path(path("draft_ideal.csv"))) {
    if (!s.cutting || s.axis.z() > 0.99) continue;  // the floor rasters: the tool vertical
    const Eigen::Vector2d from_ring(s.tip.x() + 50, s.tip.y() + 25);
    if (from_ring.norm() < 20) {
      const Eigen::Vector2d n = from_ring.normalized();
      worst = std::max(
          worst, (s.axis - Eigen::Vector3d(std::sin(ring) * n.x(), std::sin(ring) * n.y(), std::cos(ring))).norm());
      ++on_ring;
      continue;
    }
    if (s.tip.y() < -40) {
      worst = std::max(worst, (s.axis - Eigen::Vector3d(std::sin(lean), 0, std::cos(lean))).norm());
      ++in_slot;
      continue;
    }
    if (s.tip.x() < -45) {
      worst = std::max(worst, (s.axis - Eigen::Vector3d(0, std::sin(tilt), std::cos(tilt))).norm());
      ++in_pocket;
      continue;
    }
    const Eigen::Vector2d p(s.tip.x() - 20, s.tip.y() - 10);
    const Eigen::Vector2d beyond(std::abs(p.x()) - 20, std::abs(p.y()) - 10);  // past the corners' centres
    Eigen::Vector2d n = beyond.cwiseMax(0.0);
    if (n.norm() < 1e-9) n = beyond.x() > beyond.y() ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
    n = n.normalized().cwiseProduct(Eigen::Vector2d(p.x() < 0 ? -1 : 1, p.y() < 0 ? -1 : 1));
    const Eigen::Vector3d slope(std::sin(tilt) * n.x(), std::sin(tilt) * n.y(), std::cos(tilt));
    worst = std::max(worst, (s.axis - slope).norm());
    ++on_wall;
  }
  EXPECT_GT(on_wall, 1000);
  EXPECT_GT(in_slot, 100);
  EXPECT_GT(in_pocket, 100);
  EXPECT_GT(on_ring, 1000);
  EXPECT_LT(worst, 1e-5) << "the tool axis on the walls is not their slope, in the slot not along it, in the "
                            "3+2 pocket not at B35 C105, or on the ring not its generatrix";

  const Form raw = measured(p0, plan, path("draft_r0.csv"), 11);
  run_ok("predistort " + machine() + " " + p0 + " -o " + path("draft_p1.ngc") + files());
  const Form part1 = measured(path("draft_p1.ngc"), plan, path("draft_r1.csv"), 11);
  std::cout << "bc_head drafted pocket (swarf): raw PV " << raw.pv_um << " um, RMS " << raw.rms_um
            << " um; part 1 (pre-distorted with the model): PV " << part1.pv_um << " um, RMS " << part1.rms_um
            << " um, wall lean " << wall_lean_um(path("draft_r1.csv.exact.csv")) << " um\n";
  EXPECT_GT(part1.pv_um, 5.0) << "the true machine should differ enough from the model to need tuning";

  // With the cone's program and plan: the noise the tuned tables carry there, before it is cut.
  const std::string tuned_out =
      run_ok("selftune " + machine() + " " + path("draft_p1.ngc") + " " + path("draft_r1.csv") + " -o " +
             path("draft_model_p2.ngc") + " --strategy model --nominal " + p0 + " --tables-out " + path("draft_tuned") +
             " --next-program " + source("tests/programs/selftune/head_cone_b.ngc") + " --next-points " +
             source("tests/programs/selftune/head_cone_b_points.csv") + files());
  std::cout << tuned_out;
  EXPECT_NE(tuned_out.find("noise: the model leaves"), std::string::npos);
  EXPECT_NE(tuned_out.find("head_cone_b_points.csv (189 points on"), std::string::npos);
  const Form model = measured(path("draft_model_p2.ngc"), plan, path("draft_model_r2.csv"), 12);
  std::cout << "model strategy, part 2: PV " << model.pv_um << " um, RMS " << model.rms_um << " um\n";
  EXPECT_LE(model.rms_um, 0.7);
  EXPECT_LE(model.pv_um, 3.0);
  EXPECT_EQ(test::run_volcomp("check " + path("draft_tuned/bc_head.toml")).exit_code, 0);

  std::cout << run_ok("selftune " + machine() + " " + path("draft_p1.ngc") + " " + path("draft_r1.csv") + " -o " +
                      path("draft_local_p2.ngc") + files());
  const Form local = measured(path("draft_local_p2.ngc"), plan, path("draft_local_r2.csv"), 13);
  std::cout << "local strategy, part 2: PV " << local.pv_um << " um, RMS " << local.rms_um << " um, wall lean "
            << wall_lean_um(path("draft_local_r2.csv.exact.csv")) << " um\n";
  EXPECT_LE(local.rms_um, 0.7);
  EXPECT_LE(local.pv_um, 3.0);

  for (const std::string other : {"head_pocket_b", "head_cone_b"}) {
    const std::string plan_b = source("tests/programs/selftune/" + other + "_points.csv");
    const std::string b0 = source("tests/programs/selftune/" + other + ".ngc");
    run_ok("predistort " + machine() + " " + b0 + " -o " + path(other + "_model.ngc") + files());
    run_ok("predistort " + path("draft_tuned/bc_head.toml") + " " + b0 + " -o " + path(other + "_tuned.ngc") + files());
    const Form b_raw = measured(b0, plan_b, path(other + "_raw.csv"), 14);
    const Form b_shipped = measured(path(other + "_model.ngc"), plan_b, path(other + "_model.csv"), 15);
    const Form b_tuned = measured(path(other + "_tuned.ngc"), plan_b, path(other + "_tuned.csv"), 16);
    std::cout << other << ": PV raw " << b_raw.pv_um << " um, with the shipped model " << b_shipped.pv_um
              << " um, with the tables tuned on the drafted pocket " << b_tuned.pv_um << " um ("
              << 100 * (1 - b_tuned.pv_um / b_raw.pv_um) << " % below raw, "
              << 100 * (1 - b_tuned.pv_um / b_shipped.pv_um) << " % below the shipped model)\n";
    std::cout << other << ": RMS raw " << b_raw.rms_um << " um, with the shipped model " << b_shipped.rms_um
              << " um, with the tuned tables " << b_tuned.rms_um << " um\n";
    // Issue 22's targets: 90 % below raw, 70 % below the shipped model.
    EXPECT_LE(b_tuned.pv_um, 0.1 * b_raw.pv_um) << other;
    EXPECT_LE(b_tuned.pv_um, 0.3 * b_shipped.pv_um) << other;
    EXPECT_LT(b_tuned.rms_um, 0.6 * b_shipped.rms_um) << other;
  }
  // Here the pocket 98.3 % / 87.5 % and the cone 93.7 % / 91.4 % (0.58 um: the raw error is
  // mostly one offset of all the walls, which a PV does not count; the true machine's own file
  // as the model leaves 0.53 um). With part A's report drawn with noise seeds 21, 31, 41: the
  // pocket 98.0-98.9 % / 84.8-91.9 %, the cone 90.6-92.2 % / 87.3-89.4 % (0.71-0.86 um); over
  // noise seeds 51-91 the cone missed 90 % below raw twice (1.04, 1.10 um, still 84 % below the
  // shipped model): the noise of part A's report left a first and second harmonic of 0.2-0.35
  // um round the cone's walls and moved its floor. preproc/shop/README.md, "Measured".
}

}  // namespace
}  // namespace vc
