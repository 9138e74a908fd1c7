// A trace's joint columns read through the configuration that recorded it (vc::trace::TraceLayout,
// `volcomp trace --ini`): LinuxCNC's joints j0..jN-1 follow coordinates=, so on a gantry
// (coordinates=xyyz: joints 1 and 2 both Y) the machine's Z is j3, read from there, and j2 is
// checked equal to j1; the linear columns of an inch configuration are converted to mm where
// they are read. A trace written here, as headless_driver.py writes one, of mill3 (X Y Z) as
// kins/configs/mill3/mill3_gantry.ini drives it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "test_support.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/trace/session_trace.hpp"

namespace vc::trace {
namespace {

namespace fs = std::filesystem;

const char* const kHeader = "x,y,z,j0,j1,j2,j3,gain,tool_offset,controller_time,tcp,correction_length\n";

// Five samples of a gantry's trace: x, y, z and the joints (j2 = j1 unless `twin` says otherwise).
fs::path gantry_trace(const std::string& name, double twin_offset = 0.0, int twin_row = 3) {
  const fs::path path = fs::temp_directory_path() / ("vc_trace_layout_" + name + ".csv");
  std::ofstream out(path);
  out << kHeader;
  for (int k = 0; k < 5; ++k) {
    const double x = 10 + k, y = 20 + 2 * k, z = -30 - k;
    out << x << ',' << y << ',' << z << ',' << x << ',' << y << ',' << y + (k == twin_row ? twin_offset : 0.0) << ','
        << z << ",1,0," << 1000 * k << ",0,0\n";
  }
  return path;
}

TEST(TraceLayout, AGantrysZIsItsFourthJointAndItsSecondYIsCheckedEqualToTheFirst) {
  const machine::Model model = machine::load_machine(test::source_path("machines/data/mill3.toml"));
  const TraceLayout layout = trace_layout(model, "xyyz", 1.0);
  ASSERT_EQ(layout.joints.size(), 3u);
  EXPECT_EQ(layout.joints[1], (std::vector<int>{1, 2}));
  EXPECT_EQ(layout.joints[2], (std::vector<int>{3}));

  const SessionTrace t = read_session_trace(gantry_trace("gantry").string(), model, layout);
  ASSERT_EQ(t.size(), 5u);
  for (std::size_t k = 0; k < t.size(); ++k) {
    EXPECT_EQ(t.joints[k][2], t.world[k][2]) << "Z read from j3";
    EXPECT_EQ(t.joints[k][1], t.world[k][1]);
  }
  // Without the layout (the machine file's order: j0 j1 j2), Z is the second Y motor: the defect
  // the layout removes.
  const SessionTrace by_index = read_session_trace(gantry_trace("gantry").string(), model);
  EXPECT_EQ(by_index.joints[4][2], by_index.world[4][1]);

  // A second Y motor off the first: not this configuration's trace, refused at its cell.
  try {
    read_session_trace(gantry_trace("twins", 0.01).string(), model, layout);
    FAIL() << "two Y joints 0.01 apart were taken";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where().line, 5);
    EXPECT_TRUE(
        std::regex_search(e.message(), std::regex("^j2 = 26.01 differs from j1 = 26, the principal joint of Y")))
        << e.what();
  }
  EXPECT_THROW(trace_layout(model, "xyy", 1.0), std::invalid_argument);  // no joint drives Z
}

TEST(TraceLayout, AnInchTracesLinearColumnsAreConvertedToMm) {
  const machine::Model model = machine::load_machine(test::source_path("machines/data/mill3.toml"));
  const fs::path path = fs::temp_directory_path() / "vc_trace_layout_inch.csv";
  std::ofstream(path) << "x,y,z,j0,j1,j2,gain,tool_offset,controller_time,tcp,correction_length\n"
                      << "1,2,-3,1,2,-3,1,0.5,0,0,0.5\n";
  const SessionTrace t = read_session_trace(path.string(), model, trace_layout(model, "xyz", 25.4));
  ASSERT_EQ(t.size(), 1u);
  EXPECT_DOUBLE_EQ(t.world[0][0], 25.4);
  EXPECT_DOUBLE_EQ(t.world[0][2], -76.2);
  EXPECT_DOUBLE_EQ(t.joints[0][1], 50.8);
  EXPECT_DOUBLE_EQ(t.tool_offset_mm[0], 12.7);
  EXPECT_DOUBLE_EQ(t.correction_length_mm[0], 12.7);  // volkins.correction-length: in inches, as its other pins
}

// The command takes the layout, the world and the units from the INI: a conflicting --world is
// refused with the KINEMATICS line; --replay-output still needs --comp-files.
TEST(TraceLayout, VolcompTraceReadsTheConfiguration) {
  const std::string machine = test::source_path("machines/data/mill3.toml");
  const std::string gantry_ini = test::source_path("kins/configs/mill3/mill3_gantry.ini");
  const std::string trace = gantry_trace("cli").string();
  const test::CommandResult ok = test::run_volcomp("trace " + machine + " " + trace + " --ini " + gantry_ini);
  EXPECT_EQ(ok.exit_code, 0) << ok.out;
  EXPECT_NE(ok.out.find("(2 samples checked"), std::string::npos) << ok.out;
  const test::CommandResult tcp =
      test::run_volcomp("trace " + machine + " " + trace + " --ini " + gantry_ini + " --world tcp");
  EXPECT_NE(tcp.exit_code, 0) << tcp.out;
  EXPECT_TRUE(std::regex_search(tcp.out, std::regex("mill3_gantry.ini:[0-9]+: error: --world tcp contradicts the "
                                                    "configuration: volkins is loaded with world=axes")))
      << tcp.out;
  const test::CommandResult twins =
      test::run_volcomp("trace " + machine + " " + gantry_trace("cli_twins", 1.0).string() + " --ini " + gantry_ini);
  EXPECT_NE(twins.exit_code, 0) << twins.out;
  EXPECT_NE(twins.out.find("differs from j1"), std::string::npos) << twins.out;
  const test::CommandResult replay = test::run_volcomp("trace " + machine + " " + trace + " --replay-output x.csv");
  EXPECT_NE(replay.exit_code, 0) << replay.out;
  EXPECT_NE(replay.out.find("--replay-output goes with --comp-files"), std::string::npos) << replay.out;
}

}  // namespace
}  // namespace vc::trace
