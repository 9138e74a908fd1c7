// Golden bad LinuxCNC configurations for `volcomp init`: every tests/golden/bad_inis/*.ini (with
// the HAL files of its name) must be refused by the command line with exit code 2, the exact
// message of its .expect twin (trimmed; the source tree's path removed so that paths read
// relative to the repository root), and neither output file written. The good base they are
// made from (bad_inis/good/) is accepted: the machine file and the patch written, stdout a
// clean patch.
//
// VC_UPDATE_GOLDEN=1 writes the .expect files from the current messages: read every one of
// them critically before committing (the right file and line? does it say what is wrong and
// how to fix it?).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "test_support.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;

using test::relative_message;
using test::trimmed;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("vc_bad_inis_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(BadInis, EveryBadConfigurationIsRefusedWithItsMessage) {
  const fs::path dir = test::source_path("tests/golden/bad_inis");
  const std::vector<fs::path> inis = test::files_with_extension(dir, ".ini");
  ASSERT_GE(inis.size(), 7u);
  const bool update = std::getenv("VC_UPDATE_GOLDEN") != nullptr;
  const fs::path out = scratch("refused");
  for (const fs::path& ini : inis) {
    SCOPED_TRACE(ini.filename().string());
    const auto r = test::run_volcomp("init " + ini.string() + " -o " + (out / "machine.toml").string() + " --patch " +
                                     (out / "config.diff").string());
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_FALSE(fs::exists(out / "machine.toml")) << "a refusal wrote the machine file";
    EXPECT_FALSE(fs::exists(out / "config.diff")) << "a refusal wrote the patch";
    const std::string message = trimmed(relative_message(r.out));
    EXPECT_EQ(message.rfind("tests/golden/bad_inis/", 0), 0u) << "file:line first: " << message;
    EXPECT_NE(message.find(": error: "), std::string::npos) << message;
    fs::path expect = ini;
    expect.replace_extension(".expect");
    if (update) {
      std::ofstream(expect) << message << '\n';
      continue;
    }
    ASSERT_TRUE(fs::exists(expect)) << "no " << expect << " (run with VC_UPDATE_GOLDEN=1 and read it)";
    EXPECT_EQ(message, trimmed(test::file_text(expect)));
  }
  fs::remove_all(out);
}

TEST(BadInis, TheGoodBaseIsAcceptedAndWritesBothOutputs) {
  const fs::path dir = scratch("good") / "config";
  fs::copy(test::source_path("tests/golden/bad_inis/good"), dir, fs::copy_options::recursive);
  const fs::path summary = dir.parent_path() / "summary.txt";

  // --patch FILE: both outputs in files, nothing on stdout.
  const auto to_file =
      test::run_volcomp_stdout("init " + (dir / "xyzbc.ini").string() + " -o " + (dir / "xyzbc.toml").string() +
                                   " --patch " + (dir.parent_path() / "config.diff").string(),
                               summary);
  ASSERT_EQ(to_file.exit_code, 0) << test::file_text(summary);
  EXPECT_EQ(to_file.out, "");
  EXPECT_NE(test::file_text(summary).find("volcomp init: golden xyzbc"), std::string::npos) << test::file_text(summary);
  const machine::Model model = machine::load_machine((dir / "xyzbc.toml").string());
  EXPECT_EQ(model.coordinates(), "xyzbc");
  EXPECT_EQ(model.axes[3].pole_mm, Eigen::Vector3d(-20, 0, 35));  // [xr + dx, yr, zr + dz]
  EXPECT_EQ(model.fixture.translation(), Eigen::Vector3d(0, 0, -50));
  const std::string diff = test::file_text(dir.parent_path() / "config.diff");
  EXPECT_NE(diff.find("+KINEMATICS = volkins machine=xyzbc.toml coordinates=xyzbc world=tcp\n"), std::string::npos)
      << diff;
  const auto check = test::run_volcomp("check " + (dir / "xyzbc.toml").string() + " --samples 200");
  EXPECT_EQ(check.exit_code, 0) << check.out;

  // No --patch: stdout is the patch alone (the summary on stderr).
  const auto to_stdout = test::run_volcomp_stdout(
      "init " + (dir / "xyzbc.ini").string() + " -o " + (dir / "again.toml").string(), summary);
  ASSERT_EQ(to_stdout.exit_code, 0) << test::file_text(summary);
  EXPECT_EQ(to_stdout.out, std::string(diff).replace(diff.find("xyzbc.toml"), 10, "again.toml"));
  EXPECT_EQ(test::file_text(dir / "again.toml").substr(test::file_text(dir / "again.toml").find("[machine]")),
            test::file_text(dir / "xyzbc.toml").substr(test::file_text(dir / "xyzbc.toml").find("[machine]")));
  fs::remove_all(dir.parent_path());
}

}  // namespace
}  // namespace vc
