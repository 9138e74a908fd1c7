// The volcomp command line, run as a user runs it: exit codes, CSV outputs against the
// independent MC-300 reference, and file:line:column messages for bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "test_support.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/machine/machine_checksum.hpp"
#include "vc/tables/load_table.hpp"

namespace vc {
namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("volcomp_cli_" + name);
  std::ofstream(path) << text;
  return path.string();
}

const std::string kMc300 = test::machine_path("mc300");
const std::string kPoses = test::source_path("tests/reference/mc300/ctrl60_poses.csv");

TEST(VolcompCli, CheckAcceptsEveryShippedMachine) {
  for (const std::string& name : test::shipped_machines()) {
    const auto r = test::run_volcomp("check " + test::machine_path(name) + " --samples 2000");
    EXPECT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("usable"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("largest position error"), std::string::npos) << r.out;
  }
}

// check --ini alone: the machine file of the INI's volkins line, and its checksum as volkins
// shows it on volkins.checksum (machine_checksum; its own test: python's zlib.crc32).
TEST(VolcompCli, CheckIniPrintsTheChecksumOfTheInisMachineFile) {
  const auto r = test::run_volcomp("check --ini " + test::source_path("kins/configs/mill3/mill3.ini") + " --samples 100");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%08X", machine::machine_checksum(machine::load_machine(test::machine_path("mill3"))));
  EXPECT_NE(r.out.find(std::string("  checksum ") + hex + " (volkins.checksum) of its machine file " +
                       test::machine_path("mill3") + " and its 4 table files\n"),
            std::string::npos)
      << r.out;
}

TEST(VolcompCli, ErrorMatchesTheReferenceAtSixtyControlPoints) {
  const auto r = test::run_volcomp("error " + kMc300 + " --poses " + kPoses);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::string out = write_temp("error.csv", r.out);
  const test::CsvTable got(out), ref(test::source_path("tests/reference/mc300/ctrl60_ref.csv"));
  ASSERT_EQ(got.size(), 60u);
  for (std::size_t i = 0; i < 60; ++i)
    for (const char* c : {"x", "y", "z", "b", "c", "ex", "ey", "ez", "ekx", "eky", "ekz"})
      EXPECT_NEAR(got.at(i, c), ref.at(i, c), 1e-9) << c << " row " << i;
}

TEST(VolcompCli, CorrectMatchesTheReferenceAtSixtyControlPoints) {
  const auto r = test::run_volcomp("correct " + kMc300 + " --poses " + kPoses + " --tool-length 100");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "x,y,z,b,c,cx,cy,cz,cb,cc,residual_mm,residual_rad,iterations");
  const test::CsvTable got(write_temp("correct.csv", r.out)),
      ref(test::source_path("tests/reference/mc300/ctrl60_ref.csv"));
  for (std::size_t i = 0; i < 60; ++i) {
    for (const char* c : {"cx", "cy", "cz", "cb", "cc"}) EXPECT_NEAR(got.at(i, c), ref.at(i, c), 1e-8) << c;
    EXPECT_LT(got.at(i, "residual_mm"), 1e-9);
  }
}

TEST(VolcompCli, OnlyKeepsTheNamedDeviations) {
  const auto all = test::run_volcomp("error " + kMc300 + " --poses " + kPoses);
  const auto yy = test::run_volcomp("error " + kMc300 + " --poses " + kPoses + " --only EYY");
  ASSERT_EQ(yy.exit_code, 0) << yy.out;
  EXPECT_NE(all.out, yy.out);
  const test::CsvTable got(write_temp("only.csv", yy.out));
  // Y's positioning error does not tilt the tool: no direction error beyond rounding.
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got.at(i, "ekx"), 0.0, 1e-15);
  const auto bad = test::run_volcomp("error " + kMc300 + " --poses " + kPoses + " --only EQQ");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.out.find("'EQQ' is not a deviation"), std::string::npos) << bad.out;
}

