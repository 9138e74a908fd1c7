// Correction and kinematics on every shipped machine and on the test machines bc_head (a
// rotary axis in the tool chain) and xyza_table (one rotary axis), tests/unit/machines/data,
// over random poses in the travel: residuals below 1e-9 mm / 1e-9 rad, FK(IK(w)) = w in both
// world conventions, the forward against the fixed point uncorrect, the analytic Jacobian
// against central differences, the chain against a naive 4x4 product, and the pole fade.
// Seeded; VC_RANDOM_POSES overrides the pose count.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vc/machine/kinematics.hpp"
#include "random_poses.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/units.hpp"

namespace vc::machine {
namespace {

int pose_count() { return test::pose_count(10000); }
using test::random_pose;
using test::text;

// The machines only the tests use.
const std::vector<std::string> kTestMachines{"bc_head", "xyza_table"};

class EveryMachine : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    const bool test_only = std::count(kTestMachines.begin(), kTestMachines.end(), GetParam()) > 0;
    model_ = load_machine(test_only ? test::source_path("tests/unit/machines/data/" + GetParam() + ".toml")
                                    : test::machine_path(GetParam()));
  }
  Model model_;
};

TEST_P(EveryMachine, CorrectionResidualBelowOneNanometreAndNanoradian) {
  std::mt19937_64 rng(1);
  const double L = model_.tool_length_mm;
  int full_orientation = 0;
  for (int k = 0; k < pose_count(); ++k) {
    const Joints q = random_pose(model_, rng);
    const Correction c = correct(model_, q, L);
    ASSERT_EQ(c.status, Status::Ok) << describe(c.status) << " at " << text(q);
    // Independent check of the residual with the full 4x4 pose (another code path).
    const Eigen::Isometry3d real = part_T_tool(model_, Machine::Real, c.joints, L);
    const Eigen::Isometry3d ideal = part_T_tool(model_, Machine::Ideal, q, L);
    ASSERT_LT((real.translation() - ideal.translation()).norm(), 1e-9) << text(q);
    if (c.fade == 1.0 && model_.rotary_count() == 2) {
      ++full_orientation;
      ASSERT_LT(ideal.linear().col(2).cross(real.linear().col(2)).norm(), 1e-9) << text(q);
    }
    ASSERT_LE(c.iterations, 2 * model_.solver.max_iterations);
  }
  if (model_.rotary_count() == 2) {
    EXPECT_GT(full_orientation, pose_count() / 2);
  }
}

TEST_P(EveryMachine, ForwardIsTheExactInverseOfInverseInBothConventions) {
  std::mt19937_64 rng(2);
  const double L = model_.tool_length_mm;
  for (WorldConvention convention : {WorldConvention::Axes, WorldConvention::Tcp}) {
    for (int k = 0; k < pose_count(); ++k) {
      const Joints world = nominal_forward(model_, convention, random_pose(model_, rng), L);
      Joints joints, back;
      ASSERT_EQ(joints_from_world(model_, convention, world, L, joints), Status::Ok) << text(world);
      ASSERT_EQ(world_from_joints(model_, convention, joints, L, back), Status::Ok) << text(joints);
      ASSERT_LT((back - world).cwiseAbs().maxCoeff(), 1e-9) << text(world);
      // The correction really moved the joints (the machine has errors).
      if (k == 0) {
        EXPECT_GT((joints - world).cwiseAbs().maxCoeff(), 1e-6);
      }
    }
  }
}

// full_correction (the forward's band solve evaluates it at q_n): the tool where the ideal
// machine puts it and pointing its way wherever the machine leaves the pole, the fade band
// included (where correct() fades it), checked with the 4x4 chain; without rotary joints,
// correct() itself.
TEST_P(EveryMachine, FullCorrectionPutsAndPointsTheToolAsTheIdealMachine) {
  std::mt19937_64 rng(3);
  const double L = model_.tool_length_mm;
  int band = 0;
  for (int k = 0; k < pose_count() / 10; ++k) {
    const Joints q = random_pose(model_, rng);
    const Correction c = full_correction(model_, q, L, q);
    if (model_.rotary_count() == 0) {
      ASSERT_LT((c.joints - correct(model_, q, L).joints).cwiseAbs().maxCoeff(), 1e-12) << text(q);
      continue;
    }
    if (c.pole_angle_rad < model_.fade.start_rad) continue;  // at the pole the direction is singular
    ASSERT_EQ(c.status, Status::Ok) << describe(c.status) << " at " << text(q);
    band += c.fade < 1.0;
    const Eigen::Isometry3d real = part_T_tool(model_, Machine::Real, c.joints, L);
    const Eigen::Isometry3d ideal = part_T_tool(model_, Machine::Ideal, q, L);
    ASSERT_LT((real.translation() - ideal.translation()).norm(), 1e-9) << text(q);
    if (model_.rotary_count() == 2) {
      ASSERT_LT(ideal.linear().col(2).cross(real.linear().col(2)).norm(), 1e-9) << text(q);
    }
  }
  if (model_.rotary_count() == 2) {
    EXPECT_GT(band, 0);
  }
}

