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
  EXPECT_NE(p.find("[JOINT_1]MAX_LIMIT = 0.2"), std::string::npos) << p;

  const test::CommandResult refused =
      test::run_volcomp("check " + test::machine_path("mc300") + " --samples 10 --ini " + ini_path.string());
  EXPECT_EQ(refused.exit_code, 1) << refused.out;
  EXPECT_NE(refused.out.find("error: joint 1 (Y)"), std::string::npos) << refused.out;
}

TEST(HomePosition, AnotherModuleIsNotVolkins) {
  const LinuxcncIni ini = LinuxcncIni::read(source_path("kins/configs/mc300/mc300_stock.ini"));
  EXPECT_THROW(read_volkins_parameters(ini), LoadError);
}

}  // namespace
}  // namespace vc::init
