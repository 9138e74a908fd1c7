// Which machine files may replace the running one (volkins.reload): each kind of change of the
// nominal kinematics, the axes or the temperature inputs is refused with what differs; changed
// error tables and location errors are accepted.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <unistd.h>

#include "test_support.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/machine/reload_compatibility.hpp"

namespace vc::machine {
namespace {

namespace fs = std::filesystem;

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `name` (a shipped machine) with `from` replaced by `to` (a regex each), its table paths made
// absolute, loaded from a file of its own in the temporary folder.
Model edited(const std::string& name, const std::string& from, const std::string& to) {
  const std::string original = text_of(test::machine_path(name));
  const std::string changed = std::regex_replace(original, std::regex(from), to);
  EXPECT_NE(changed, original) << from;
  const fs::path path = fs::temp_directory_path() / ("reload_compatibility_" + std::to_string(::getpid()) + ".toml");
  std::ofstream(path) << std::regex_replace(changed, std::regex("\\.\\./\\.\\./tables/data/"),
                                            test::source_path("tables/data/"));
  Model m = load_machine(path.string());
  fs::remove(path);
  return m;
}

TEST(ReloadCompatibility, SameFileAndChangedErrorsAreAccepted) {
  const Model running = load_machine(test::machine_path("mill3"));
  EXPECT_EQ(reload_incompatibility(running, load_machine(test::machine_path("mill3"))), "");
  EXPECT_EQ(reload_incompatibility(running, edited("mill3", "EC0X_arcsec = 8\\.0", "EC0X_arcsec = 12.0")), "");
  EXPECT_EQ(reload_incompatibility(running, edited("mill3", "\\[\\[tool_chain\\.tables\\]\\]\nfile = \"\\.\\./\\.\\./tables/data/mill3/z_by_y\\.csv\"[^\n]*\n", "")), "")
      << "a table less";
}

TEST(ReloadCompatibility, EachChangeOfTheNominalKinematicsIsRefusedWithWhatDiffers) {
  const Model running = load_machine(test::machine_path("mill3"));
  struct Case {
    std::string from, to, message;
  };
  const std::vector<Case> cases{
      {"pole_mm = \\[0, 0, 500\\]", "pole_mm = [0, 0, 500.001]", "axis Z's pole is (0, 0, 500.00"},
      {"gauge_point_mm = \\[0, 0, 0\\]", "gauge_point_mm = [0, 0, 1]", "the spindle's gauge point is (0, 0, 1) mm"},
      {"origin_mm = \\[0, 0, 60\\]", "origin_mm = [0, 0, 61]", "its fixture differs"},
      {"tool_length_mm = 100\\.0 ", "tool_length_mm = 100.0\ntool_length_reference_mm = 90 ", "tool_length_reference_mm is 90, in the running file 0"},
  };
  for (const Case& c : cases) {
    const std::string why = reload_incompatibility(running, edited("mill3", c.from, c.to));
    EXPECT_NE(why.find(c.message), std::string::npos) << c.to << ": " << why;
    EXPECT_NE(why.find("nominal kinematics must not change"), std::string::npos) << why;
  }
  // Other axes, another type, temperature inputs: other machines' files.
  EXPECT_EQ(reload_incompatibility(running, load_machine(test::machine_path("mc300"))),
            "its axes are \"xyzbc\", the running file's \"xyz\"");
  const Model mc300 = load_machine(test::machine_path("mc300"));
  EXPECT_NE(reload_incompatibility(mc300, load_machine(test::machine_path("mc300_thermal"))).find("temperature inputs are ["),
            std::string::npos);
  Model tilted = running;  // a direction 1e-9 rad off: beyond the tolerance
  tilted.axes[2].direction = Eigen::Vector3d(0.0, 1e-9, 1.0).normalized();
  EXPECT_NE(reload_incompatibility(running, tilted).find("axis Z's direction is (0, 1.0000000000000001e-09, 1)"),
            std::string::npos)
      << reload_incompatibility(running, tilted);
  Model within = running;  // rounding: accepted
  within.axes[2].pole_mm.z() += 1e-13;
  EXPECT_EQ(reload_incompatibility(running, within), "");
  Model rotary = running;  // (the loader's letters: a type change made on the model itself)
  rotary.axes[2].type = AxisType::Rotary;
  EXPECT_EQ(reload_incompatibility(running, rotary), "axis Z is rotary, in the running file linear");
  Model other_chain = running;
  other_chain.axes[0].chain = Chain::Tool;
  EXPECT_EQ(reload_incompatibility(running, other_chain), "axis X is in the tool chain, in the running file in the workpiece chain");
  Model renamed = mc300;
  renamed.temperatures.push_back({"spindle", 20.0, 0.0, 50.0});
  EXPECT_EQ(reload_incompatibility(mc300, renamed),
            "its temperature inputs are [spindle], the running file's [] (their HAL pins volkins.temperature.<name> exist "
            "already)");
}

}  // namespace
}  // namespace vc::machine