TEST(VolcompCli, BadPosesFileNamesLineAndColumn) {
  const std::string poses = write_temp("bad_poses.csv", "x,y,z,b,c\n-300,-150,-130,0,0\n-300,-150,abc,0,0\n");
  const auto r = test::run_volcomp("correct " + kMc300 + " --poses " + poses);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find(poses + ":3:11: error: 'abc' is not a finite number"), std::string::npos) << r.out;
  const std::string wrong_axis = write_temp("wrong_axis.csv", "x,y,z,a,c\n");
  const auto w = test::run_volcomp("error " + kMc300 + " --poses " + wrong_axis);
  EXPECT_EQ(w.exit_code, 2);
  EXPECT_NE(w.out.find(wrong_axis + ":1:7: error: column 'a' is not an axis of MC-300 (xyzbc)"), std::string::npos)
      << w.out;
}

TEST(VolcompCli, BadMachineFileFailsWithItsLocation) {
  const auto r = test::run_volcomp("check " + test::source_path("tests/reference/mc300/README.md"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("README.md:3:8: error: "), std::string::npos) << r.out;
}

TEST(VolcompCli, BalanceListsTheDeviationsAndWritesItsCsv) {
  const std::string csv = write_temp("balance.csv", "");
  std::filesystem::remove(csv);
  auto r = test::run_volcomp("balance " + kMc300 + " --levels 3 -o " + csv);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("243 poses over the travel (3 per joint), L = 100 mm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("EA0B"), std::string::npos) << r.out;
  std::ifstream in(csv);
  std::string line;
  int rows = 0;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#' && line.rfind("deviation,", 0) != 0) ++rows;
  EXPECT_EQ(rows, 37);  // MC-300: 41 primary deviations, 4 of them zero in the source (e30 e31 e40 e41)
  r = test::run_volcomp("balance " + kMc300 + " --levels 1");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("--levels must be in 2..21"), std::string::npos) << r.out;
  r = test::run_volcomp("balance /nonexistent/machine.toml");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("/nonexistent/machine.toml"), std::string::npos) << r.out;
}

TEST(VolcompCli, IdentifyLaserWritesATableTheLoaderReads) {
  std::string runs =
      "# instrument: test\n# measured_at_mm: 0, 0, -100\ntarget[mm],1+[um],1-[um],2+[um],2-[um],3+[um],3-[um]\n";
  for (int k = 0; k <= 6; ++k)
    runs += std::to_string(-100 * k) + "," + std::to_string(0.5 * k) + "," + std::to_string(0.5 * k - 1) + "," +
            std::to_string(0.5 * k + 0.2) + "," + std::to_string(0.5 * k - 0.8) + "," + std::to_string(0.5 * k - 0.2) +
            "," + std::to_string(0.5 * k - 1.2) + "\n";
  const std::string in = write_temp("runs.csv", runs), table = write_temp("exx.csv", "");
  std::filesystem::remove(table);
  auto r = test::run_volcomp("identify laser " + in + " --error EXX -o " + table);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("reversal value B            1.00 um"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(the readings: the tool against the part)"), std::string::npos) << r.out;
  const tables::ErrorTable t = tables::load_table(table);
  ASSERT_EQ(t.node_count(), 7);
  EXPECT_NEAR(t.value(0, 0), (0.5 * 6 - 0.5) * 1e-3, 1e-9);  // at -600 mm (ascending): mean of +3.0 ... -> 2.5 um
  // The runs measure a translation of a linear axis: an angle or a rotary axis is refused.
  r = test::run_volcomp("identify laser " + in + " --error EAX");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("the deviations are lengths but EAX is a rotation"), std::string::npos) << r.out;
  r = test::run_volcomp("identify laser " + in + " --error ECC");
  EXPECT_NE(r.out.find("the targets are in mm but ECC is an error of the rotary axis C"), std::string::npos) << r.out;
}

