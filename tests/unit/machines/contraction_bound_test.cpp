// correct() with a contraction bound (the servo thread's inverse): where it takes a Newton step
// without evaluating the real machine after it (at full correction, the fade band's full
// correction, or the position's last step where the pole fade is below 1), the residual it
// leaves, computed afterwards on another code path (the 4x4 chain, part_T_tool), is within the
// bound it reports and the solver's tolerance, and the joints are the core's. On every shipped
// machine, the test machines and the MC-300 with temperature inputs (the bound sampled over
// their ranges, the correction at temperatures drawn in them), at tool lengths and seeds as
// volkins sees them.
// Seeded; VC_RANDOM_POSES overrides the pose count.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "random_poses.hpp"
#include "test_support.hpp"
#include "vc/machine/contraction_bound.hpp"
#include "vc/machine/correct.hpp"
#include "vc/machine/correction_equations.hpp"
#include "vc/machine/deviations.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::machine {
namespace {

const std::vector<double> kToolLengths{0.0, 100.0, 200.0, 300.0};

Model load(const std::string& name) {
  if (name == "bc_head" || name == "xyza_table")
    return load_machine(test::source_path("tests/unit/machines/data/" + name + ".toml"));
  return load_machine(test::machine_path(name));
}

class ContractionBoundTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ContractionBoundTest, UncheckedStepsLandWithinTheirBoundOnTheCoresJoints) {
  const Model model = load(GetParam());
  const ContractionBound bound(model, kToolLengths, true);
  Conditions at = model.reference_conditions();  // its temperatures drawn at each pose
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), exponent(-11.0, -6.0), length(0.0, 300.0);
  const double tolerance = model.solver.position_tolerance_mm;
  int unchecked = 0, full = 0, faded = 0, unchecked_faded = 0, unchecked_band = 0;
  double worst_ratio = 0.0;  // exact residual / reported bound, where the bound is above rounding
  double worst_band = 0.0;   // the fade band's full correction: exact position residual / the solver's limit
  const int poses = test::pose_count(3000);
  for (int k = 0; k < poses; ++k) {
    for (std::size_t i = 0; i < model.temperatures.size(); ++i)
      at.temperature_degC[i] =
          std::uniform_real_distribution<double>(model.temperatures[i].min_degC, model.temperatures[i].max_degC)(rng);
    const Joints q = test::random_pose(model, rng);
    const double L = length(rng);
    const Correction core = correct(model, at, q, L);
    ASSERT_EQ(core.status, Status::Ok) << test::text(q);
    // Seeds as the servo thread's extrapolation gives them: the answer, 1e-11 to 1e-6 off (in
    // the fade band also the full correction's).
    const double scale = std::pow(10.0, exponent(rng));
    auto near = [&](const Joints& answer) {
      Joints seed = answer;
      for (int j = 0; j < seed.size(); ++j) seed[j] += scale * unit(rng);
      return seed;
    };
    const bool band = core.fade > 0.0 && core.fade < 1.0;
    const Joints full_seed = band ? near(core.full_joints) : Joints();
    const Correction c = correct(model, at, q, L, near(core.joints), &bound, band ? &full_seed : nullptr);
    ASSERT_EQ(c.status, Status::Ok) << test::text(q);
    // Both within the tolerance of the residual; near a pole that leaves the joints ~1e-9 apart.
    ASSERT_LT((c.joints - core.joints).cwiseAbs().maxCoeff(), 1e-8) << test::text(q);
    full += core.fade == 1.0;
    faded += core.fade < 1.0;
    if (c.full_unchecked_step) {
      // The fade band's full correction ended on the bound: its equations' residual, on the 4x4
      // chain, within what the solver stops on there (the direction tolerance times sin(phi)).
      ++unchecked_band;
      ASSERT_TRUE(band) << test::text(q);
      const double limit =
          std::min(tolerance, kDirectionLeverMm * model.solver.direction_tolerance_rad * std::sin(core.pole_angle_rad));
      const Eigen::Isometry3d real = part_T_tool(model, at, Machine::Real, c.full_joints, L);
      const Eigen::Isometry3d ideal = part_T_tool(model, Machine::Ideal, q, L);
      const double position = (real.translation() - ideal.translation()).norm();
      ASSERT_LE(position, limit + 1e-12) << test::text(q);
      worst_band = std::max(worst_band, position / limit);
      if (model.rotary_count() == 2) {
        ASSERT_LE(ideal.linear().col(2).cross(real.linear().col(2)).norm(), limit / kDirectionLeverMm + 1e-15)
            << test::text(q);
      }
      ASSERT_LT((c.full_joints - core.full_joints).cwiseAbs().maxCoeff(), 1e-8) << test::text(q);
    }
    if (!c.unchecked_step) continue;
    ++(core.fade == 1.0 ? unchecked : unchecked_faded);
    ASSERT_LE(c.residual_mm, tolerance);
    const Eigen::Isometry3d real = part_T_tool(model, at, Machine::Real, c.joints, L);
    const Eigen::Isometry3d ideal = part_T_tool(model, Machine::Ideal, q, L);
    const double position = (real.translation() - ideal.translation()).norm();
    // The tool direction: within the bound at full correction (where two rotary joints correct
    // all of it); below, the fade's error, which the position's step (linear joints alone) left
    // as it was.
    const double direction = ideal.linear().col(2).cross(real.linear().col(2)).norm();
    if (core.fade == 1.0 && model.rotary_count() == 2) {
      ASSERT_LE(direction, c.residual_rad + 1e-15) << test::text(q);
    } else if (core.fade < 1.0) {
      ASSERT_NEAR(c.residual_rad, direction, 1e-13) << test::text(q);
    }
    // Rounding of the two chains (~1e-13 mm) on top of the bound.
    ASSERT_LE(position, c.residual_mm + 1e-12) << test::text(q) << " seed off by " << scale << ", L " << L;
    if (c.residual_mm > 1e-12) worst_ratio = std::max(worst_ratio, position / c.residual_mm);
  }
  std::printf(
      "%s: %d of %d poses at full correction and %d of %d in the fade band or at the pole solved with an "
      "unchecked step, %d with the fade band's full correction unchecked; exact residual / bound (above "
      "1e-12 mm) at most %.3f, the band's full correction's / its limit %.3f\n",
      GetParam().c_str(), unchecked, full, unchecked_faded, faded, unchecked_band, worst_ratio, worst_band);
  // Seeds up to 1e-6 off: most at full correction are within reach of the bound, and some below.
  EXPECT_GT(unchecked, full / 2);
  if (faded >= 20) {
    EXPECT_GT(unchecked_faded, 0);
    EXPECT_GT(unchecked_band, 0);
  }
}

