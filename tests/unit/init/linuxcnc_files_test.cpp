// `volcomp init` reads a LinuxCNC configuration as LinuxCNC 2.9 does: the INI file (blanks,
// comments, repeated keys, #INCLUDE, continued lines, the first section of a name), the HAL
// files in LinuxCNC's order ([SECTION]KEY references, comments, LIB:, Tcl files not read),
// and what a kinematics pin holds at the end (setp, sets on its signal, the last one wins, a
// pin driven by another is live), every value with its file and line.
#include <gtest/gtest.h>

#include <cstdlib>

#include "init_test_files.hpp"
#include "vc/init/hal_file.hpp"
#include "vc/init/linuxcnc_ini.hpp"
#include "vc/init/pin_value.hpp"

namespace vc::init {
namespace {

namespace fs = std::filesystem;
using test::write_file;

// A configuration of the files given (name, text) in a scratch folder; returns the INI's path.
fs::path configuration(const std::string& name, const std::vector<std::pair<std::string, std::string>>& files) {
  const fs::path dir = test::scratch_folder(name);
  for (const auto& [file, text] : files) write_file(dir / file, text);
  return dir / files.front().first;
}

TEST(LinuxcncIni, ReadsValuesAsLinuxcncWithTheirLines) {
  const fs::path ini = configuration("ini", {{"m.ini",
                                              "# comment\n"
                                              "[KINS]\n"
                                              "            KINEMATICS = trivkins coordinates=xyz   \r\n"
                                              "JOINTS=3\n"
                                              "; another comment\n"
                                              "[HAL]\n"
                                              "HALCMD = net a b\n"
                                              "HALFILE = x.hal\n"
                                              "HALCMD = setp c \\\n"
                                              "  1\n"
                                              "[KINS]\n"
                                              "JOINTS = 9\n"}});
  const LinuxcncIni r = LinuxcncIni::read(ini.string());
  const IniEntry* k = r.find("KINS", "KINEMATICS");
  ASSERT_NE(k, nullptr);
  EXPECT_EQ(k->value, "trivkins coordinates=xyz");
  EXPECT_EQ(k->line, 3);
  EXPECT_EQ(k->path, ini.string());
  EXPECT_EQ(k->value_offset, 25u);
  EXPECT_EQ(r.find("KINS", "JOINTS")->value, "3");  // the first [KINS] only, as LinuxCNC
  const auto halcmd = r.find_all("HAL", "HALCMD");
  ASSERT_EQ(halcmd.size(), 2u);
  EXPECT_EQ(halcmd[0]->value, "net a b");
  EXPECT_EQ(halcmd[1]->value, "setp c   1");  // continued with '\'
  EXPECT_EQ(halcmd[1]->line, 9);
  EXPECT_EQ(halcmd[1]->last_line, 10);
  EXPECT_EQ(r.find("HAL", "NONE"), nullptr);
  EXPECT_EQ(r.where_missing("HAL").line, 6);
  EXPECT_EQ(r.cite(*k), "m.ini:3 `KINEMATICS = trivkins coordinates=xyz`");
  EXPECT_EQ(r.files().front().lines[2].end, "\r\n");  // line ends kept for the patch
}

TEST(LinuxcncIni, FollowsIncludesKeepingTheirFileAndLine) {
  const fs::path ini = configuration("include", {{"main.ini", "#INCLUDE base.inc\n[KINS]\nJOINTS = 3\n"},
                                                 {"base.inc", "[TRAJ]\nCOORDINATES = X Y Z\n#INCLUDE nested.inc\n"}});
  const LinuxcncIni r = LinuxcncIni::read(ini.string());
  const IniEntry* c = r.find("TRAJ", "COORDINATES");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->path, (ini.parent_path() / "base.inc").string());
  EXPECT_EQ(c->line, 2);
  EXPECT_EQ(r.find("KINS", "JOINTS")->line, 3);
  EXPECT_EQ(r.files().size(), 2u);  // an #INCLUDE in an included file is a comment (no recursion)

  const fs::path bad = configuration("bad_include", {{"main.ini", "[KINS]\n#INCLUDE missing.inc\n"}});
  try {
    LinuxcncIni::read(bad.string());
    FAIL() << "a missing #INCLUDE was accepted";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where().line, 2);
    EXPECT_NE(std::string(e.what()).find("#INCLUDE missing.inc: cannot read"), std::string::npos) << e.what();
  }
}