// --machine-out: the identified table REPLACES the axis's old values of the error, solved through
// the model. On the MC-300 (X's x.csv holds EXX 0..3 um; +X moves the tool -x in the part frame),
// runs of a made-up reading at X's line: the written machine, with every error of the file, reads
// the runs' bidirectional mean at every target (with --reference datum: the runs' value at the
// first target, the laser's zero, replaced by the file's there), worked out here from the runs and
// `volcomp error --ideal-tip` (the reading along the axis's ideal motion), not identify's code;
// the table written beside it holds the
// axis's own EXX, whose sign is the reading's turned (the axis runs along -x); X's other errors
// are as they were.
TEST(VolcompCli, IdentifyLaserMachineOutReplacesTheErrorOfTheAxis) {
  const auto reading_um = [](double x) { return 4 * std::sin(x / 150) - 0.01 * x; };  // x in mm
  std::string runs =
      "# at: x=0, y=-160, z=-150, b=0, c=0\n# tool_length_mm: 100\n"
      "target[mm],1+[um],1-[um],2+[um],2-[um],3+[um],3-[um]\n";
  for (int k = 0; k <= 6; ++k) {
    const double x = -600.0 + 100.0 * k, v = reading_um(x);  // up +0.75, down -0.75, run offsets +0.1, -0.1, 0
    runs += std::to_string(x) + "," + std::to_string(v + 0.85) + "," + std::to_string(v - 0.65) + "," +
            std::to_string(v + 0.65) + "," + std::to_string(v - 0.85) + "," + std::to_string(v + 0.75) + "," +
            std::to_string(v - 0.75) + "\n";
  }
  const std::string in = write_temp("replace_runs.csv", runs);
  const std::string folder = (std::filesystem::temp_directory_path() / "vc_cli_laser_machine_out").string();
  std::filesystem::remove_all(folder);
  auto r = test::run_volcomp("identify laser " + in + " --error EXX --machine " + kMc300 + " --machine-out " + folder);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("machine file written: " + folder + "/mc300.toml"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("self-check: the written file reads the runs within"), std::string::npos) << r.out;
  const std::string written = folder + "/mc300.toml";
  EXPECT_EQ(test::run_volcomp("check " + written + " --samples 500").exit_code, 0);

  // The reading of a machine file along X's ideal motion at the targets (um).
  std::string poses = "x,y,z,b,c\n";
  for (int k = 0; k <= 6; ++k) poses += std::to_string(-600.0 + 100.0 * k) + ",-160,-150,0,0\n";
  const std::string poses_file = write_temp("replace_poses.csv", poses);
  const auto read_along_x = [&](const std::string& machine, const std::string& only) {
    const auto e = test::run_volcomp("error " + machine + " --poses " + poses_file + " --ideal-tip" + only);
    const test::CsvTable t(write_temp("replace_error.csv", e.out));
    std::vector<double> um;
    const double dx = t.at(6, "tx") - t.at(0, "tx"), dy = t.at(6, "ty") - t.at(0, "ty"),
                 dz = t.at(6, "tz") - t.at(0, "tz");
    const double n = std::sqrt(dx * dx + dy * dy + dz * dz);
    EXPECT_NEAR(dx / n, -1.0, 1e-12);  // the MC-300's +X moves the tool -x
    for (std::size_t i = 0; i < t.size(); ++i)
      um.push_back((t.at(i, "ex") * dx + t.at(i, "ey") * dy + t.at(i, "ez") * dz) / n * 1e3);
    return um;
  };
  const std::vector<double> before = read_along_x(kMc300, ""), after = read_along_x(written, "");
  for (int k = 0; k <= 6; ++k) EXPECT_NEAR(after[k], reading_um(-600.0 + 100.0 * k), 2e-3) << "x = " << -600 + 100 * k;
  r = test::run_volcomp("identify laser " + in + " --error EXX --reference datum --machine " + kMc300 +
                        " --machine-out " + folder + "_datum");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::vector<double> datum = read_along_x(folder + "_datum/mc300.toml", "");
  EXPECT_GT(std::abs(before[0] - reading_um(-600)), 1.0);  // the file does not read the runs' zero there
  for (int k = 0; k <= 6; ++k) {
    const double x = -600.0 + 100.0 * k;
    EXPECT_NEAR(datum[k], reading_um(x) - reading_um(-600) + before[0], 2e-3) << "x = " << x;
  }
  std::filesystem::remove_all(folder + "_datum");

  // The table beside it, read back as text: x and EXX in um, the axis's own: the file's EXX
  // (x.csv's zeroed, so EXX alone is this table) turns the reading's change round along -x.
  std::ifstream table(folder + "/x_EXX_laser.csv");
  ASSERT_TRUE(table) << r.out;
  std::string line;
  while (std::getline(table, line) && line.rfind('#', 0) == 0) {
  }
  EXPECT_EQ(line, "x[mm],EXX[um]");
  const std::vector<double> exx_alone = read_along_x(written, " --only EXX");
  int rows = 0;
  for (double x, v; std::getline(table, line); ++rows) {
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf", &x, &v), 2) << line;
    EXPECT_NEAR(v, -exx_alone[rows], 2e-3) << line;
  }
  EXPECT_EQ(rows, 7);
  // X's other errors as they were (x.csv copied as it is, EXX zero).
  for (const char* other : {"EYX", "EAX", "EBX"})
    EXPECT_EQ(test::run_volcomp("error " + written + " --poses " + poses_file + " --only " + other).out,
              test::run_volcomp("error " + kMc300 + " --poses " + poses_file + " --only " + other).out)
        << other;

  // EXX also in a table over X and a temperature (mc300_thermal: EXX(x, coolant)): that one stays,
  // read where the runs stood; x.csv's EXX is replaced.
  r = test::run_volcomp("identify laser " + in + " --error EXX --machine " + test::machine_path("mc300_thermal") +
                        " --machine-out " + folder + "_thermal");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("kept: the solve read it where the runs stood"), std::string::npos) << r.out;
  // Refused: --machine-out without --machine, the machine's own folder, runs that do not say
  // where the axes stood or where the optic was (nothing written).
  r = test::run_volcomp("identify laser " + in + " --error EXX --machine-out " + folder);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("--machine-out needs --machine"), std::string::npos) << r.out;
  r = test::run_volcomp("identify laser " + in + " --error EXX --machine " + kMc300 + " --machine-out " +
                        std::filesystem::path(kMc300).parent_path().string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("the machine file's own folder"), std::string::npos) << r.out;
  std::string bare = runs.substr(runs.find("target"));
  const std::string bare_in = write_temp("bare_runs.csv", bare);
  r = test::run_volcomp("identify laser " + bare_in + " --error EXX --machine " + kMc300 + " --machine-out " + folder +
                        "_bare");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("where did the axes stand during the runs? Add a '# at: x=..., y=..., z=..., b=..., c=...'"),
            std::string::npos)
      << r.out;
  r = test::run_volcomp("identify laser " + bare_in + " --error EXX --machine " + kMc300 +
                        " --at x=0,y=-160 --machine-out " + folder + "_bare");
  EXPECT_NE(r.out.find("where did z, b, c stand during the runs?"), std::string::npos) << r.out;
  r = test::run_volcomp("identify laser " + bare_in + " --error EXX --machine " + kMc300 +
                        " --at x=0,y=-160,z=-150,b=0,c=0 --machine-out " + folder + "_bare -o " + folder + "_bare.csv");
  EXPECT_NE(r.out.find("where was the tool-side optic?"), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(folder + "_bare/mc300.toml"));
  EXPECT_FALSE(std::filesystem::exists(folder + "_bare.csv"));  // nor the readings' table
  std::filesystem::remove_all(folder);
  std::filesystem::remove_all(folder + "_thermal");
  std::filesystem::remove_all(folder + "_bare");
}

