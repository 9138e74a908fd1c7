// volkins in a real HAL (halrun, no motion): it loads with every shipped machine and exposes
// its pins and parameters; the enable ramp moves as documented; bad machine files and bad
// module parameters make loadrt fail with the loader's message and leave nothing loaded.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>

#include "linuxcnc_run.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;

// loadrt of a machine file given relative to the source tree (staged by test::halrun).
std::string loadrt(const std::string& machine, const std::string& extra = "") {
  return "loadrt volkins machine=@SRC@" + machine + (extra.empty() ? "" : " " + extra) + "\n";
}

std::string shipped(const std::string& name) { return "machines/data/" + name + ".toml"; }

// Values of a float pin in the order `show pin NAME` printed them.
std::vector<double> shown_values(const std::string& out, const std::string& pin) {
  const std::regex line(R"(float\s+\S+\s+(\S+)\s+)" + std::regex_replace(pin, std::regex(R"(\.)"), R"(\.)") + R"(\s)");
  std::vector<double> values;
  for (auto it = std::sregex_iterator(out.begin(), out.end(), line); it != std::sregex_iterator(); ++it)
    values.push_back(std::stod((*it)[1]));
  return values;
}

// True if `show comp` listed a volkins component.
bool volkins_listed(const std::string& out) {
  return std::regex_search(out, std::regex(R"((^|\n)\s*\d+\s+RT\s+volkins\s)"));
}

class ShippedMachine : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedMachine, LoadsAndExposesItsPins) {
  const machine::Model model = machine::load_machine(test::machine_path(GetParam()));
  const test::CommandResult r =
      test::halrun("load_" + GetParam(), loadrt(shipped(GetParam())) + "show pin volkins\nshow param volkins\n");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  for (const char* pin : {"volkins.enable",
                          "volkins.tool-offset",
                          "volkins.tool-offset-slew-time",
                          "volkins.gain",
                          "volkins.active",
                          "volkins.update-missing",
                          "volkins.iterations",
                          "volkins.forward-iterations",
                          "volkins.out-of-table",
                          "volkins.limit-exceeded",
                          "volkins.failures",
                          "volkins.ramp-time",
                          "volkins.max-correction-mm",
                          "volkins.max-correction-deg",
                          "volkins.pole-fade-start-deg",
                          "volkins.pole-fade-full-deg",
                          "volkins.update.time",
                          "volkins.type.l-pos.enable",
                          "volkins.type.r-spec.gain",
                          "volkins.type.for.enable",
                          "volkins.thermal.enable",
                          "volkins.thermal.gain",
                          "volkins.reload",
                          "volkins.reload-state",
                          "volkins.reload-failed",
                          "volkins.reloads",
                          "volkins.checksum"})
    EXPECT_NE(r.out.find(pin), std::string::npos) << pin << " missing:\n" << r.out;
  for (int j = 0; j < 6; ++j) {
    const std::string pin = "volkins.joint." + std::to_string(j) + ".correction";
    EXPECT_EQ(r.out.find(pin) != std::string::npos, j < model.joint_count()) << pin << "\n" << r.out;
  }
  // Shown by their names; the former names are aliases HAL does not list.
  EXPECT_EQ(r.out.find("volkins.tool-length"), std::string::npos) << r.out;
  // The tool length starts at the machine file's.
  const std::vector<double> tool = shown_values(r.out, "volkins.tool-offset");
  ASSERT_EQ(tool.size(), 1u) << r.out;
  EXPECT_DOUBLE_EQ(tool[0], model.tool_length_mm);
}

INSTANTIATE_TEST_SUITE_P(Shipped, ShippedMachine, ::testing::ValuesIn(test::shipped_machines()),
                         [](const auto& p) { return p.param; });