// The module's case: part of the correction (the enable ramp) and solvers seeded with the
// previous answer, or with a far or non-finite seed (LinuxCNC's first call, a jump), and
// with a correction seed that is right, nearly right, far too large or not finite.
TEST_P(EveryMachine, PartialCorrectionWithAnySeedRoundTrips) {
  std::mt19937_64 rng(5);
  const double L = model_.tool_length_mm;
  for (WorldConvention convention : {WorldConvention::Axes, WorldConvention::Tcp}) {
    for (int k = 0; k < pose_count() / 10; ++k) {
      const Joints world = nominal_forward(model_, convention, random_pose(model_, rng), L);
      const double gain = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
      Joints full, nominal;
      ASSERT_EQ(joints_from_world(model_, convention, world, L, full), Status::Ok);
      ASSERT_EQ(nominal_inverse(model_, convention, world, L, nominal), Status::Ok);
      Joints near_seed = full, far_seed = random_pose(model_, rng), nan_seed = full;
      near_seed.array() += 0.01;
      nan_seed[0] = std::nan("");
      const Joints exact_correction = full - nominal;
      Joints near_correction = exact_correction, far_correction = exact_correction, nan_correction = exact_correction;
      near_correction.array() += 2e-4;
      far_correction.array() += 5.0;
      nan_correction[1] = std::nan("");
      for (const Joints* seed : std::array<const Joints*, 4>{nullptr, &near_seed, &far_seed, &nan_seed}) {
        for (const Joints* correction : std::array<const Joints*, 5>{nullptr, &exact_correction, &near_correction,
                                                                     &far_correction, &nan_correction}) {
          Joints joints, back;
          ASSERT_EQ(joints_from_world(model_, convention, world, L, Applied{gain, seed, correction}, joints),
                    Status::Ok);
          ASSERT_LT((joints - (nominal + gain * (full - nominal))).cwiseAbs().maxCoeff(), 1e-9) << text(world);
          const Joints world_seed = seed ? Joints(world.array() + 0.02) : world;
          ASSERT_EQ(world_from_joints(model_, convention, joints, L, Applied{gain, &world_seed, correction}, back),
                    Status::Ok);
          ASSERT_LT((back - world).cwiseAbs().maxCoeff(), 1e-9) << text(world) << " gain " << gain;
        }
      }
      Joints joints;
      ASSERT_EQ(joints_from_world(model_, convention, world, L, Applied{0.0, nullptr}, joints), Status::Ok);
      EXPECT_EQ(joints, nominal);
    }
  }
}

// kinematicsForward's call (gain 1, seeded with the previous cycle's world position: one step
// of 0.1 mm / 0.06 deg per joint before, and with or without that cycle's correction, as
// volkins seeds it) against the core's fixed point uncorrect, which evaluates whole
// corrections only (another code path), to 1e-9 in both conventions.
TEST_P(EveryMachine, ForwardAgreesWithTheFixedPointUncorrect) {
  std::mt19937_64 rng(7);
  const double L = model_.tool_length_mm;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (WorldConvention convention : {WorldConvention::Axes, WorldConvention::Tcp}) {
    for (int k = 0; k < pose_count() / 5; ++k) {
      const Joints nominal = random_pose(model_, rng);
      Joints before(model_.joint_count());
      for (int j = 0; j < model_.joint_count(); ++j)
        before[j] = nominal[j] + unit(rng) * (model_.axes[j].type == AxisType::Linear ? 0.1 : 0.06);
      const Joints world = nominal_forward(model_, convention, nominal, L);
      const Joints previous_world = nominal_forward(model_, convention, before, L);
      Joints joints, previous_joints;
      ASSERT_EQ(joints_from_world(model_, convention, world, L, joints), Status::Ok) << text(world);
      ASSERT_EQ(joints_from_world(model_, convention, previous_world, L, previous_joints), Status::Ok);
      const Joints previous_correction = previous_joints - before;
      const Uncorrection reference = uncorrect(model_, joints, L);
      ASSERT_EQ(reference.status, Status::Ok) << text(joints);
      for (const Joints* correction : {static_cast<const Joints*>(nullptr), &previous_correction}) {
        Joints back;
        ASSERT_EQ(world_from_joints(model_, convention, joints, L, Applied{1.0, &previous_world, correction}, back),
                  Status::Ok);
        ASSERT_LT((back - nominal_forward(model_, convention, reference.nominal, L)).cwiseAbs().maxCoeff(), 1e-9)
            << text(world);
        ASSERT_LT((back - world).cwiseAbs().maxCoeff(), 1e-9) << text(world);
      }
    }
  }
}