// The main job's laser half: a true MC-300 whose X has a pitch error the file lacks (perturb
// --add-table), the simulated laser (preproc/identify/simulate-laser-runs: 5 runs each way,
// reversal 1.5 um, noise 0.5 um + 0.5 um/m) on it, identify laser into the nominal file: the
// identified file's EXX at the tip is the true machine's within 3.5 standard errors of the
// bidirectional mean at every target, and the reversal comes back.
TEST(VolcompCli, SimulatedLaserRunsOnATrueMachineGiveItsTableBack) {
  const std::string folder = (std::filesystem::temp_directory_path() / "vc_cli_simulated_laser").string();
  std::filesystem::remove_all(folder);
  std::string pitch = "x[mm],EXX[um]\n";
  for (int x = -600; x <= 0;
       x += 25)  // 0 at -600 mm, the laser's datum: what the laser cannot know is right in the file
    pitch += std::to_string(x) + "," + std::to_string(4 * std::sin((x + 600) / 70.0) + 0.012 * (x + 600)) + "\n";
  auto r = test::run_volcomp("perturb " + kMc300 + " -o " + folder + "/true --add-table " +
                             write_temp("sim_pitch.csv", pitch));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::string targets;
  for (int x = -600; x <= 0; x += 50) targets += std::to_string(x) + " ";
  const std::string runs = folder + "/runs.csv";
  const std::string command = test::source_path("preproc/identify/simulate-laser-runs") + " " + VC_VOLCOMP + " " +
                              folder + "/true/mc300.toml EXX x,y,z,b,c 0,-160,-150,0,0 '" + targets + "' 7 > " + runs;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  r = test::run_volcomp("identify laser " + runs + " --error EXX --machine " + kMc300 + " --machine-out " + folder +
                        "/laser");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::size_t at = r.out.find("(mean ", r.out.find("reversal value B"));
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_NEAR(std::stod(r.out.substr(at + 6)), 1.5, 0.3) << r.out;  // 13 targets' mean reversal

  std::string poses = "x,y,z,b,c\n";
  for (int x = -600; x <= 0; x += 50) poses += std::to_string(x) + ",-160,-150,0,0\n";
  const std::string poses_file = write_temp("sim_poses.csv", poses);
  const test::CsvTable truth(
      write_temp("sim_truth.csv",
                 test::run_volcomp("error " + folder + "/true/mc300.toml --poses " + poses_file + " --only EXX").out));
  const test::CsvTable got(
      write_temp("sim_got.csv",
                 test::run_volcomp("error " + folder + "/laser/mc300.toml --poses " + poses_file + " --only EXX").out));
  const test::CsvTable nominal(write_temp(
      "sim_nominal.csv", test::run_volcomp("error " + kMc300 + " --poses " + poses_file + " --only EXX").out));
  ASSERT_EQ(got.size(), 13u);
  double off_nominal = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    // The laser's noise there and at the datum (-600 mm, 0.5 um), each a mean of 10 readings.
    const double x = got.at(i, "x"), sigma_um = std::hypot(0.5 + 0.5 * (x + 600) / 1000, 0.5);
    EXPECT_NEAR(got.at(i, "ex") * 1e3, truth.at(i, "ex") * 1e3, 3.5 * sigma_um / std::sqrt(10.0)) << "x = " << x;
    off_nominal = std::max(off_nominal, std::abs(truth.at(i, "ex") - nominal.at(i, "ex")) * 1e3);
  }
  EXPECT_GT(off_nominal, 5.0);  // the truth is far from the file: the check above can fail
  std::filesystem::remove_all(folder);
}

