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

// halcmd's `source FILE` runs FILE's commands at that point (do_source_cmd): from the
// configuration folder, INI references replaced in a chain that began in a HAL file, no line
// continuation; the last setting wins in that order.
TEST(HalFile, FollowsSourceWhereLinuxcncDoes) {
  const fs::path ini = configuration("source", {{"m.ini",
                                                 "[GEO]\nZ = 50\nFILE = geometry.hal\n"
                                                 "[HAL]\nHALFILE = sub/m.hal\nHALCMD = source late.hal\n"},
                                                {"geometry.hal", "setp k.z [GEO]Z\nsetp k.x 2 \\\nsetp k.y 3\n"},
                                                {"late.hal", "setp k.y 9\n"}});
  // m.hal lies in sub/, but halcmd opens a sourced name from the configuration folder.
  fs::create_directories(ini.parent_path() / "sub");
  write_file(ini.parent_path() / "sub/m.hal", "setp k.z 1\nsource [GEO]FILE\nsetp k.after 1\n");
  const LinuxcncIni r = LinuxcncIni::read(ini.string());
  const HalConfig hal = read_hal(r);
  std::vector<std::string> order;
  for (const HalCommand& c : hal.commands) order.push_back(c.words[0] + " " + (c.words.size() > 1 ? c.words[1] : ""));
  EXPECT_EQ(order, (std::vector<std::string>{"setp k.z", "source geometry.hal", "setp k.z", "setp k.x", "setp k.y",
                                             "setp k.after", "source late.hal", "setp k.y"}));
  EXPECT_EQ(pin_value(hal, "k.z", 0.0).value, 50.0);  // the sourced setp comes after the HAL file's
  EXPECT_EQ(pin_value(hal, "k.z", 0.0).command->path, (ini.parent_path() / "geometry.hal").string());
  EXPECT_EQ(pin_value(hal, "k.z", 0.0).command->line, 1);
  EXPECT_EQ(pin_value(hal, "k.y", 0.0).value, 9.0);  // the HALCMD's source runs after the HAL files
  // No '\' continuation in a sourced file: `setp k.x 2 \` is its own command with the word `\`.
  EXPECT_EQ(hal.commands[3].words, (std::vector<std::string>{"setp", "k.x", "2", "\\"}));
  ASSERT_EQ(hal.sources.size(), 2u);
  EXPECT_EQ(hal.sources[0].path, (ini.parent_path() / "geometry.hal").string());
  EXPECT_EQ(hal.sources[0].cite, "sub/m.hal:2 `source [GEO]FILE`");
  EXPECT_EQ(hal.sources[1].path, (ini.parent_path() / "late.hal").string());
}

TEST(HalFile, RefusesAMissingSourcedFileALoopAndAReferenceAfterAHalcmd) {
  auto refusal = [](const std::string& name, const std::vector<std::pair<std::string, std::string>>& files) {
    const fs::path ini = configuration(name, files);
    try {
      read_hal(LinuxcncIni::read(ini.string()));
    } catch (const LoadError& e) {
      return test::relative_message(std::string(e.what())).substr(ini.parent_path().string().size() + 1);
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal("source_missing", {{"m.ini", "[HAL]\nHALFILE = m.hal\n"}, {"m.hal", "# x\nsource gone.hal\n"}}),
            "m.hal:2: error: source gone.hal: cannot read " + (fs::temp_directory_path() / "").string() +
                test::scratch_prefix() +
                "source_missing/gone.hal: no such file (halcmd opens it from the configuration folder; LinuxCNC "
                "would not start)");
  EXPECT_EQ(refusal("source_loop", {{"m.ini", "[HAL]\nHALCMD = source a.hal\n"},
                                    {"a.hal", "source b.hal\n"},
                                    {"b.hal", "setp k.x 1\nsource a.hal\n"}}),
            "b.hal:2: error: source a.hal: a loop: a.hal is running this file already (halcmd would source them in "
            "turn until it runs out of open files)");
  EXPECT_EQ(refusal("source_itself", {{"m.ini", "[HAL]\nHALFILE = m.hal\n"}, {"m.hal", "source m.hal\n"}}),
            "m.hal:1: error: source m.hal: a loop: m.hal is running this file already (halcmd would source them in "
            "turn until it runs out of open files)");
  EXPECT_EQ(refusal("source_reference",
                    {{"m.ini", "[A]\nB = 1\n[HAL]\nHALCMD = source r.hal\n"}, {"r.hal", "setp k.x [A]B\n"}}),
            "r.hal:1: error: `[A]B` in a file sourced from a [HAL]HALCMD: LinuxCNC runs HALCMDs without the INI file "
            "(no halcmd -i), so halcmd cannot replace an INI reference there and stops at this line");
}

// scripts/linuxcnc's handle_includes only warns about an #INCLUDE without a file name.
TEST(LinuxcncIni, SkipsABareIncludeWithARemark) {
  const fs::path ini = configuration("bare_include", {{"m.ini", "[KINS]\n#INCLUDE   \nJOINTS = 3\n"}});
  const LinuxcncIni r = LinuxcncIni::read(ini.string());
  EXPECT_EQ(r.find("KINS", "JOINTS")->value, "3");
  EXPECT_TRUE(r.includes().empty());
  ASSERT_EQ(r.remarks().size(), 1u);
  EXPECT_EQ(r.remarks()[0],
            "m.ini:2 `#INCLUDE`: #INCLUDE without a file name, skipped (LinuxCNC warns \"found #INCLUDE with no "
            "filename\" and goes on)");
}

TEST(TextFile, SaysWhyAFileCannotBeReadAndEscapesWhatItQuotes) {
  const fs::path dir = test::scratch_folder("unreadable");
  auto message = [](const fs::path& path) {
    try {
      read_text_file(path.string(), "INI file");
    } catch (const LoadError& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  EXPECT_EQ(message(dir / "none.ini"), (dir / "none.ini").string() + ": error: cannot read the INI file: no such file");
  EXPECT_EQ(message(dir), dir.string() + ": error: cannot read the INI file: a directory, not a file");
  write_file(dir / "nul.ini", std::string("[A]\nB = 1\0"
                                          "2\n",
                                          12));
  EXPECT_EQ(message(dir / "nul.ini"), (dir / "nul.ini").string() +
                                          ":2:6: error: a NUL byte in `B = 1\\x002`: LinuxCNC reads the line only up "
                                          "to it (the INI file must be text: remove the byte)");
  EXPECT_EQ(printable(std::string("a\0b\tc\x1b[0m\r\x7f\xff caf\xc3\xa9", 18)),
            "a\\0b\tc\\x1b[0m\\r\\x7f\\xff caf\xc3\xa9");
  EXPECT_EQ(cite("/c/m.hal", 3, "setp \x01", "/c"), "m.hal:3 `setp \\x01`");
}

}  // namespace
}  // namespace vc::init