TEST_P(EveryMachine, OutsideTablesOnlyBeyondAGrid) {
  std::mt19937_64 rng(6);
  for (int k = 0; k < 100; ++k) EXPECT_FALSE(outside_tables(model_, random_pose(model_, rng)));
  for (const BoundTable& bound : model_.tables) {
    const tables::GridVariable& v = bound.table.grid()[0];
    Joints q = random_pose(model_, rng);
    q[bound.joint[0]] = v.nodes.back() + 1.0;
    EXPECT_EQ(outside_tables(model_, q), !v.periodic) << bound.table.path();
    q[bound.joint[0]] = v.nodes.front() - 1.0;
    EXPECT_EQ(outside_tables(model_, q), !v.periodic) << bound.table.path();
  }
}

TEST_P(EveryMachine, TcpNominalKinematicsRoundTrip) {
  std::mt19937_64 rng(3);
  for (int k = 0; k < 1000; ++k) {
    const Joints q = random_pose(model_, rng);
    const Joints world = nominal_forward(model_, WorldConvention::Tcp, q, model_.tool_length_mm);
    Joints back;
    ASSERT_EQ(nominal_inverse(model_, WorldConvention::Tcp, world, model_.tool_length_mm, back), Status::Ok);
    ASSERT_LT((back - q).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST_P(EveryMachine, AnalyticJacobianMatchesCentralDifferences) {
  std::mt19937_64 rng(4);
  const double L = model_.tool_length_mm;
  for (int k = 0; k < 200; ++k) {
    const Joints q = random_pose(model_, rng);
    for (Machine m : {Machine::Real, Machine::Ideal}) {
      PoseDerivatives d;
      const ToolPose pose = tool_pose(model_, m, q, L, d);
      const ToolPose pose_alone = tool_pose(model_, m, q, L);
      EXPECT_LT((pose.tip_mm - pose_alone.tip_mm).norm(), 1e-11) << text(q);
      EXPECT_LT((pose.direction - pose_alone.direction).norm(), 1e-14) << text(q);
      for (int j = 0; j < model_.joint_count(); ++j) {
        // A rotary joint of the ideal machine turns the tool direction about its line
        // (the part turns it the other way).
        const Axis& axis = model_.axes[static_cast<std::size_t>(j)];
        if (m == Machine::Ideal && axis.type == AxisType::Rotary) {
          const double sign = axis.chain == Chain::Tool ? 1.0 : -1.0;
          const Eigen::Vector3d turn = sign * tables::kDegToRad * d.axis_line.col(j).cross(pose.direction);
          EXPECT_NEAR(d.axis_line.col(j).norm(), 1.0, 1e-14);
          EXPECT_LT((turn - d.direction.col(j)).norm(), 1e-15) << "joint " << j << " at " << text(q);
        }
        const double h = 1e-5;
        Joints plus = q, minus = q;
        plus[j] += h;
        minus[j] -= h;
        const ToolPose p = tool_pose(model_, m, plus, L), n = tool_pose(model_, m, minus, L);
        const Eigen::Vector3d tip_rate = (p.tip_mm - n.tip_mm) / (2 * h);
        const Eigen::Vector3d dir_rate = (p.direction - n.direction) / (2 * h);
        EXPECT_LT((tip_rate - d.tip.col(j)).norm(), 1e-6) << "joint " << j << " at " << text(q);
        EXPECT_LT((dir_rate - d.direction.col(j)).norm(), 1e-9) << "joint " << j << " at " << text(q);
      }
    }
  }
}

// model.md's chain written naively with 4x4 matrices, against the library's evaluation (the
// ideal machine: no table and no location error).
Eigen::Matrix4d naive_chain(const Model& model, Machine machine, const std::vector<int>& chain, const Joints& q) {
  Eigen::Matrix4d f = Eigen::Matrix4d::Identity();
  for (int i : chain) {
    const Axis& a = model.axes[i];
    AxisErrors e;
    axis_errors(model, i, q, e);
    const bool real = machine == Machine::Real;
    if (!real) e.delta_mm.setZero(), e.eps_rad.setZero();
    const Eigen::Vector3d location_mm = real ? a.location_mm : Eigen::Vector3d::Zero();
    const Eigen::Vector3d location_rad = real ? a.location_rad : Eigen::Vector3d::Zero();
    auto T = [](const Eigen::Vector3d& v) {
      Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
      m.block<3, 1>(0, 3) = v;
      return m;
    };
    auto R = [](const Eigen::Matrix3d& r) {
      Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
      m.block<3, 3>(0, 0) = r;
      return m;
    };
    auto Rxyz = [&](const Eigen::Vector3d& v) {
      return R((Eigen::AngleAxisd(v[0], Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(v[1], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(v[2], Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix());
    };
    const Eigen::Matrix4d base = T(a.pole_mm + location_mm) * Rxyz(location_rad);
    if (a.type == AxisType::Linear)
      f = f * base * T(q[i] * a.direction) * T(e.delta_mm) * Rxyz(e.eps_rad);
    else
      f = f * base * T(e.delta_mm) * Rxyz(e.eps_rad) *
          R(Eigen::AngleAxisd(q[i] * M_PI / 180.0, a.direction).toRotationMatrix());
  }
  return f;
}

TEST_P(EveryMachine, ChainEqualsNaiveMatrixProduct) {
  std::mt19937_64 rng(5);
  const double L = model_.tool_length_mm;
  for (const Machine machine : {Machine::Real, Machine::Ideal}) {
    const Eigen::Isometry3d& spindle = machine == Machine::Real ? model_.spindle.real : model_.spindle.ideal;
    for (int k = 0; k < 1000; ++k) {
      const Joints q = random_pose(model_, rng);
      Eigen::Matrix4d tool_offset = Eigen::Matrix4d::Identity();
      tool_offset(2, 3) = -L;
      const Eigen::Matrix4d tool = naive_chain(model_, machine, model_.tool_chain, q) * spindle.matrix() * tool_offset;
      const Eigen::Matrix4d part = naive_chain(model_, machine, model_.workpiece_chain, q) * model_.fixture.matrix();
      const Eigen::Matrix4d expected = part.inverse() * tool;
      const Eigen::Matrix4d got = part_T_tool(model_, machine, q, L).matrix();
      ASSERT_LT((expected - got).cwiseAbs().maxCoeff(), 1e-10) << text(q);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Shipped, EveryMachine, ::testing::ValuesIn(test::shipped_machines()),
                         [](const auto& param_info) { return param_info.param; });
INSTANTIATE_TEST_SUITE_P(TestsOnly, EveryMachine, ::testing::ValuesIn(kTestMachines),
                         [](const auto& param_info) { return param_info.param; });

// Pole fade on the MC-300 (pole at B = 0): rotary joints stay nominal at the pole, the
// correction moves continuously through the fade band, and position stays exact.
TEST(PoleFade, Mc300RotaryCorrectionFadesContinuouslyNearThePole) {
  const Model model = load_machine(test::machine_path("mc300"));
  Joints q(5);
  q << -320.0, -170.0, -140.0, 0.0, 37.0;
  Correction previous = correct(model, q, model.tool_length_mm);
  EXPECT_EQ(previous.fade, 0.0);
  EXPECT_EQ(previous.joints[3], q[3]);
  EXPECT_EQ(previous.joints[4], q[4]);
  EXPECT_GT(previous.residual_rad, 1e-6);  // direction error left by design at the pole
  double previous_fade = 0.0;
  for (double b = -0.01; b >= -15.0; b -= 0.01) {
    q[3] = b;
    const Correction c = correct(model, q, model.tool_length_mm, previous.joints);
    ASSERT_EQ(c.status, Status::Ok) << "b = " << b;
    EXPECT_LT(c.residual_mm, 1e-9);
    EXPECT_GE(c.fade, previous_fade);
    // Joints move smoothly: the step in every corrected joint is the nominal step (0.01 deg
    // on B) plus at most a fraction of a micrometre or micro-degree.
    const Joints step = c.joints - previous.joints;
    EXPECT_NEAR(step[3], -0.01, 2e-4) << "b = " << b;
    EXPECT_LT(std::abs(step[4]), 2e-4) << "b = " << b;
    previous = c;
    previous_fade = c.fade;
  }
  EXPECT_EQ(previous.fade, 1.0);
  EXPECT_LT(previous.residual_rad, 1e-9);
}

}  // namespace
}  // namespace vc::machine
