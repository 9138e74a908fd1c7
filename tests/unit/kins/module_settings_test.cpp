// The module parameters' rules (machine, coordinates, world, sparm, units), without a HAL.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "module_settings.hpp"
#include "test_support.hpp"

namespace vc::kins {
namespace {

TEST(ModuleSettings, DefaultsFollowTheMachineFile) {
  const ModuleSettings s = settings_from_parameters(test::machine_path("mc300").c_str(), nullptr, nullptr);
  EXPECT_EQ(s.kinematics_types[0], machine::WorldConvention::Axes);
  EXPECT_EQ(s.kinematics_types[1], machine::WorldConvention::Tcp);
  EXPECT_EQ(s.kinematics_type_count(), 2);
  EXPECT_EQ(s.model.coordinates(), "xyzbc");
  const std::array<int, 5> fields{0, 1, 2, 4, 5};  // x y z b c in EmcPose order x y z a b c u v w
  for (int j = 0; j < 5; ++j) EXPECT_EQ(s.pose_field[j], fields[j]);
}

TEST(ModuleSettings, CoordinatesAndWorldAreCaseInsensitive) {
  const ModuleSettings s = settings_from_parameters(test::machine_path("ac_trunnion").c_str(), "XYZAC", "TCP");
  EXPECT_EQ(s.kinematics_types[0], machine::WorldConvention::Tcp);
  EXPECT_EQ(s.kinematics_types[1], machine::WorldConvention::Axes);
  EXPECT_EQ(s.pose_field[3], 3);
  EXPECT_EQ(s.pose_field[4], 5);
}

// LinuxCNC's trt modules: without sparm type 0 is TCP, with sparm=identityfirst the identity.
// volkins starts in the identity unless world=tcp; sparm=identityfirst is taken as world=axes.
TEST(ModuleSettings, SparmIdentityfirstMakesTypeZeroTheIdentity) {
  const std::string mc300 = test::machine_path("mc300");
  for (const char* world : {static_cast<const char*>(nullptr), "axes"}) {
    const ModuleSettings s = settings_from_parameters(mc300.c_str(), "xyzbc", world, "identityfirst");
    EXPECT_EQ(s.kinematics_types[0], machine::WorldConvention::Axes);
    EXPECT_EQ(s.kinematics_types[1], machine::WorldConvention::Tcp);
  }
  EXPECT_THROW(settings_from_parameters(mc300.c_str(), "xyzbc", "tcp", "identityfirst"), std::runtime_error);
  EXPECT_THROW(settings_from_parameters(mc300.c_str(), "xyzbc", nullptr, "tcpfirst"), std::runtime_error);
}

// units=: LinuxCNC's LINEAR_UNITS. Inch scales the linear axes' joints and world only (mm per
// unit 25.4), rotary ones stay in degrees; mm is the default; anything else is refused.
TEST(ModuleSettings, UnitsInchScalesTheLinearAxesOnly) {
  const std::string mc300 = test::machine_path("mc300");
  const ModuleSettings mm = settings_from_parameters(mc300.c_str(), nullptr, nullptr);
  EXPECT_EQ(mm.mm_per_unit, 1.0);
  const ModuleSettings inch = settings_from_parameters(mc300.c_str(), nullptr, nullptr, nullptr, "INCH");
  EXPECT_EQ(inch.mm_per_unit, 25.4);
  const std::array<double, 5> scale{25.4, 25.4, 25.4, 1.0, 1.0};  // x y z b c
  for (int j = 0; j < 5; ++j) EXPECT_EQ(inch.linear_scale[j], scale[j]) << j;
  EXPECT_EQ(settings_from_parameters(mc300.c_str(), nullptr, nullptr, nullptr, "mm").linear_scale[0], 1.0);
  EXPECT_THROW(settings_from_parameters(mc300.c_str(), nullptr, nullptr, nullptr, "cm"), std::runtime_error);
}

// LinuxCNC's coordinates=: a letter per joint, in any order, a letter twice for two joints
// driven alike (a gantry); the forward reads the first joint of each letter.
TEST(ModuleSettings, CoordinatesMapLinuxcncJointsToTheMachinesAxes) {
  const ModuleSettings gantry = settings_from_parameters(test::machine_path("mill3").c_str(), "XYYZ", nullptr);
  EXPECT_EQ(gantry.joint_count, 4);
  const std::array<int, 4> axis_of{0, 1, 1, 2};
  for (int k = 0; k < 4; ++k) EXPECT_EQ(gantry.model_joint[k], axis_of[k]) << k;
  const std::array<int, 3> principal{0, 1, 3};
  for (int j = 0; j < 3; ++j) EXPECT_EQ(gantry.principal_joint[j], principal[j]) << j;

  const ModuleSettings swapped = settings_from_parameters(test::machine_path("mc300").c_str(), "xyzcb", nullptr);
  EXPECT_EQ(swapped.model_joint[3], 4);  // joint 3 drives C, the machine file's fifth axis
  EXPECT_EQ(swapped.principal_joint[3], 4);
}

// A bridge mill's head as LinuxCNC's 5axiskins has it (X Y Z carry C carrying B; W moves the
// tool along its axis): the W joint drives no axis of the model, volkins passes it through.
TEST(ModuleSettings, TheToolAxisCoordinatesJointIsPassedThrough) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "vc_module_settings_head.toml";
  std::ofstream(file) << R"([machine]
name = "bridge mill head"
[spindle]
gauge_point_mm = [0, 0, -250]
tool_axis_coordinate = "W"
[[tool_chain]]
axis = "X"
type = "linear"
direction = [1, 0, 0]
pole_mm = [0, 0, 0]
travel_mm = [-500, 500]
[[tool_chain]]
axis = "Y"
type = "linear"
direction = [0, 1, 0]
pole_mm = [0, 0, 0]
travel_mm = [-500, 500]
[[tool_chain]]
axis = "Z"
type = "linear"
direction = [0, 0, 1]
pole_mm = [0, 0, 0]
travel_mm = [-500, 100]
[[tool_chain]]
axis = "C"
type = "rotary"
direction = [0, 0, 1]
pole_mm = [0, 0, 250]
travel_deg = [-360, 360]
[[tool_chain]]
axis = "B"
type = "rotary"
direction = [0, -1, 0]
pole_mm = [0, 0, 0]
travel_deg = [-120, 120]
)";
  const ModuleSettings s = settings_from_parameters(file.c_str(), "xyzbcwy", "tcp");
  EXPECT_EQ(s.joint_count, 7);
  const std::array<int, 7> axis_of{0, 1, 2, 3, 4, -1, 1};
  for (int k = 0; k < 7; ++k) EXPECT_EQ(s.model_joint[k], axis_of[k]) << k;
  EXPECT_EQ(s.tool_axis_joint, 5);
  EXPECT_EQ(s.tool_axis_field, 8);                                                        // EmcPose's w
  EXPECT_EQ(settings_from_parameters(file.c_str(), "xyzbc", "tcp").tool_axis_joint, -1);  // W unused: w = 0
  EXPECT_THROW(settings_from_parameters(file.c_str(), "xyzbcwu", "tcp"),
               std::runtime_error);  // U is not its coordinate
  EXPECT_THROW(settings_from_parameters(test::machine_path("mc300").c_str(), "xyzbcw", nullptr), std::runtime_error);
  std::filesystem::remove(file);
}