TEST(HalFile, RunsHalfilesThenHalcmdsThenPostguiWithReferencesReplaced) {
  const fs::path lib = test::scratch_folder("hallib");
  write_file(lib / "lib.hal", "setp lib.pin 1\n");
  write_file(lib / "sim.tcl", "this is not read\n");
  ::setenv("HALLIB_DIR", lib.c_str(), 1);
  const fs::path ini = configuration("hal", {{"m.ini",
                                              "[KINS]\nKINEMATICS = trivkins\n[AXIS_X]\nMAX_LIMIT = 7\n"
                                              "[HAL]\n"
                                              "HALFILE = LIB:sim.tcl -arg\n"
                                              "HALFILE = local.hal\n"
                                              "HALCMD = setp halcmd.pin [AXIS_X]MAX_LIMIT\n"
                                              "POSTGUI_HALFILE = lib.hal\n"
                                              "POSTTASK_HALFILE = task.hal\n"},
                                             {"task.hal", "setp task.pin 2\n"},
                                             {"local.hal",
                                              "loadrt [KINS]KINEMATICS   # the kinematics\n"
                                              "net sig <= out.pin => in.pin other.pin\n"
                                              "\n"
                                              "a.pin = [AXIS_X](MAX_LIMIT)\n"}});
  const LinuxcncIni r = LinuxcncIni::read(ini.string());
  const HalConfig hal = read_hal(r);
  ::unsetenv("HALLIB_DIR");
  ASSERT_EQ(hal.uses.size(), 4u);
  EXPECT_FALSE(hal.uses[0].read);  // Tcl
  EXPECT_EQ(hal.uses[0].path, (lib / "sim.tcl").string());
  EXPECT_TRUE(hal.uses[1].read);
  EXPECT_EQ(hal.uses[2].key, "POSTTASK_HALFILE");
  EXPECT_EQ(hal.uses[3].path, (lib / "lib.hal").string());  // not in the folder: from the library
  ASSERT_EQ(hal.commands.size(), 6u);
  EXPECT_EQ(hal.commands[0].words, (std::vector<std::string>{"loadrt", "trivkins"}));
  EXPECT_FALSE(hal.commands[0].word_is_token(1));  // from [KINS]KINEMATICS
  EXPECT_EQ(hal.commands[1].line, 2);
  EXPECT_EQ(hal.commands[2].words[2], "7");
  EXPECT_EQ(hal.commands[3].words[1], "task.pin");  // task runs POSTTASK_HALFILEs before the HALCMDs
  EXPECT_EQ(hal.commands[4].words, (std::vector<std::string>{"setp", "halcmd.pin", "[AXIS_X]MAX_LIMIT"}))
      << "a HALCMD runs as written";
  EXPECT_TRUE(hal.commands[4].in_ini);
  EXPECT_EQ(hal.commands[5].path, (lib / "lib.hal").string());
  const auto net = net_of(hal.commands[1]);
  ASSERT_TRUE(net);
  EXPECT_EQ(net->signal, "sig");
  ASSERT_EQ(net->pins.size(), 3u);
  EXPECT_FALSE(net->pins[0].reader);
  EXPECT_TRUE(net->pins[1].reader);
  EXPECT_TRUE(net->pins[2].reader);
  const auto setp = setp_of(hal.commands[2]);
  ASSERT_TRUE(setp);
  EXPECT_EQ(setp->target, "a.pin");
}