// Switchable kinematics: volkins starts in type 0 and says so on LinuxCNC's kinstype.is-N pins;
// volkins.tcp tells which world type 0 is (world=, sparm=identityfirst).
TEST(Volkins, StartsInKinematicsTypeZeroOfTheWorldItWasGiven) {
  struct Case {
    std::string parameters;
    bool tcp;
  };
  for (const Case& c : {Case{"", false}, Case{"world=tcp", true}, Case{"sparm=identityfirst", false}}) {
    const test::CommandResult r = test::halrun("kinstype", loadrt(shipped("mc300"), c.parameters) + "show pin\n");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    auto bit = [&](const std::string& pin) {
      std::smatch m;
      EXPECT_TRUE(std::regex_search(r.out, m,
                                    std::regex(R"(bit\s+OUT\s+(TRUE|FALSE)\s+)" +
                                               std::regex_replace(pin, std::regex(R"(\.)"), R"(\.)") + R"(\s)")))
          << pin << " missing:\n"
          << r.out;
      return m.size() > 1 && m[1] == "TRUE";
    };
    EXPECT_TRUE(bit("kinstype.is-0")) << c.parameters;
    EXPECT_FALSE(bit("kinstype.is-1")) << c.parameters;
    EXPECT_FALSE(bit("kinstype.is-2")) << c.parameters;
    EXPECT_EQ(bit("volkins.tcp"), c.tcp) << c.parameters;
  }
}

// volkins.update moves the gain 0 -> 1 in ramp-time seconds and back when enable drops.
TEST(Volkins, EnableRampsTheGainInRampTime) {
  const std::string script = loadrt(shipped("mc300")) +
                             "loadrt threads name1=servo period1=1000000\n"
                             "addf volkins.update servo\n"
                             "setp volkins.ramp-time 0.5\n"
                             "start\n"
                             "loadusr -w sleep 0.15\n"
                             "show pin volkins.gain\n"
                             "loadusr -w sleep 0.8\n"
                             "show pin volkins.gain\n"
                             "show pin volkins.active\n"
                             "setp volkins.enable 0\n"
                             "loadusr -w sleep 0.8\n"
                             "show pin volkins.gain\n"
                             "show pin volkins.active\n"
                             "show pin volkins.update-missing\n";
  const test::CommandResult r = test::halrun("ramp", script);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::vector<double> gain = shown_values(r.out, "volkins.gain");
  ASSERT_EQ(gain.size(), 3u) << r.out;
  const double early = gain[0], on = gain[1], off = gain[2];
  EXPECT_GT(early, 0.0) << r.out;
  EXPECT_LT(early, 1.0) << r.out;
  EXPECT_EQ(on, 1.0) << r.out;
  EXPECT_EQ(off, 0.0) << r.out;
  // volkins.active says whether a correction is applied; the update function ran.
  const std::regex active(R"(bit\s+OUT\s+(TRUE|FALSE)\s+volkins\.active\s)");
  std::vector<std::string> states;
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), active); it != std::sregex_iterator(); ++it)
    states.push_back((*it)[1]);
  EXPECT_EQ(states, (std::vector<std::string>{"TRUE", "FALSE"})) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(bit\s+OUT\s+FALSE\s+volkins\.update-missing)"))) << r.out;
}

// Each compensation type's switch (volkins.type.<code>.enable, and FOR's and thermal's) ramps its
// own gain in ramp-time, the others staying on; a switch set before the thread starts is taken
// at once (the correction is not applied yet).
TEST(Volkins, EachTypesSwitchRampsItsOwnGain) {
  const std::string script = loadrt(shipped("mc300")) +
                             "loadrt threads name1=servo period1=1000000\n"
                             "addf volkins.update servo\n"
                             "setp volkins.ramp-time 0.5\n"
                             "setp volkins.type.r-por.enable 0\n"
                             "start\n"
                             "loadusr -w sleep 0.05\n"
                             "show pin volkins.type.r-por.gain\n"
                             "loadusr -w sleep 0.75\n"
                             "setp volkins.type.l-ang.enable 0\n"
                             "setp volkins.thermal.enable 0\n"
                             "loadusr -w sleep 0.15\n"
                             "show pin volkins.type.l-ang.gain\n"
                             "loadusr -w sleep 0.8\n"
                             "show pin volkins.type\n"
                             "show pin volkins.thermal.gain\n";
  const test::CommandResult r = test::halrun("type_ramp", script);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::vector<double> l_ang = shown_values(r.out, "volkins.type.l-ang.gain");
  ASSERT_EQ(l_ang.size(), 2u) << r.out;
  EXPECT_GT(l_ang[0], 0.0) << "on its way: " << r.out;
  EXPECT_LT(l_ang[0], 1.0) << "on its way: " << r.out;
  EXPECT_EQ(l_ang[1], 0.0) << r.out;
  EXPECT_EQ(shown_values(r.out, "volkins.type.r-por.gain"), (std::vector<double>{0.0, 0.0})) << "at once: " << r.out;
  EXPECT_EQ(shown_values(r.out, "volkins.thermal.gain"), std::vector<double>{0.0}) << r.out;
  for (const char* on : {"l-pos", "l-str", "l-squ", "r-pos", "r-rax", "r-ang", "l-spec", "r-spec", "for"})
    EXPECT_EQ(shown_values(r.out, std::string("volkins.type.") + on + ".gain"), std::vector<double>{1.0})
        << on << ": " << r.out;
}

