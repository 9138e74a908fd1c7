// A volkins configuration's limits against the correction: where it leaves each axis after
// homing (vc/init/home_position.hpp) and the room its joint limits leave at the ends of the
// travel (vc/init/joint_room.hpp). The configurations shipped here pass both; one homing at a
// limit, or a joint limit at its axis's, is refused with the INI lines and the value that fixes
// it; `volcomp check --ini` says so and exits 1.
#include "vc/init/home_position.hpp"
#include "vc/init/joint_room.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>

#include "init_test_files.hpp"
#include "vc/init/number.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::init {
namespace {

using test::source_path;

struct Config {
  const char* ini;
  const char* machine;
};
const Config kShipped[] = {{"kins/configs/mc300/mc300.ini", "machines/data/mc300.toml"},
                           {"kins/configs/mc300/mc300_thermal.ini", "machines/data/mc300_thermal.toml"},
                           {"kins/configs/mill3/mill3.ini", "machines/data/mill3.toml"},
                           {"kins/configs/mill3/mill3_gantry.ini", "machines/data/mill3.toml"}};

// `text` (an INI) with the first `KEY = ...` line of [section] (leading blanks allowed) made `KEY = value`.
std::string with_ini_value(std::string text, const std::string& section, const std::string& key,
                           const std::string& value) {
  const std::size_t from = text.find("[" + section + "]");
  EXPECT_NE(from, std::string::npos) << section;
  std::smatch line;
  const std::string rest = text.substr(from);
  EXPECT_TRUE(std::regex_search(rest, line, std::regex("\n[ \t]*" + key + "[ \t]*=[^\n]*"))) << section << key;
  text.replace(from + static_cast<std::size_t>(line.position(0)), static_cast<std::size_t>(line.length(0)),
               "\n" + key + " = " + value);
  return text;
}

// The INI's text with `KEY = value` of [JOINT_n] replaced, written beside nothing else.
std::filesystem::path with_joint_value(const Config& config, int joint, const std::string& key,
                                       const std::string& value, const std::string& name) {
  std::string text = test::file_text(source_path(config.ini));
  const std::string section = "[JOINT_" + std::to_string(joint) + "]";
  const std::size_t at = text.find("\n" + key + " = ", text.find(section)) + 1;
  text.replace(at, text.find('\n', at) - at, key + " = " + value);
  const std::filesystem::path ini = test::scratch_folder(name) / "config.ini";
  test::write_file(ini, text);
  return ini;
}
std::filesystem::path with_home(const Config& config, int joint, const std::string& value, const std::string& name) {
  return with_joint_value(config, joint, "HOME", value, name);
}

// A configuration as the checks take it: its INI (or `ini` in its place), its machine, volkins' parameters.
struct Loaded {
  LinuxcncIni ini;
  machine::Model model;
  VolkinsParameters volkins;
};
Loaded load(const Config& config, const std::string& ini = "") {
  LinuxcncIni read = LinuxcncIni::read(ini.empty() ? source_path(config.ini) : ini);
  const VolkinsParameters volkins = read_volkins_parameters(read);
  return {std::move(read), machine::load_machine(source_path(config.machine)), volkins};
}

TEST(HomePosition, ShippedConfigurationsHomeInsideTheirLimits) {
  for (const Config& c : kShipped) {
    SCOPED_TRACE(c.ini);
    const Loaded l = load(c);
    const machine::Model& model = l.model;
    const HomeCheck check = check_home_position(l.ini, model, l.volkins);
    EXPECT_TRUE(check.problems.empty()) << check.problems.front();
    ASSERT_EQ(check.axes.size(), static_cast<std::size_t>(model.joint_count()));
    // The world it reports maps back to the HOME joints through the inverse (the correction
    // evaluated forward, not inverted), and lies inside the limits.
    machine::Joints world(model.joint_count()), home(model.joint_count()), joints;
    for (int j = 0; j < model.joint_count(); ++j) {
      world[j] = check.axes[j].world;
      home[j] = check.axes[j].home;
      EXPECT_GE(world[j], check.axes[j].min_limit) << check.axes[j].letter;
      EXPECT_LE(world[j], check.axes[j].max_limit) << check.axes[j].letter;
    }
    ASSERT_EQ(machine::joints_from_world(model, check.convention, world, model.correction_length(0.0), joints),
              machine::Status::Ok);
    EXPECT_LT((joints - home).cwiseAbs().maxCoeff(), 1e-9);
    // The linear axes' correction at home is not nothing: homing at the limit would be beyond it.
    EXPECT_GT((world - home).head(3).cwiseAbs().maxCoeff(), 1e-3) << "the check would have nothing to find";
  }
}

TEST(HomePosition, HomingAtTheLimitIsRefusedWithTheLinesAndTheFix) {
  // MC-300: X homes at its MAX_LIMIT 0, where the corrected world X is ~5 um beyond it.
  const std::filesystem::path ini_path = with_home(kShipped[0], 0, "0", "mc300_at_limit");
  const LinuxcncIni ini = LinuxcncIni::read(ini_path.string());
  const machine::Model model = machine::load_machine(source_path(kShipped[0].machine));
  const HomeCheck check = check_home_position(ini, model, read_volkins_parameters(ini));
  ASSERT_EQ(check.problems.size(), 1u);
  const std::string& p = check.problems[0];
  EXPECT_NE(p.find("X homes "), std::string::npos) << p;
  EXPECT_NE(p.find("beyond its MAX_LIMIT (config.ini:"), std::string::npos) << p;
  EXPECT_TRUE(std::regex_search(p, std::regex("config.ini:[0-9]+ `HOME = 0` puts the corrected world X at 0\\.00")))
      << p;
  EXPECT_NE(p.find("would exceed X's positive limit"), std::string::npos) << p;
  EXPECT_NE(p.find("[JOINT_0]HOME = -0.1"), std::string::npos) << p;
  EXPECT_GT(check.axes[0].world, 0.0);

  // mill3: X homes at its MIN_LIMIT 0, the world ~6 um below it.
  const std::filesystem::path mill_ini = with_home(kShipped[2], 0, "0", "mill3_at_limit");
  const LinuxcncIni mill = LinuxcncIni::read(mill_ini.string());
  const HomeCheck mill_check =
      check_home_position(mill, machine::load_machine(source_path(kShipped[2].machine)), read_volkins_parameters(mill));
  ASSERT_EQ(mill_check.problems.size(), 1u);
  EXPECT_NE(mill_check.problems[0].find("beyond its MIN_LIMIT"), std::string::npos) << mill_check.problems[0];
  EXPECT_NE(mill_check.problems[0].find("[JOINT_0]HOME = 0.1"), std::string::npos) << mill_check.problems[0];
}

TEST(HomePosition, TheGantrysSecondJointIsReadForItsLetter) {
  // coordinates=xyyz: the machine's Z is LinuxCNC's joint 3; a Z homed at its MAX_LIMIT there.
  const std::filesystem::path ini_path = with_home(kShipped[3], 3, "0.2", "gantry_z");
  const LinuxcncIni ini = LinuxcncIni::read(ini_path.string());
  const HomeCheck check =
      check_home_position(ini, machine::load_machine(source_path(kShipped[3].machine)), read_volkins_parameters(ini));
  ASSERT_EQ(check.axes.size(), 3u);
  EXPECT_EQ(check.axes[2].joint, 3);
  EXPECT_DOUBLE_EQ(check.axes[2].home, 0.2);
  ASSERT_EQ(check.problems.size(), 1u);
  EXPECT_NE(check.problems[0].find("Z homes "), std::string::npos) << check.problems[0];
  EXPECT_NE(check.problems[0].find("[JOINT_3]HOME = -0.1"), std::string::npos) << check.problems[0];
}

TEST(HomePosition, VolcompCheckSaysItAndExitsOne) {
  const test::CommandResult good =
      test::run_volcomp("check " + test::machine_path("mc300") + " --samples 10 --ini " + source_path(kShipped[0].ini));
  EXPECT_EQ(good.exit_code, 0) << good.out;
  EXPECT_NE(good.out.find("  after homing (each joint at its HOME"), std::string::npos) << good.out;
  EXPECT_NE(good.out.find("    X  HOME -0.1 -> world -0.09"), std::string::npos) << good.out;

  const std::filesystem::path bad = with_home(kShipped[0], 0, "0", "mc300_cli");
  const test::CommandResult refused =
      test::run_volcomp("check " + test::machine_path("mc300") + " --samples 10 --ini " + bad.string());
  EXPECT_EQ(refused.exit_code, 1) << refused.out;
  EXPECT_NE(refused.out.find("error: X homes "), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("NOT usable"), std::string::npos) << refused.out;
}

TEST(JointRoom, ShippedConfigurationsLeaveRoomForTheCorrection) {
  for (const Config& c : kShipped) {
    SCOPED_TRACE(c.ini);
    const Loaded l = load(c);
    const machine::Model& model = l.model;
    const JointRoomCheck check = check_joint_room(l.ini, model, l.volkins);
    EXPECT_TRUE(check.problems.empty()) << check.problems.front();
    EXPECT_EQ(check.poses, 2 * static_cast<int>(std::pow(5, model.joint_count())));
    // The correction does take joints beyond the axes' limits (else there is nothing to check),
    // and every joint stays within its own.
    double beyond_axis = 0;
    for (const JointRoom& j : check.joints) {
      EXPECT_GE(j.lowest, j.min_limit) << j.joint;
      EXPECT_LE(j.highest, j.max_limit) << j.joint;
      const machine::Axis& a = model.axes[static_cast<std::size_t>(model.joint_of(j.letter))];
      beyond_axis = std::max({beyond_axis, j.highest - a.travel_max, a.travel_min - j.lowest});
    }
    EXPECT_GT(beyond_axis, 1e-3);
  }
  // The gantry: both Y joints are checked.
  const LinuxcncIni gantry = LinuxcncIni::read(source_path(kShipped[3].ini));
  const JointRoomCheck g = check_joint_room(gantry, machine::load_machine(source_path(kShipped[3].machine)),
                                            read_volkins_parameters(gantry));
  ASSERT_EQ(g.joints.size(), 4u);
  EXPECT_EQ(g.joints[1].letter, 'Y');
  EXPECT_EQ(g.joints[2].letter, 'Y');
  EXPECT_EQ(g.joints[2].highest, g.joints[1].highest);
}

TEST(JointRoom, AJointLimitAtItsAxisLimitIsRefusedWithTheFix) {
  // MC-300's Y joint limited where its axis is (0): the correction takes it ~0.18 mm beyond.
  const std::filesystem::path ini_path = with_joint_value(kShipped[0], 1, "MAX_LIMIT", "0", "mc300_no_room");
  const LinuxcncIni ini = LinuxcncIni::read(ini_path.string());
  const machine::Model model = machine::load_machine(source_path(kShipped[0].machine));
  const JointRoomCheck check = check_joint_room(ini, model, read_volkins_parameters(ini));
  ASSERT_EQ(check.problems.size(), 1u);
  const std::string& p = check.problems[0];
  EXPECT_TRUE(
      std::regex_search(p, std::regex("^joint 1 \\(Y\\): the correction takes it to 0\\.1[0-9]* at the upper end "
                                      "of Y's travel, [0-9.]+ um beyond its MAX_LIMIT \\(config.ini:[0-9]+ "
                                      "`MAX_LIMIT = 0`\\)")))
      << p;
  // The cause is the axis's limit at the joint's: narrowing it is the fix; widening the joint's
  // only with the travel before the limit switch.
  std::smatch fix;
  ASSERT_TRUE(std::regex_search(p, fix,
                                std::regex("The cause is Y's own limit, \\[AXIS_Y\\]MAX_LIMIT \\(config.ini:[0-9]+ "
                                           "`MAX_LIMIT = 0`\\), .*: narrow Y's travel: \\[AXIS_Y\\]MAX_LIMIT = "
                                           "(-0\\.[0-9]+)\\. That is the safe fix")))
      << p;
  EXPECT_NE(p.find("widening the joint's limit instead ([JOINT_1]MAX_LIMIT = 0.2) is only right if the machine has "
                   "that travel before its limit switch"),
            std::string::npos)
      << p;
  // The advised axis limit leaves the room.
  const std::filesystem::path fixed = ini_path.parent_path() / "fixed.ini";
  test::write_file(fixed, with_ini_value(test::file_text(ini_path), "AXIS_Y", "MAX_LIMIT", fix[1].str()));
  const LinuxcncIni fixed_ini = LinuxcncIni::read(fixed.string());
  const JointRoomCheck after = check_joint_room(fixed_ini, model, read_volkins_parameters(fixed_ini));
  EXPECT_TRUE(after.problems.empty()) << after.problems.front();

  const test::CommandResult refused =
      test::run_volcomp("check " + test::machine_path("mc300") + " --samples 10 --ini " + ini_path.string());
  EXPECT_EQ(refused.exit_code, 1) << refused.out;
  EXPECT_NE(refused.out.find("error: joint 1 (Y)"), std::string::npos) << refused.out;
}

// LinuxCNC's xyzbc-trt sample, retrofitted (volcomp init, its patch) and given a machine file
// with errors (volcomp perturb): its [AXIS_B] limits are +-36000 over a tilting joint of -100 ..
// 50, its C's and the linear axes' limits its joints'. The check traces each crossing to the axis
// limit that causes it and never widens the tilting joint's; the advised values, written in,
// pass.
TEST(JointRoom, TheTrtSampleIsAdvisedToNarrowItsAxisLimitsNeverToWidenItsTiltingJoint) {
  if (!test::samples_installed()) GTEST_SKIP() << "LinuxCNC's sample configurations are not installed";
  namespace fs = std::filesystem;
  const fs::path dir = test::scratch_folder("trt_room"), user = dir / "user";
  fs::copy(test::kSampleConfigs / "table-rotary-tilting", user, fs::copy_options::recursive);
  const fs::path ini_path = user / "xyzbc-trt.ini";
  const test::CommandResult init =
      test::run_volcomp("init " + ini_path.string() + " -o " + (user / "xyzbc-trt.toml").string() + " --patch " +
                        (dir / "volkins.patch").string());
  ASSERT_EQ(init.exit_code, 0) << init.out;
  ASSERT_EQ(test::apply_patch(user, dir / "volkins.patch"), 0);
  const test::CommandResult perturb =
      test::run_volcomp("perturb " + (user / "xyzbc-trt.toml").string() + " -o " + (dir / "measured").string() +
                        " --location EX0C=15um --location EY0C=-10um --location EA0C=-6arcsec --location EC0B=8arcsec");
  ASSERT_EQ(perturb.exit_code, 0) << perturb.out;
  const std::string machine = (dir / "measured" / "xyzbc-trt.toml").string();

  const test::CommandResult refused =
      test::run_volcomp("check " + machine + " --samples 10 --ini " + ini_path.string());
  EXPECT_EQ(refused.exit_code, 1) << refused.out;
  EXPECT_TRUE(std::regex_search(
      refused.out, std::regex("error: joint 3 \\(B\\): B's own limit, \\[AXIS_B\\]MAX_LIMIT \\(xyzbc-trt.ini:[0-9]+ "
                              "`MAX_LIMIT = +36000`\\), lies beyond its joint's MAX_LIMIT \\(xyzbc-trt.ini:[0-9]+ "
                              "`MAX_LIMIT = +50`\\): LinuxCNC refuses a move that ends there")))
      << refused.out;
  // A linear axis at its joint's limit: the correction crosses it; narrowing is the safe fix.
  EXPECT_TRUE(
      std::regex_search(refused.out, std::regex("error: joint 0 \\(X\\): the correction takes it to 200\\.0[0-9]+ at "
                                                "the upper end of X's travel.*narrow X's travel: "
                                                "\\[AXIS_X\\]MAX_LIMIT = 199.9. That is the safe fix")))
      << refused.out;
  EXPECT_NE(refused.out.find("[AXIS_B]MAX_LIMIT = 49.9 (a rotary axis with stops"), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("[AXIS_B]MIN_LIMIT = -99.9 (a rotary axis with stops"), std::string::npos) << refused.out;
  for (const char* widened :
       {"[JOINT_3]MAX_LIMIT =", "[JOINT_3]MIN_LIMIT =", "[JOINT_4]MAX_LIMIT =", "[JOINT_4]MIN_LIMIT ="})
    EXPECT_EQ(refused.out.find(widened), std::string::npos) << "a rotary joint's stops widened: " << refused.out;

  // Every advised axis limit written into the INI: the check passes.
  std::string text = test::file_text(ini_path);
  const std::regex advice("narrow [A-Z]'s travel: \\[(AXIS_[A-Z])\\]((MAX|MIN)_LIMIT) = (-?[0-9]+(\\.[0-9]+)?)");
  int advised = 0;
  for (auto it = std::sregex_iterator(refused.out.begin(), refused.out.end(), advice); it != std::sregex_iterator();
       ++it, ++advised)
    text = with_ini_value(text, (*it)[1].str(), (*it)[2].str(), (*it)[4].str());
  EXPECT_GE(advised, 3) << refused.out;  // B at both ends and a linear axis at least
  test::write_file(ini_path, text);
  const test::CommandResult usable = test::run_volcomp("check " + machine + " --samples 10 --ini " + ini_path.string());
  EXPECT_EQ(usable.exit_code, 0) << usable.out;
}

// A rotary joint without limits (LinuxCNC's +-1e99, a continuous table) needs no room, and its
// axis without limits is sampled over the machine file's travel, not over +-1e99.
TEST(JointRoom, ARotaryJointWithoutLimitsNeedsNoRoom) {
  std::string text = test::file_text(source_path(kShipped[0].ini));
  for (const char* key : {"MIN_LIMIT", "MAX_LIMIT"}) {
    const std::string none = key[1] == 'I' ? "-1e99" : "1e99";
    text = with_ini_value(with_ini_value(text, "JOINT_4", key, none), "AXIS_C", key, none);
  }
  const std::filesystem::path ini_path = test::scratch_folder("mc300_continuous_c") / "config.ini";
  test::write_file(ini_path, text);
  const LinuxcncIni ini = LinuxcncIni::read(ini_path.string());
  const machine::Model model = machine::load_machine(source_path(kShipped[0].machine));
  const JointRoomCheck check = check_joint_room(ini, model, read_volkins_parameters(ini));
  EXPECT_TRUE(check.problems.empty()) << check.problems.front();
  ASSERT_EQ(check.joints.size(), 5u);
  EXPECT_EQ(check.joints[4].letter, 'C');
  EXPECT_TRUE(no_limit(check.joints[4].max_limit));
  const machine::Axis& c = model.axes[static_cast<std::size_t>(model.joint_of('C'))];
  EXPECT_NEAR(check.joints[4].highest, c.travel_max, 0.5);  // the correction: hundredths of a degree
  EXPECT_NEAR(check.joints[4].lowest, c.travel_min, 0.5);
}

// mill3's configuration in inch (LINEAR_UNITS = inch, volkins' units=inch, every linear limit and
// HOME divided by 25.4): the checks see the same machine in mm, and advise in inch.
TEST(VolkinsConfig, AnInchConfigurationIsCheckedInMmAndAdvisedInInch) {
  std::string text = test::file_text(source_path(kShipped[2].ini));
  const auto replace = [&](const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("LINEAR_UNITS = mm", "LINEAR_UNITS = inch");
  replace("coordinates=xyz", "coordinates=xyz units=inch");
  const LinuxcncIni mm_ini = LinuxcncIni::read(source_path(kShipped[2].ini));
  for (const char* section : {"AXIS_X", "AXIS_Y", "AXIS_Z", "JOINT_0", "JOINT_1", "JOINT_2"})
    for (const char* key : {"MIN_LIMIT", "MAX_LIMIT", "HOME"})
      if (const IniEntry* e = mm_ini.find(section, key))
        text = with_ini_value(text, section, key, format_number(std::stod(e->value) / 25.4));
  const std::filesystem::path ini_path = test::scratch_folder("mill3_inch") / "config.ini";
  test::write_file(ini_path, text);
  const LinuxcncIni inch_ini = LinuxcncIni::read(ini_path.string());
  const VolkinsParameters inch = read_volkins_parameters(inch_ini);
  ASSERT_TRUE(inch.units.inch());
  const machine::Model model = machine::load_machine(source_path(kShipped[2].machine));

  const VolkinsParameters mm = read_volkins_parameters(mm_ini);
  const HomeCheck home_mm = check_home_position(mm_ini, model, mm),
                  home_inch = check_home_position(inch_ini, model, inch);
  EXPECT_TRUE(home_inch.problems.empty()) << home_inch.problems.front();
  const JointRoomCheck room_mm = check_joint_room(mm_ini, model, mm),
                       room_inch = check_joint_room(inch_ini, model, inch);
  EXPECT_TRUE(room_inch.problems.empty()) << room_inch.problems.front();
  ASSERT_EQ(room_inch.joints.size(), room_mm.joints.size());
  for (std::size_t j = 0; j < room_mm.joints.size(); ++j) {
    EXPECT_NEAR(home_inch.axes[j].world, home_mm.axes[j].world, 1e-9) << j;
    EXPECT_NEAR(home_inch.axes[j].max_limit, home_mm.axes[j].max_limit, 1e-9) << j;
    EXPECT_NEAR(room_inch.joints[j].highest, room_mm.joints[j].highest, 1e-9) << j;
    EXPECT_NEAR(room_inch.joints[j].lowest, room_mm.joints[j].lowest, 1e-9) << j;
    EXPECT_NEAR(room_inch.joints[j].max_limit, room_mm.joints[j].max_limit, 1e-9) << j;
  }

  // X homed at its MIN_LIMIT 0 and the Y joint limited at its axis's 0 .. 300 mm (11.811 inch):
  // the advice in inch, in steps of 0.01 inch.
  const std::filesystem::path bad_path = ini_path.parent_path() / "bad.ini";
  test::write_file(bad_path, with_ini_value(with_ini_value(with_ini_value(text, "JOINT_0", "HOME", "0"), "JOINT_1",
                                                           "MAX_LIMIT", format_number(300 / 25.4)),
                                            "JOINT_1", "MIN_LIMIT", "0"));
  const LinuxcncIni bad = LinuxcncIni::read(bad_path.string());
  const HomeCheck home = check_home_position(bad, model, read_volkins_parameters(bad));
  ASSERT_EQ(home.problems.size(), 1u);
  EXPECT_NE(home.problems[0].find("[JOINT_0]HOME = 0.01"), std::string::npos) << home.problems[0];
  EXPECT_TRUE(std::regex_search(home.problems[0], std::regex("world X at -0\\.000[0-9]+ inch"))) << home.problems[0];
  const JointRoomCheck room = check_joint_room(bad, model, read_volkins_parameters(bad));
  ASSERT_FALSE(room.problems.empty());
  for (const std::string& p : room.problems) {
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        p, m,
        std::regex("takes it to (-?[0-9.]+) at the (upper|lower) end.*\\[AXIS_Y\\]M(AX|IN)_LIMIT = (-?[0-9.]+) inch")))
        << p;
    const bool upper = m[2] == "upper";
    EXPECT_NEAR(std::stod(m[1]), upper ? 300 / 25.4 : 0.0, 0.001) << p;  // inch, not mm
    EXPECT_NEAR(std::stod(m[4]), upper ? 11.81 : 0.01, 1e-9) << p;       // one step inside
  }
}

TEST(HomePosition, AnotherModuleIsNotVolkins) {
  const LinuxcncIni ini = LinuxcncIni::read(source_path("kins/configs/mc300/mc300_stock.ini"));
  EXPECT_THROW(read_volkins_parameters(ini), LoadError);
}

}  // namespace
}  // namespace vc::init
