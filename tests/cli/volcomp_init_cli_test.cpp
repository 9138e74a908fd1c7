// `volcomp init`'s options against its inputs: no output may be a file init reads (the INI, an
// #INCLUDEd file, a HAL file, a sourced file, the tool table; a symlink to one counts), -o and
// --patch may not be the same file, -o - is refused; each exits 2 naming the option, the file
// and which input it is, and changes nothing (bytes and mtimes). And the reasons a missing INI
// or a directory cannot be read, and the summary's remarks (a bare #INCLUDE, a copied include).
// Locking indexers: volkins' pins netted to motion's signals.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <string>

#include "test_support.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;

// The golden xyzbc mill with an #INCLUDE, a sourced HAL file and a tool table, in a folder of its own.
fs::path configuration(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("vc_init_cli_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::copy(test::source_path("tests/golden/bad_inis/good"), dir, fs::copy_options::recursive);
  std::string ini = test::file_text(dir / "xyzbc.ini");
  ini.replace(ini.find("[EMC]\n"), 6, "#INCLUDE emc.inc\n");
  ini += "\n[EMCIO]\nTOOL_TABLE = tools.tbl\n";
  std::ofstream(dir / "xyzbc.ini") << ini;
  std::ofstream(dir / "emc.inc") << "[EMC]\n";
  std::ofstream(dir / "xyzbc.hal", std::ios::app) << "source more.hal\n";
  std::ofstream(dir / "more.hal") << "# nothing more\n";
  std::ofstream(dir / "tools.tbl") << "T1 P1 Z50 ;a tool\n";
  return dir;
}

struct Snapshot {
  std::map<std::string, std::pair<std::string, fs::file_time_type>> files;
  bool operator==(const Snapshot& o) const { return files == o.files; }
};
Snapshot snapshot(const fs::path& dir) {
  Snapshot s;
  for (const auto& e : fs::directory_iterator(dir))
    s.files[e.path().filename().string()] = {test::file_text(e.path()), fs::last_write_time(e.path())};
  return s;
}

TEST(VolcompInit, RefusesEveryInputAsAnOutputAndChangesNothing) {
  const fs::path dir = configuration("inputs");
  fs::create_symlink(dir / "xyzbc.ini", dir / "link.toml");
  const std::string ini = (dir / "xyzbc.ini").string();
  const std::string at = " " + (dir / "").string();
  const struct {
    std::string options, message;
  } cases[] = {
      {"-o " + ini, "error: -o " + ini + " is " + ini + ", the INI file, which init reads"},
      {"-o " + (dir / "link.toml").string(),
       "error: -o " + (dir / "link.toml").string() + " is " + ini + ", the INI file, which init reads"},
      {"-o m.toml --patch " + ini, "error: --patch " + ini + " is " + ini + ", the INI file"},
      {"-o " + (dir / "emc.inc").string(),
       "is " + (dir / "emc.inc").string() + ", a file the INI includes (xyzbc.ini:3)"},
      {"-o " + (dir / "xyzbc.hal").string(),
       "is " + (dir / "xyzbc.hal").string() + ", a HAL file (xyzbc.ini:16 `HALFILE = xyzbc.hal`)"},
      {"-o m.toml --patch " + (dir / "." / "more.hal").string(),
       "is " + (dir / "more.hal").string() + ", a HAL file run by source (xyzbc.hal:9 `source more.hal`)"},
      {"-o " + (dir / "tools.tbl").string(), "the tool table (xyzbc.ini:"},
      {"-o " + (dir / "x").string() + " --patch " + (dir / "sub/../x").string(), "are the same file: give them two"},
      {"-o -", "error: -o -: the machine file needs a name"},
  };
  const Snapshot before = snapshot(dir);
  for (const auto& c : cases) {
    SCOPED_TRACE(c.options);
    const auto r = test::run_volcomp("init " + ini + " " + c.options);
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_NE(r.out.find(c.message), std::string::npos) << r.out;
    EXPECT_TRUE(snapshot(dir) == before) << "a refusal changed the folder";
    EXPECT_FALSE(fs::exists("m.toml"));
  }
  // The same configuration with outputs of their own: accepted.
  const auto ok =
      test::run_volcomp("init " + ini + " -o " + (dir / "m.toml").string() + " --patch " + (dir / "p.diff").string());
  EXPECT_EQ(ok.exit_code, 0) << ok.out;
  fs::remove_all(dir);
}

TEST(VolcompInit, SaysWhyTheIniCannotBeRead) {
  const fs::path dir = configuration("unreadable");
  const auto missing = test::run_volcomp("init " + (dir / "none.ini").string() + " -o " + (dir / "m.toml").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(test::trimmed(missing.out),
            (dir / "none.ini").string() + ": error: cannot read the INI file: no such file");
  const auto folder = test::run_volcomp("init " + dir.string() + " -o " + (dir / "m.toml").string());
  EXPECT_EQ(folder.exit_code, 2);
  EXPECT_EQ(test::trimmed(folder.out), dir.string() + ": error: cannot read the INI file: a directory, not a file");
  fs::remove_all(dir);
}

// A bare #INCLUDE is skipped with a remark, as LinuxCNC warns and goes on; the #INCLUDEd file
// the patch changes is copied, and the summary names the option that edits it in place.
TEST(VolcompInit, RemarksOnABareIncludeAndOnTheCopyOfAnInclude) {
  const fs::path dir = configuration("remarks");
  std::string ini = test::file_text(dir / "xyzbc.ini");
  ini.replace(ini.find("[KINS]\nKINEMATICS = xyzbc-trt-kins\n"), 35, "#INCLUDE\n#INCLUDE kins.inc\n");
  std::ofstream(dir / "xyzbc.ini") << ini;
  std::ofstream(dir / "kins.inc") << "[KINS]\nKINEMATICS = xyzbc-trt-kins\n";
  const auto r = test::run_volcomp("init " + (dir / "xyzbc.ini").string() + " -o " + (dir / "m.toml").string() +
                                   " --patch " + (dir / "p.diff").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("note: xyzbc.ini:6 `#INCLUDE`: #INCLUDE without a file name, skipped"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("note: kins.inc is left as it is: an #INCLUDEd file, which other configurations may include "
                       "too; its edits go to the new kins.volkins.inc, which xyzbc.ini:7 now names (volcomp init "
                       "--edit-shared edits it in place instead"),
            std::string::npos)
      << r.out;
  const auto patch = test::run_command("patch -s -p1 -d " + dir.string() + " < " + (dir / "p.diff").string() + " 2>&1");
  EXPECT_EQ(patch.exit_code, 0) << patch.out;
  EXPECT_EQ(test::file_text(dir / "kins.inc"), "[KINS]\nKINEMATICS = xyzbc-trt-kins\n");
  EXPECT_NE(test::file_text(dir / "kins.volkins.inc").find("KINEMATICS = volkins machine=m.toml"), std::string::npos);

  const auto shared = test::run_volcomp("init " + (dir / "xyzbc.ini").string() + " -o " + (dir / "m2.toml").string() +
                                        " --edit-shared --patch " + (dir / "p2.diff").string());
  // The patched INI now loads volkins from the copy (line 3, after its header): init refuses it there.
  EXPECT_EQ(shared.exit_code, 2) << shared.out;
  EXPECT_NE(shared.out.find("kins.volkins.inc:3: error:"), std::string::npos) << shared.out;
  fs::remove_all(dir);
}

// B a locking indexer whose clamp the HAL file simulates (its pins on signals, as LinuxCNC's
// xyzb_locking_indexer sample has them), C one whose pins are on no signal yet: volkins' pins
// join B's signals, C's get signals of their own; X, Y, Z and a not-indexer stay as they are.
TEST(VolcompInit, NetsVolkinsToEveryLockingIndexersUnlockAndIsUnlocked) {
  const fs::path dir = configuration("indexers");
  std::string ini = test::file_text(dir / "xyzbc.ini");
  ini.replace(ini.find("[JOINT_3]\n"), 10, "[JOINT_3]\nLOCKING_INDEXER = 1\n");
  ini.replace(ini.find("[JOINT_4]\n"), 10, "[JOINT_4]\nLOCKING_INDEXER = yes\n");
  std::ofstream(dir / "xyzbc.ini") << ini;
  std::ofstream(dir / "xyzbc.hal", std::ios::app) << "net B-unlock joint.3.unlock\nnet B-is-unlocked joint.3.is-unlocked\n";
  const auto r = test::run_volcomp("init " + (dir / "xyzbc.ini").string() + " -o " + (dir / "m.toml").string() +
                                   " --patch " + (dir / "p.diff").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::string diff = test::file_text(dir / "p.diff");
  for (const char* line : {"+HALCMD = net B-unlock volkins.joint.3.unlock\n",
                           "+HALCMD = net B-is-unlocked volkins.joint.3.is-unlocked\n",
                           "+HALCMD = net :volkins-joint-4-unlock joint.4.unlock volkins.joint.4.unlock\n",
                           "+HALCMD = net :volkins-joint-4-is-unlocked joint.4.is-unlocked volkins.joint.4.is-unlocked\n"})
    EXPECT_NE(diff.find(line), std::string::npos) << line << diff;
  EXPECT_EQ(diff.find("joint.2."), std::string::npos) << diff;
  EXPECT_NE(r.out.find("note: joint 3 is a locking indexer (xyzbc.ini:"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vc
