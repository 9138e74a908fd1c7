// Clamped rotary axes (vc/machine/held_rotary.hpp): a held joint keeps its offset exactly (also
// against the enable ramp's gain), the real tool tip is where the ideal machine has it (the
// machines' own forward, not the solver), the direction error reported is the one left, the
// inverse undoes the held correction, every joint free again is correct() itself, and releasing
// moves the joints continuously. On every shipped and test machine with rotary axes, both worlds
// through the kinematics' Applied::held.
#include "vc/machine/held_rotary.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/machine/travel_samples.hpp"

namespace vc::machine {
namespace {

class HeldRotaryTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    const std::string& name = GetParam();
    model_ = load_machine(name == "bc_head" || name == "xyza_table"
                              ? test::source_path("tests/unit/machines/data/" + name + ".toml")
                              : test::machine_path(name));
    for (int j = 0; j < model_.joint_count(); ++j)
      if (model_.axes[static_cast<std::size_t>(j)].type == AxisType::Rotary) rotary_.push_back(j);
  }
  // The first rotary joint held at its free correction of another pose (as after X, Y, Z moved
  // while it was clamped), the others free.
  HeldRotary held_first(const Joints& elsewhere, double L) const {
    HeldRotary h;
    const Correction c = correct(model_, elsewhere, L);
    const int b = rotary_.front();
    h.offset_deg[static_cast<std::size_t>(b)] = c.joints[b] - elsewhere[b];
    h.release[static_cast<std::size_t>(b)] = 0.0;
    return h;
  }
  Model model_;
  std::vector<int> rotary_;
};

TEST_P(HeldRotaryTest, AHeldJointKeepsItsOffsetAndTheTipIsExact) {
  TravelSamples samples(model_);
  const double L = model_.tool_length_mm;
  double tip = 0.0, reported = 0.0, roundtrip = 0.0, left = 0.0;
  for (int i = 0; i < 100; ++i) {
    const Joints q = samples.next(), elsewhere = samples.next();
    const HeldRotary held = held_first(elsewhere, L);
    ASSERT_TRUE(held.any(model_));
    for (double gain : {1.0, 0.4}) {
      const Correction c = correct_held(model_, model_.reference_conditions(), q, L, gain, held, q);
      ASSERT_EQ(c.status, Status::Ok) << i;
      const int b = rotary_.front();
      EXPECT_EQ(c.joints[b], q[b] + held.offset_deg[static_cast<std::size_t>(b)]) << "held, whatever the gain";
      if (gain != 1.0) continue;
      const ToolPose real = tool_pose(model_, Machine::Real, c.joints, L);
      const ToolPose ideal = tool_pose(model_, Machine::Ideal, q, L);
      tip = std::max(tip, (real.tip_mm - ideal.tip_mm).norm());
      const double direction = ideal.direction.cross(real.direction).norm();
      reported = std::max(reported, std::abs(c.residual_rad - direction));
      left = std::max(left, direction);
      const Uncorrection u = uncorrect_held(model_, model_.reference_conditions(), c.joints, L, 1.0, held, c.joints);
      ASSERT_EQ(u.status, Status::Ok) << i;
      roundtrip = std::max(roundtrip, (u.nominal - q).cwiseAbs().maxCoeff());
    }
  }
  EXPECT_LT(tip, 1e-9);
  EXPECT_LT(reported, 1e-12);
  EXPECT_LT(roundtrip, 1e-9);
  EXPECT_GT(left, 1e-7) << "a held joint leaves a direction error";
}

TEST_P(HeldRotaryTest, EveryJointFreeIsTheCorrectionItself) {
  TravelSamples samples(model_);
  const HeldRotary free;
  EXPECT_FALSE(free.any(model_));
  for (int i = 0; i < 30; ++i) {
    const Joints q = samples.next();
    const Correction c = correct(model_, q, 120.0);
    const Correction h = correct_held(model_, model_.reference_conditions(), q, 120.0, 1.0, free, q);
    EXPECT_LT((c.joints - h.joints).cwiseAbs().maxCoeff(), 1e-10) << i;
  }
}

// Released over a ramp: the joints move continuously from the held correction to the free one.
TEST_P(HeldRotaryTest, ReleasingMovesTheJointsContinuously) {
  TravelSamples samples(model_);
  const double L = model_.tool_length_mm;
  const Joints q = samples.next();
  HeldRotary held = held_first(samples.next(), L);
  const int b = rotary_.front();
  Joints last = correct_held(model_, model_.reference_conditions(), q, L, 1.0, held, q).joints;
  const Joints free = correct(model_, q, L).joints;
  const double span = (free - last).cwiseAbs().maxCoeff();
  ASSERT_GT(span, 1e-6);
  double largest_step = 0.0;
  for (int k = 1; k <= 100; ++k) {
    held.release[static_cast<std::size_t>(b)] = k / 100.0;
    const Joints now = correct_held(model_, model_.reference_conditions(), q, L, 1.0, held, last).joints;
    largest_step = std::max(largest_step, (now - last).cwiseAbs().maxCoeff());
    last = now;
  }
  EXPECT_LT((last - free).cwiseAbs().maxCoeff(), 1e-10) << "released: the free correction";
  EXPECT_LT(largest_step, 0.02 * span + 1e-12) << "a step of 1 % of the release moves the joints by ~1 % of the span";
}

// Through the kinematics, both worlds: the forward undoes the held inverse.
TEST_P(HeldRotaryTest, TheKinematicsTakeTheHeldJoints) {
  TravelSamples samples(model_);
  const double L = model_.tool_length_mm;
  for (WorldConvention w : {WorldConvention::Axes, WorldConvention::Tcp}) {
    double worst = 0.0;
    for (int i = 0; i < 30; ++i) {
      const Joints q = samples.next();
      const HeldRotary held = held_first(samples.next(), L);
      Applied applied;
      applied.held = &held;
      const Joints world = nominal_forward(model_, w, q, L);
      Joints joints, back;
      ASSERT_EQ(joints_from_world(model_, w, world, L, applied, joints), Status::Ok);
      const int b = rotary_.front();
      EXPECT_NEAR(joints[b], q[b] + held.offset_deg[static_cast<std::size_t>(b)], 1e-9);
      ASSERT_EQ(world_from_joints(model_, w, joints, L, applied, back), Status::Ok);
      worst = std::max(worst, (back - world).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, 1e-9);
  }
}

INSTANTIATE_TEST_SUITE_P(Rotary, HeldRotaryTest, ::testing::Values("mc300", "ac_trunnion", "bc_head", "xyza_table"),
                         [](const auto& p) { return std::string(p.param); });

}  // namespace
}  // namespace vc::machine
