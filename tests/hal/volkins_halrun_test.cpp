// volkins in a real HAL (halrun, no motion): it loads with every shipped machine and exposes
// its pins and parameters; the enable ramp moves as documented; bad machine files and bad
// module parameters make loadrt fail with the loader's message and leave nothing loaded.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
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
                          "volkins.thermal.gain"})
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