TEST(ModuleSettings, RelativePathsAreMadeAbsolute) {
  const auto here = std::filesystem::current_path();
  std::filesystem::current_path(test::source_path("machines/data"));
  const ModuleSettings s = settings_from_parameters("mill3.toml", "", "");
  std::filesystem::current_path(here);
  EXPECT_EQ(s.model.path, test::machine_path("mill3"));
}

TEST(ModuleSettings, RefusesWhatItCannotHonour) {
  const std::string mc300 = test::machine_path("mc300");
  EXPECT_THROW(settings_from_parameters(nullptr, nullptr, nullptr), std::runtime_error);
  EXPECT_THROW(settings_from_parameters("", nullptr, nullptr), std::runtime_error);
  EXPECT_THROW(settings_from_parameters(mc300.c_str(), "xyzb", nullptr), std::runtime_error);    // no C joint
  EXPECT_THROW(settings_from_parameters(mc300.c_str(), "xyzbca", nullptr), std::runtime_error);  // no A axis
  EXPECT_THROW(settings_from_parameters(mc300.c_str(), "xyzbcxxxxxxxxxxxx", nullptr), std::runtime_error);  // 17 joints
  EXPECT_THROW(settings_from_parameters(mc300.c_str(), nullptr, "joints"), std::runtime_error);
  EXPECT_THROW(settings_from_parameters("/nonexistent.toml", nullptr, nullptr), LoadError);
}

}  // namespace
}  // namespace vc::kins