// A temperature input of the machine file is a pin volkins.temperature.<name>: low-passed with
// volkins.temperature-time-constant (sensor noise never reaches the joints), and a reading
// outside the model's range (or not a number) holds the last good value and raises
// volkins.temperature-fault while it lasts.
TEST(Volkins, TemperaturesAreLowPassedAndAFaultyReadingIsHeld) {
  const std::string script = loadrt("tests/hal/data/mill3_thermal.toml") +
                             "loadrt threads name1=servo period1=1000000\n"
                             "addf volkins.update servo\n"
                             "setp volkins.temperature-time-constant 0.2\n"
                             "show pin volkins.temperature.x_screw.filtered\n"  // the reference until a reading
                             "setp volkins.temperature.x_screw 30\n"
                             "start\n"
                             "loadusr -w sleep 0.05\n"
                             "show pin volkins.temperature.x_screw.filtered\n"  // on its way
                             "loadusr -w sleep 1.5\n"
                             "show pin volkins.temperature.x_screw.filtered\n"  // there (7 time constants)
                             "setp volkins.temperature.x_screw 90\n"            // beyond max_degC 45: a fault
                             "loadusr -w sleep 0.3\n"
                             "show pin volkins.temperature.x_screw.filtered\n"
                             "show pin volkins.temperature-fault\n"
                             "setp volkins.temperature.x_screw 31\n"
                             "loadusr -w sleep 0.3\n"
                             "show pin volkins.temperature-fault\n";
  const test::CommandResult r = test::halrun("temperature", script);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::vector<double> t = shown_values(r.out, "volkins.temperature.x_screw.filtered");
  ASSERT_EQ(t.size(), 4u) << r.out;
  EXPECT_EQ(t[0], 20.0) << r.out;
  EXPECT_GT(t[1], 20.0) << r.out;
  EXPECT_LT(t[1], 29.0) << r.out;  // not a step
  EXPECT_NEAR(t[2], 30.0, 0.01) << r.out;
  EXPECT_NEAR(t[3], 30.0, 0.01) << r.out;  // held while faulty (not on its way to 90)
  const std::regex fault(R"(bit\s+OUT\s+(TRUE|FALSE)\s+volkins\.temperature-fault\s)");
  std::vector<std::string> states;
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), fault); it != std::sregex_iterator(); ++it)
    states.push_back((*it)[1]);
  EXPECT_EQ(states, (std::vector<std::string>{"TRUE", "FALSE"})) << r.out;
}

// The tool-length rule in the module: the correction is computed for L = the machine file's
// tool_length_reference_mm + the tool length offset motion gives volkins.tool-offset (here a
// table of lengths relative to a 90 mm reference tool); before any offset, the file's L. The
// pin's and the slew time's former names (volkins.tool-length, volkins.tool-length-slew-time)
// still set them: configurations written before the rename load for one more release.
TEST(Volkins, CorrectionLengthIsTheReferencePlusTheOffset) {
  const std::string script = loadrt("tests/hal/data/mill3_reference.toml") +
                             "loadrt threads name1=servo period1=1000000\n"
                             "addf volkins.update servo\n"
                             "setp volkins.tool-length-slew-time 0\n"
                             "start\n"
                             "loadusr -w sleep 0.05\n"
                             "show pin volkins.correction-length\n"
                             "setp volkins.tool-length 25\n"
                             "loadusr -w sleep 0.05\n"
                             "show pin volkins.correction-length\n"
                             "setp volkins.tool-offset -12.5\n"
                             "loadusr -w sleep 0.05\n"
                             "show pin volkins.correction-length\n";
  const test::CommandResult r = test::halrun("reference", script);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::vector<double> L = shown_values(r.out, "volkins.correction-length");
  ASSERT_EQ(L.size(), 3u) << r.out;
  EXPECT_DOUBLE_EQ(L[0], 100.0) << r.out;  // tool_length_mm of the file
  EXPECT_DOUBLE_EQ(L[1], 115.0) << r.out;
  EXPECT_DOUBLE_EQ(L[2], 77.5) << r.out;
}