TEST_P(ContractionBoundTest, NoUncheckedStepBeyondTheSampledToolLengths) {
  const Model model = load(GetParam());
  const ContractionBound bound(model, kToolLengths, true);
  EXPECT_TRUE(bound.covers(0.0) && bound.covers(300.0));
  EXPECT_FALSE(bound.covers(-0.1) || bound.covers(300.1));
  std::mt19937_64 rng(8);
  for (int k = 0; k < test::pose_count(2000); ++k) {
    const Joints q = test::random_pose(model, rng);
    const Correction core = correct(model, q, 350.0);
    ASSERT_EQ(core.status, Status::Ok);
    const Correction c = correct(model, q, 350.0, Joints(core.joints.array() + 1e-9), &bound);
    ASSERT_EQ(c.status, Status::Ok);
    ASSERT_FALSE(c.unchecked_step) << "tool length beyond the sampled ones";
  }
}

TEST(ContractionBound, NoBoundWhereTheEquationsAreNotSquareOrNotSampled) {
  const Model model = load("mc300");
  const ContractionBound none(model, {});
  for (int band = 0; band < ContractionBound::kBands; ++band) EXPECT_TRUE(std::isinf(none.kappa(band)));
  EXPECT_TRUE(std::isinf(none.position_kappa()));
  EXPECT_FALSE(none.covers(100.0));
  const double mid = 0.5 * (model.fade.start_rad + model.fade.full_rad);  // in the fade band
  EXPECT_TRUE(std::isinf(none.full_kappa(mid)));
  const ContractionBound bound(model, {100.0});
  EXPECT_EQ(bound.band_of(0.5 * model.fade.full_rad), -1);
  // The fade band's: finite where sampled, growing towards the pole as 1 / sin(phi), none below.
  EXPECT_GT(bound.full_kappa(mid), 0.0);
  EXPECT_LT(bound.full_kappa(mid), 1e-1);
  EXPECT_NEAR(bound.full_kappa(model.fade.start_rad) * std::sin(model.fade.start_rad),
              bound.full_kappa(mid) * std::sin(mid), 1e-15);
  EXPECT_TRUE(std::isinf(bound.full_kappa(0.99 * model.fade.start_rad)));
  EXPECT_EQ(bound.full_kappa(model.fade.full_rad), bound.kappa(0));
  for (int band = 0; band < ContractionBound::kBands; ++band) {
    EXPECT_GT(bound.kappa(band), 0.0);
    EXPECT_LT(bound.kappa(band), 1e-2);
  }
  EXPECT_GT(bound.position_kappa(), 0.0);
  EXPECT_LT(bound.position_kappa(), 1e-2);
  // On three linear axes the position's equations are the bands' own: no second kappa.
  EXPECT_TRUE(std::isinf(ContractionBound(load("mill3"), {100.0}).position_kappa()));
}

// The bound describes a step from the servo thread's extrapolation, next to the answer. Where
// the inverse has no correction to start from (its first call, after a clamp, after the gain was
// 0), its seed is LinuxCNC's last joints, a servo period of motion away (0.13 deg of a rotary axis
// at 8000 deg/min): the nominal machine's own curvature over that step is in no sampled kappa,
// and a machine whose kappa is ~0 (errors zero or small) would stop after one step short of the
// answer (0.34 um on LinuxCNC's xyzb sample). Such a seed is solved with every step evaluated.
TEST_P(ContractionBoundTest, ASeedAServoPeriodAwayIsSolvedToTheCoresJoints) {
  const Model measured = load(GetParam());
  for (const Model& model : {measured, keep_only(measured, {})}) {
    const ContractionBound bound(model, kToolLengths);
    std::mt19937_64 rng(9);
    double worst = 0.0;
    for (int k = 0; k < test::pose_count(500); ++k) {
      const Joints q = test::random_pose(model, rng);
      Joints seed = q;  // the last command's joints: 0.13 deg, 0.05 mm behind
      for (int j = 0; j < model.joint_count(); ++j)
        seed[j] -= model.axes[j].type == AxisType::Rotary ? 0.13 : 0.05;
      const Correction core = correct(model, q, 100.0);
      ASSERT_EQ(core.status, Status::Ok);
      Applied applied;
      applied.seed = &seed;
      applied.contraction = &bound;
      Joints joints;
      ASSERT_EQ(joints_from_world(model, WorldConvention::Axes, q, 100.0, applied, joints), Status::Ok);
      worst = std::max(worst, (joints - core.joints).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, 1e-9) << (&model == &measured ? "" : "zero errors");
  }
}

INSTANTIATE_TEST_SUITE_P(Machines, ContractionBoundTest,
                         ::testing::Values("mc300", "mill3", "ac_trunnion", "mc300_thermal", "bc_head", "xyza_table"),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

}  // namespace
}  // namespace vc::machine