// A rotary axis indexed against a reference over one full turn (ECC, arcsec): 0 and 360 deg are
// one position, so the table is periodic and loads; their readings are averaged.
TEST(VolcompCli, IdentifyLaserOnAFullTurnWritesAPeriodicTable) {
  std::string runs = "target[deg],1+[arcsec],1-[arcsec],2+[arcsec],2-[arcsec]\n";
  for (int k = 0; k <= 8; ++k) {
    const double v = 3 * std::sin(k * M_PI / 4) + (k == 8 ? 0.4 : 0.0);  // 360 reads 0.4 arcsec off 0
    runs += std::to_string(45 * k) + "," + std::to_string(v + 0.5) + "," + std::to_string(v - 0.5) + "," +
            std::to_string(v + 0.6) + "," + std::to_string(v - 0.4) + "\n";
  }
  const std::string in = write_temp("ecc_runs.csv", runs), table = write_temp("ecc.csv", "");
  std::filesystem::remove(table);
  const auto r = test::run_volcomp("identify laser " + in + " --error ECC -o " + table);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("One full turn"), std::string::npos) << r.out;
  const tables::ErrorTable t = tables::load_table(table);
  ASSERT_TRUE(t.grid()[0].periodic);
  EXPECT_NEAR(t.value(0, 0), t.value(8, 0), 1e-12);
  EXPECT_NEAR(t.value(0, 0) / (M_PI / 648000), 0.2 + 0.05, 1e-3);  // the mean of 0.05 and 0.45 arcsec
  const auto m = test::run_volcomp("identify laser " + in + " --error ECC --machine " + test::machine_path("mill3"));
  EXPECT_NE(m.exit_code, 0);
  EXPECT_NE(m.out.find("ECC is an error of axis C, which mill3"), std::string::npos) << m.out;
}