// units=inch: volkins.tool-offset and volkins.correction-length are in LinuxCNC's inches (motion
// nets the offset in them), the machine file's lengths in mm: 100 mm by default, 90 mm + 1 inch.
TEST(Volkins, InchConfigurationsTakeTheOffsetAndShowTheLengthInInches) {
  const std::string script = loadrt("tests/hal/data/mill3_reference.toml", "units=inch") +
                             "loadrt threads name1=servo period1=1000000\n"
                             "addf volkins.update servo\n"
                             "setp volkins.tool-offset-slew-time 0\n"
                             "start\n"
                             "loadusr -w sleep 0.05\n"
                             "show pin volkins.correction-length\n"
                             "setp volkins.tool-offset 1\n"
                             "loadusr -w sleep 0.05\n"
                             "show pin volkins.correction-length\n";
  const test::CommandResult r = test::halrun("inch", script);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::vector<double> L = shown_values(r.out, "volkins.correction-length");
  ASSERT_EQ(L.size(), 2u) << r.out;
  EXPECT_NEAR(L[0], 100.0 / 25.4, 1e-6) << r.out;  // halcmd shows 7 significant digits
  EXPECT_NEAR(L[1], 115.4 / 25.4, 1e-6) << r.out;
}

// Every golden bad machine file is refused by loadrt with the loader's message (the .expect
// twin, with absolute paths), and afterwards no volkins component exists and a good machine
// loads in the same HAL session.
TEST(Volkins, BadMachineFilesFailLoadrtWithTheirMessage) {
  const fs::path folder = test::source_path("tests/golden/bad_machines");
  const std::vector<fs::path> files = test::files_with_extension(folder, ".toml");
  ASSERT_GT(files.size(), 30u);
  std::string script;
  for (const fs::path& f : files) script += loadrt("tests/golden/bad_machines/" + f.filename().string());
  const test::CommandResult r = test::halrun("bad_machines", script + "show comp\n");

  for (const fs::path& f : files) {
    std::ifstream in(fs::path(f).replace_extension(".expect"));
    std::stringstream expected;
    expected << in.rdbuf();
    std::string message = expected.str();
    message.erase(message.find_last_not_of(" \n\r") + 1);
    EXPECT_NE(r.out.find("volkins: " + message + "\n"), std::string::npos)
        << f.filename() << ": expected\n  " << message << "\nin\n"
        << r.out;
  }
  EXPECT_FALSE(volkins_listed(r.out)) << "a refused load left a component:\n" << r.out;

  // The same HAL session then loads a good machine (nothing of the failures is in the way).
  const test::CommandResult good = test::halrun("bad_then_good", script + loadrt(shipped("mill3")) + "show comp\n");
  EXPECT_TRUE(volkins_listed(good.out)) << good.out;
}

