// The volumetric survey of volcomp check: the poses it visits (the 3^n corners and middles of the
// travel, then reproducible random ones), its largest errors against the core's at those poses,
// and the correction converging over the travel of the shipped machines.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "vc/identify/travel_survey.hpp"
#include "vc/machine/correct.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::identify {
namespace {

int power_of_3(int n) { return n == 0 ? 1 : 3 * power_of_3(n - 1); }

TEST(TravelSurvey, VisitsTheCornersAndMiddlesThenTheSamples) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  EXPECT_EQ(survey_travel(model, 0).poses, power_of_3(model.joint_count()));
  EXPECT_EQ(survey_travel(model, 100).poses, power_of_3(model.joint_count()) + 100);
}

TEST(TravelSurvey, TheGridsLargestErrorIsTheCoresAtItsWorstPose) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const TravelSurvey s = survey_travel(model, 0);
  const int n = model.joint_count();
  double largest = 0, largest_direction = 0;
  machine::Joints q(n);
  for (int k = 0; k < power_of_3(n); ++k) {
    for (int j = 0, rest = k; j < n; ++j, rest /= 3)
      q[j] = model.axes[j].travel_min + 0.5 * (rest % 3) * (model.axes[j].travel_max - model.axes[j].travel_min);
    const machine::VolumetricError e = machine::volumetric_error(model, q, model.tool_length_mm);
    largest = std::max(largest, e.position_mm.norm());
    largest_direction = std::max(largest_direction, e.direction_rad.norm());
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_DOUBLE_EQ(s.max_position_mm, largest);
  EXPECT_DOUBLE_EQ(s.max_direction_rad, largest_direction);
  ASSERT_EQ(s.worst_position.size(), n);
  EXPECT_DOUBLE_EQ(machine::volumetric_error(model, s.worst_position, model.tool_length_mm).position_mm.norm(),
                   largest);
}

TEST(TravelSurvey, TheRandomPosesAreTheSameEveryRunAndInsideTheTravel) {
  const machine::Model model = machine::load_machine(test::machine_path("ac_trunnion"));
  const TravelSurvey a = survey_travel(model, 500), b = survey_travel(model, 500);
  EXPECT_EQ(a.max_position_mm, b.max_position_mm);
  EXPECT_EQ(a.worst_position, b.worst_position);
  EXPECT_EQ(a.max_iterations, b.max_iterations);
  for (int j = 0; j < model.joint_count(); ++j) {
    EXPECT_GE(a.worst_position[j], model.axes[j].travel_min);
    EXPECT_LE(a.worst_position[j], model.axes[j].travel_max);
  }
}

TEST(TravelSurvey, TheCorrectionConvergesOverTheShippedMachines) {
  for (const std::string& name : test::shipped_machines()) {
    const machine::Model model = machine::load_machine(test::machine_path(name));
    const TravelSurvey s = survey_travel(model, 200);
    EXPECT_EQ(s.failures, 0) << name;
    EXPECT_GE(s.max_iterations, 1) << name;
    EXPECT_LT(s.max_residual_mm, 1e-6) << name;
  }
}

}  // namespace
}  // namespace vc::identify