// A CMM export selftune cannot read for sure is refused at its line and column, with the way
// out, and no program is written.
TEST(VolcompCli, SelftuneRefusesAnAmbiguousCmmExportAndWritesNothing) {
  const std::string program = test::source_path("tests/programs/selftune/part_a.ngc");
  const std::string files = " --var " + test::source_path("tests/programs/mill3.var") + " --tool-table " +
                            test::source_path("tests/programs/mill3.tbl");
  const std::string next = write_temp("selftune_next.ngc", "");
  const std::string report =
      write_temp("export.txt", "Units: mm\nPoint;X Nom;Y Nom;Z Nom;I;J;K;Dev\nP1;100;0;-5;1;0;0;0.004\n");
  const auto run = [&](const std::string& options) {
    std::filesystem::remove(next);
    return test::run_volcomp("selftune " + test::machine_path("mill3") + " " + program + " " + report + " -o " + next +
                             files + options);
  };
  auto r = run("");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find(report + ":2:31: error: the sign of 'Dev' is not stated: give --deviation-sign"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(std::filesystem::exists(next));
  r = run(" --deviation-sign actual-minus-nominal --report-unit inch");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find(report + ":1:1: error: this units line says mm, --report-unit says inch"), std::string::npos)
      << r.out;
  r = run(" --deviation-sign plus");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("--deviation-sign"), std::string::npos) << r.out;
  r = run(" --deviation-sign actual-minus-nominal --strategy model --tables-out " + next + ".d --next-program " +
          program);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("--next-program and --next-points go together"), std::string::npos) << r.out;
  r = run(" --deviation-sign actual-minus-nominal --next-program " + program + " --next-points " + report);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("--next-program and --next-points need --strategy model"), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(next));
  // Read: one point is too few for the program, which is the next refusal.
  r = run(" --deviation-sign actual-minus-nominal");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("read as a CMM export, semicolon-separated, header on line 2"), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(next));
}