// A new machine file without a restart (volkins.reload): the file loadrt named is changed on
// disk (a copy with its tables in a run folder); a pulse of volkins.reload reads it, ramps the
// correction out and the new file's in (reload-state 1 -> 2 -> 3 -> 0, recorded every servo
// period by a sampler), counts it and shows the new file's checksum (python's zlib.crc32 of
// the file's bytes then its tables' in the file's order); a file that changes the nominal
// geometry and one that does not load are refused with the file and the problem, the active
// file kept.
TEST(Volkins, ReloadSwapsACompatibleFileAndRefusesOthers) {
  const fs::path dir = test::run_folder("reload_files");
  std::ifstream in(test::machine_path("mill3"));
  std::stringstream text;
  text << in.rdbuf();
  const std::string local = std::regex_replace(text.str(), std::regex("\\.\\./\\.\\./tables/data/mill3/"), "");
  for (const char* t : {"x.csv", "y.csv", "z.csv", "z_by_y.csv"})
    fs::copy_file(test::source_path(std::string("tables/data/mill3/") + t), dir / t);
  const auto write = [&](const std::string& name, const std::string& content) {
    std::ofstream(dir / name) << content;
    fs::permissions(dir / name, fs::perms::all);
  };
  const std::string compatible = std::regex_replace(local, std::regex("EC0X_arcsec = 8\\.0"), "EC0X_arcsec = 12.0");
  const std::string moved_pole = std::regex_replace(local, std::regex("pole_mm = \\[0, 0, 500\\]"), "pole_mm = [0, 0, 501]");
  const std::string broken = std::regex_replace(local, std::regex("travel_mm = \\[0, 500\\]"), "travel_mm = [0, 500]\nspeed = 3");
  ASSERT_NE(compatible, local);
  ASSERT_NE(moved_pole, local);
  ASSERT_NE(broken, local);
  write("active.toml", local);
  write("compatible.toml", compatible);
  write("moved_pole.toml", moved_pole);
  write("broken.toml", broken);
  for (const auto& e : fs::directory_iterator(dir)) fs::permissions(e.path(), fs::perms::all);
  // The checksum computed apart from the module: the tables in the order the file names them.
  const auto crc = [&](const std::string& machine) {
    const test::CommandResult r = test::run_in(
        dir, "python3 -c \"import zlib; print(zlib.crc32(b''.join(open(f, 'rb').read() for f in ['" + machine +
                 "', 'y.csv', 'x.csv', 'z.csv', 'z_by_y.csv'])))\"");
    EXPECT_EQ(r.exit_code, 0) << r.out;
    return std::stoul(r.out);
  };
  const unsigned long old_crc = crc("active.toml"), new_crc = crc("compatible.toml");
  ASSERT_NE(old_crc, new_crc);

  const std::string d = dir.string() + "/";
  const std::string script = "loadrt volkins machine=" + d + "active.toml\n" +
                             "loadrt threads name1=servo period1=1000000\n"
                             "loadrt sampler depth=8000 cfg=sf\n"
                             "addf volkins.update servo\n"
                             "addf sampler.0 servo\n"
                             "net state volkins.reload-state => sampler.0.pin.0\n"
                             "net gain volkins.gain => sampler.0.pin.1\n"
                             "setp volkins.ramp-time 0.3\n"
                             "show pin volkins.checksum\n"
                             "start\n"
                             "loadusr -w sleep 0.5\n"
                             "loadusr -w cp " + d + "compatible.toml " + d + "active.toml\n"
                             "setp volkins.reload 1\n"
                             "loadusr -w halsampler -n 5000\n"
                             "show pin volkins.reloads\n"
                             "show pin volkins.reload-failed\n"
                             "show pin volkins.checksum\n"
                             "loadusr -w cp " + d + "moved_pole.toml " + d + "active.toml\n"
                             "setp volkins.reload 0\n"
                             "loadusr -w sleep 0.05\n"  // a servo period sees it low: the next is an edge
                             "setp volkins.reload 1\n"
                             "loadusr -w sleep 2\n"
                             "show pin volkins.reload-failed\n"
                             "show pin volkins.reloads\n"
                             "show pin volkins.checksum\n"
                             "loadusr -w cp " + d + "broken.toml " + d + "active.toml\n"
                             "setp volkins.reload 0\n"
                             "loadusr -w sleep 0.05\n"  // a servo period sees it low: the next is an edge
                             "setp volkins.reload 1\n"
                             "loadusr -w sleep 2\n"
                             "show pin volkins.reload-failed\n"
                             "show pin volkins.reloads\n"
                             "show pin volkins.checksum\n";
  const test::CommandResult r = test::halrun("reload", script);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  // The sampler's lines: state and gain of every servo period from the start.
  std::vector<int> states;
  std::vector<double> gains;
  const std::regex sample(R"((?:^|\n)(-?\d+) (-?[0-9.e+-]+) ?(?=\n))");
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), sample); it != std::sregex_iterator(); ++it) {
    states.push_back(std::stoi((*it)[1]));
    gains.push_back(std::stod((*it)[2]));
  }
  ASSERT_EQ(states.size(), 5000u) << r.out.substr(0, 2000);
  std::vector<int> sequence;  // the states in the order they came, each once
  for (int s : states)
    if (sequence.empty() || sequence.back() != s) sequence.push_back(s);
  EXPECT_EQ(sequence, (std::vector<int>{0, 1, 2, 3, 0})) << r.out.substr(0, 2000);
  const auto first = [&](int state) { return std::find(states.begin(), states.end(), state) - states.begin(); };
  const long ramp_out = first(3) - first(2), ramp_in = std::find(states.begin() + first(3), states.end(), 0) - states.begin() - first(3);
  EXPECT_NEAR(ramp_out, 300, 5) << "ms ramping out";  // ramp-time 0.3 s at 1 ms a period
  EXPECT_NEAR(ramp_in, 300, 5) << "ms ramping in";
  double largest_step = 0.0, lowest = 1.0;
  for (std::size_t k = 1; k < gains.size(); ++k) {
    largest_step = std::max(largest_step, std::abs(gains[k] - gains[k - 1]));
    lowest = std::min(lowest, gains[k]);
  }
  EXPECT_EQ(lowest, 0.0);                  // the swap at gain 0
  EXPECT_LT(largest_step, 2.0 / 300 + 1e-9);  // the ramp's rate limit, 2 / ramp-time: no step
  EXPECT_EQ(gains.back(), 1.0);
  std::cout << "reload: " << first(2) - first(1) << " ms reading, " << ramp_out << " ms out, " << ramp_in
            << " ms in; largest gain step " << largest_step << "\n";

  // Pins after each request.
  const std::regex s32(R"(s32\s+OUT\s+(-?\d+)\s+volkins\.reloads\s)"), u32(R"(u32\s+OUT\s+0x([0-9A-Fa-f]+)\s+volkins\.checksum\s)"),
      failed(R"(bit\s+OUT\s+(TRUE|FALSE)\s+volkins\.reload-failed\s)");
  const auto all = [&](const std::regex& re) {
    std::vector<std::string> v;
    for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), re); it != std::sregex_iterator(); ++it) v.push_back((*it)[1]);
    return v;
  };
  const std::vector<std::string> checksums = all(u32);
  ASSERT_EQ(checksums.size(), 4u) << r.out.substr(r.out.size() - std::min<std::size_t>(r.out.size(), 3000));
  EXPECT_EQ(std::stoul(checksums[0], nullptr, 16), old_crc);
  EXPECT_EQ(std::stoul(checksums[1], nullptr, 16), new_crc);
  EXPECT_EQ(std::stoul(checksums[2], nullptr, 16), new_crc) << "the refused file left the active one";
  EXPECT_EQ(std::stoul(checksums[3], nullptr, 16), new_crc) << "the refused file left the active one";
  EXPECT_EQ(all(s32), (std::vector<std::string>{"1", "1", "1"}));
  EXPECT_EQ(all(failed), (std::vector<std::string>{"FALSE", "TRUE", "TRUE"}));
  EXPECT_NE(r.out.find("volkins: reload refused: " + d + "active.toml: axis Z's pole is (0, 0, 501) mm, in the running file (0, 0, 500) mm"),
            std::string::npos) << r.out.substr(r.out.size() - std::min<std::size_t>(r.out.size(), 3000));
  EXPECT_TRUE(std::regex_search(r.out, std::regex("volkins: reload refused: " + d + "active\\.toml:\\d+:\\d+: error: .*speed")))
      << r.out.substr(r.out.size() - std::min<std::size_t>(r.out.size(), 3000));
}