// loadrt and loadusr as halcmd takes them (loadusr's options -w -W -i -n NAME, as getopt
// "+wWin:"), and the net that puts a pin on its signal.
TEST(HalFile, ReadsLoadCommandsAndTheSignalOfAPin) {
  const fs::path ini = configuration("loads", {{"m.ini", "[HAL]\nHALFILE = m.hal\n"},
                                               {"m.hal",
                                                "loadrt sum2 names=a,b\n"
                                                "loadusr -W 5axisgui pivot_len=300\n"
                                                "loadusr -Wn gui /usr/bin/5axisgui x=1\n"
                                                "loadusr -i -nname prog\n"
                                                "net :s a.out => b.in0\n"
                                                "net :s => k.pin\n"}});
  const HalConfig hal = read_hal(LinuxcncIni::read(ini.string()));
  ASSERT_EQ(hal.commands.size(), 6u);
  const auto rt = loadrt_of(hal.commands[0]);
  ASSERT_TRUE(rt);
  EXPECT_EQ(rt->module, "sum2");
  EXPECT_EQ(rt->arguments, (std::vector<std::string>{"names=a,b"}));
  EXPECT_FALSE(loadusr_of(hal.commands[0]));
  const auto gui = loadusr_of(hal.commands[1]);
  ASSERT_TRUE(gui);
  EXPECT_EQ(gui->module, "5axisgui");
  EXPECT_EQ(gui->arguments, (std::vector<std::string>{"pivot_len=300"}));
  EXPECT_EQ(loadusr_of(hal.commands[2])->module, "/usr/bin/5axisgui");  // -Wn takes the next word
  EXPECT_EQ(loadusr_of(hal.commands[2])->arguments, (std::vector<std::string>{"x=1"}));
  EXPECT_EQ(loadusr_of(hal.commands[3])->module, "prog");  // -nname: the name in the option
  std::string signal;
  EXPECT_EQ(net_of_pin(hal, "k.pin", &signal), &hal.commands[5]);
  EXPECT_EQ(signal, ":s");
  EXPECT_EQ(net_of_pin(hal, "a.out"), &hal.commands[4]);
  EXPECT_EQ(net_of_pin(hal, "none.pin"), nullptr);
}

TEST(HalFile, RefusesAnUndefinedIniReferenceWithItsLine) {
  const fs::path ini =
      configuration("undefined", {{"m.ini", "[HAL]\nHALFILE = m.hal\n"}, {"m.hal", "# first\nsetp a.b [NOPE]VALUE\n"}});
  try {
    read_hal(LinuxcncIni::read(ini.string()));
    FAIL() << "an undefined reference was accepted";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where().path, (ini.parent_path() / "m.hal").string());
    EXPECT_EQ(e.where().line, 2);
    EXPECT_NE(std::string(e.what()).find("[NOPE]VALUE is not defined"), std::string::npos) << e.what();
  }
}

TEST(PinValue, TheLastSettingInLinuxcncsOrderWins) {
  const fs::path ini = configuration("pins", {{"m.ini",
                                               "[HAL]\nHALFILE = m.hal\n"
                                               "HALCMD = sets :off 2.5\n"
                                               "HALCMD = net :live motion.tooloffset.z\n"},
                                              {"m.hal",
                                               "setp k.set 1\n"
                                               "setp k.set -4e1\n"
                                               "net :off k.off => gui.off\n"
                                               "setp k.off 3\n"
                                               "net :live k.live\n"
                                               "net :read k.read => gui.read\n"
                                               "setp k.bad 1O\n"}});
  const LinuxcncIni r = LinuxcncIni::read(ini.string());
  const HalConfig hal = read_hal(r);
  const PinValue set = pin_value(hal, "k.set", 0.0);
  EXPECT_EQ(set.source, PinValue::Source::Setp);
  EXPECT_EQ(set.value, -40.0);
  EXPECT_EQ(set.command->line, 2);
  const PinValue off = pin_value(hal, "k.off", 0.0);  // setp in the HAL file, then sets in a HALCMD
  EXPECT_EQ(off.source, PinValue::Source::Sets);
  EXPECT_EQ(off.value, 2.5);
  EXPECT_EQ(off.signal, ":off");
  EXPECT_EQ(off.net->line, 3);
  const PinValue live = pin_value(hal, "k.live", 0.0);
  EXPECT_EQ(live.source, PinValue::Source::Live);
  EXPECT_EQ(live.driver, "motion.tooloffset.z");
  const PinValue read = pin_value(hal, "k.read", 7.0);  // gui.read only reads the signal
  EXPECT_EQ(read.source, PinValue::Source::Default);
  EXPECT_EQ(read.value, 7.0);
  try {
    pin_value(hal, "k.bad", 0.0);
    FAIL() << "a value that is not a number was accepted";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where().line, 7);
    EXPECT_NE(std::string(e.what()).find("'1O' is not a number (the value of k.bad)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vc::init