// perturb --location: a true machine differing in the named location errors only, by the
// amounts given (the tables kept); a component error or a change without its unit refused.
TEST(VolcompCli, PerturbLocationChangesOnlyTheNamedLocationErrors) {
  const std::string folder = (std::filesystem::temp_directory_path() / "vc_cli_perturb_location").string();
  std::filesystem::remove_all(folder);
  auto r = test::run_volcomp("perturb " + test::machine_path("mc300") + " -o " + folder +
                             " --location EX0C=15um --location EA0C=-3arcsec --location EZ0B=0.008mm");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("3 location errors changed, 0 tables added"), std::string::npos) << r.out;
  const machine::Model before = machine::load_machine(test::machine_path("mc300"));
  const machine::Model after = machine::load_machine(folder + "/mc300.toml");
  const auto &b0 = before.axes[before.joint_of('B')], &b1 = after.axes[after.joint_of('B')];
  const auto &c0 = before.axes[before.joint_of('C')], &c1 = after.axes[after.joint_of('C')];
  EXPECT_NEAR(c1.location_mm[0] - c0.location_mm[0], 0.015, 1e-12);
  EXPECT_NEAR(c1.location_rad[0] - c0.location_rad[0], -3 * M_PI / 648000, 1e-12);
  EXPECT_NEAR(b1.location_mm[2] - b0.location_mm[2], 0.008, 1e-12);
  EXPECT_EQ(b1.location_rad, b0.location_rad);  // the rest as it was
  EXPECT_EQ(c1.location_mm[1], c0.location_mm[1]);
  ASSERT_EQ(after.tables.size(), before.tables.size());
  // --add-table: the true machine's X has a pitch error on top of x.csv's: EXX at the tip is the sum.
  const std::string pitch = write_temp("true_pitch.csv", "x[mm],EXX[um]\n-600,6\n-300,-3\n0,0\n");
  std::filesystem::remove_all(folder);
  r = test::run_volcomp("perturb " + test::machine_path("mc300") + " -o " + folder + " --add-table " + pitch);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("0 location errors changed, 1 tables added"), std::string::npos) << r.out;
  const std::string poses = write_temp("pitch_poses.csv", "x,y,z,b,c\n-450,-160,-150,0,0\n");
  const test::CsvTable with(write_temp(
      "pitch_with.csv", test::run_volcomp("error " + folder + "/mc300.toml --poses " + poses + " --only EXX").out));
  const test::CsvTable without(
      write_temp("pitch_without.csv",
                 test::run_volcomp("error " + test::machine_path("mc300") + " --poses " + poses + " --only EXX").out));
  EXPECT_NEAR((with.at(0, "ex") - without.at(0, "ex")) * 1e3, 1.5, 1e-9);  // halfway from 6 to -3 um
  r = test::run_volcomp("perturb " + test::machine_path("mc300") + " -o " + folder + " --add-table " +
                        test::source_path("tables/data/mc300/x.csv"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("axis X already lists a table of that name"), std::string::npos) << r.out;
  r = test::run_volcomp("perturb " + test::machine_path("mc300") + " -o " + folder + " --location EXC=15um");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("--location EXC=15um: a location error of MC-300"), std::string::npos) << r.out;
  r = test::run_volcomp("perturb " + test::machine_path("mc300") + " -o " + folder + " --location EA0C=3um");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("the change needs its unit (arcsec or urad)"), std::string::npos) << r.out;
  std::filesystem::remove_all(folder);
}

// probe-plan's touch: a back-off that leaves no room before the surface, or no feed, is refused.
TEST(VolcompCli, ProbePlanRefusesATouchThatCannotWork) {
  const std::string plan =
      "probe-plan " + test::machine_path("mc300") + " --centre -300,-160,-200 --grid B=0,-90 --grid C=0,180";
  auto r = test::run_volcomp(plan);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("G38.2 Z-0.6000 F10.0000"), std::string::npos) << "the measuring touch";
  for (const char* bad : {" --back-off 3", " --touch-feed 0", " --back-off -0.1"}) {
    r = test::run_volcomp(plan + bad);
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_NE(r.out.find("the feeds must be positive and the back-off between 0 and the clearance"), std::string::npos)
        << bad << "\n"
        << r.out;
  }
}

TEST(VolcompCli, HelpIsEverywhere) {
  for (const char* sub : {"", "check ", "error ", "correct ", "balance ", "identify laser ", "identify circle ",
                          "identify sphere ", "probe-plan ", "perturb ", "fit-tables "}) {
    const auto r = test::run_volcomp(std::string(sub) + "--help");
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub;
  }
}

}  // namespace
}  // namespace vc