TEST(Volkins, BadModuleParametersFailLoadrt) {
  const std::string mc300 = shipped("mc300");
  struct Case {
    std::string line, message;
  };
  const std::vector<Case> cases{
      {"loadrt volkins\n", "volkins: error: no machine file"},
      {loadrt(mc300, "coordinates=xyz"),
       "volkins: error: coordinates=xyz does not match the machine file machines/data/mc300.toml"},
      {loadrt(mc300, "coordinates=xyzba"), "joint 4's axis A is not in it (its axes are \"xyzbc\""},
      {loadrt(mc300, "world=tool"), "volkins: error: world=tool is not a world convention"},
      {loadrt(mc300, "world=tcp sparm=identityfirst"), "volkins: error: world=tcp and sparm=identityfirst contradict"},
      {loadrt(mc300, "units=cm"), "volkins: error: units=cm is not a length unit of LinuxCNC"},
      {"loadrt volkins machine=/nonexistent/machine.toml\n", "volkins: /nonexistent/machine.toml: error:"},
  };
  for (const Case& c : cases) {
    const test::CommandResult r = test::halrun("bad_parameters", c.line + "show comp\n");
    EXPECT_NE(r.out.find(c.message), std::string::npos) << c.line << r.out;
    EXPECT_NE(r.out.find("insmod for volkins failed"), std::string::npos) << c.line << r.out;
    EXPECT_FALSE(volkins_listed(r.out)) << c.line << r.out;
  }
}

}  // namespace
}  // namespace vc
