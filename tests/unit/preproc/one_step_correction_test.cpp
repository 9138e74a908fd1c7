// The pre-distorter's one-step correction against the core's on every shipped machine: the
// same corrected joints, and the contraction bound it takes unverified steps on holds (the
// residual after a step, computed exactly, is within kappa times the residual before it).
#include <gtest/gtest.h>

#include <random>

#include "test_support.hpp"
#include "vc/machine/correct.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/one_step_correction.hpp"

namespace vc::predistort {
namespace {

using machine::Joints;
using machine::Machine;

// |W F| at q for the equations of the full correction at `target` (W: direction rows x lever).
struct Equations {
  const machine::Model& model;
  double L;
  machine::CorrectionTarget target;
  machine::SquareMatrix b;  // d F / d q of the ideal machine at the target

  Equations(const machine::Model& m, const Joints& nominal, double tool_length_mm) : model(m), L(tool_length_mm) {
    machine::PoseDerivatives d;
    const machine::ToolPose ideal = machine::tool_pose(model, Machine::Ideal, nominal, L, d);
    target = model.rotary_count() > 0 ? machine::full_target(model, ideal, d) : machine::position_target(ideal);
    std::array<int, machine::kMaxAxes> all{0, 1, 2, 3, 4, 5};
    b = machine::correction_jacobian(target, d, all, model.joint_count());
  }
  Joints residual(const Joints& q) const {
    return machine::correction_residual(target, machine::tool_pose(model, Machine::Real, q, L), model.joint_count());
  }
  static double weighted(const Joints& r) {
    return std::hypot(r.head(3).norm(), machine::kDirectionLeverMm * std::sqrt(machine::direction_squared_norm(r)));
  }
};

// Rounding in a residual evaluated through chains of hundreds of mm (the bound is about the
// exact residual; 1e-11 mm is a hundredth of the accepted one).
constexpr double kRoundingMm = 1e-11;

class OneStepCorrectionTest : public ::testing::TestWithParam<const char*> {};

TEST_P(OneStepCorrectionTest, AgreesWithTheCoreAndItsContractionBoundHolds) {
  const machine::Model model = machine::load_machine(test::machine_path(GetParam()));
  OneStepCorrection one_step(model, model.reference_conditions());
  ASSERT_TRUE(one_step.applies());
  const int n = model.joint_count();
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int tried = 0, fast = 0, declined = 0;
  double worst_ratio = 0.0, worst_difference = 0.0;
  for (double L : {model.tool_length_mm, model.tool_length_mm + 50.0}) {
    for (int i = 0; i < 2000; ++i) {
      Joints target(n);
      for (int j = 0; j < n; ++j)
        target[j] = model.axes[j].travel_min + unit(random) * (model.axes[j].travel_max - model.axes[j].travel_min);
      // Seeded as along a path: the corrections 0.05 and 0.1 mm (or deg) back along a random
      // direction, extrapolated (PathCorrector::seed_for).
      Joints u(n);
      double length2 = 0.0;
      for (int j = 0; j < n; ++j) {
        u[j] = 2 * unit(random) - 1;
        length2 += u[j] * u[j];
      }
      u *= 0.05 / std::sqrt(length2);
      const Joints back1 = target - u, back2 = target - 2 * u;
      const Joints offset1 = machine::correct(model, back1, L).joints - back1;
      const Joints offset2 = machine::correct(model, back2, L).joints - back2;
      const Joints seed = target + offset1 + (offset1 - offset2);
      const machine::Correction core = machine::correct(model, target, L);
      ASSERT_EQ(core.status, machine::Status::Ok);
      ++tried;
      if (!one_step.applies() || model.rotary_count() == 0) {
      } else if (core.fade < 1.0) {
        EXPECT_EQ(one_step.band_at(target, L), -1);
      } else {
        EXPECT_EQ(one_step.band_at(target, L), one_step.band_of(core.pole_angle_rad, L)) << core.pole_angle_rad;
      }
      Joints corrected;
      if (!one_step.correct(target, L, seed, corrected)) {
        EXPECT_LT(core.fade, 1.0) << "declined away from the pole";
        ++declined;
        continue;
      }
      const double kappa = one_step.contraction(L, machine::pole_angle(model, target, L));
      EXPECT_GT(kappa, 0.0);
      EXPECT_LT(kappa, 1e-2);
      const Equations equations(model, target, L);
      EXPECT_LE(Equations::weighted(equations.residual(corrected)), OneStepCorrection::kAcceptedResidualMm);
      worst_difference = std::max(worst_difference, (corrected - core.joints).cwiseAbs().maxCoeff());
      // One step from the seed, evaluated exactly.
      const Joints before = equations.residual(seed);
      const Joints stepped = seed - Joints(equations.b.lu().solve(before));
      const double after = Equations::weighted(equations.residual(stepped));
      const double bound = kappa * Equations::weighted(before);
      EXPECT_LE(after, bound + kRoundingMm);
      if (Equations::weighted(before) > 1e-8) worst_ratio = std::max(worst_ratio, after / bound);
      fast += bound <= OneStepCorrection::kAcceptedResidualMm;
    }
  }
  std::printf(
      "%s: kappa %.3g at the full-correction angle, %.3g at 60 deg (L = %.0f mm); residual after a step / its bound: largest %.3f; "
      "%d of %d seeds within one unverified step, %d declined (pole); "
      "largest joint difference to the core %.2e mm or deg\n",
      GetParam(), one_step.contraction(model.tool_length_mm, model.fade.full_rad),
      one_step.contraction(model.tool_length_mm, M_PI / 3), model.tool_length_mm, worst_ratio, fast, tried, declined,
      worst_difference);
  EXPECT_LE(worst_difference, 1e-8);
  EXPECT_GT(fast, tried / 2);  // most points of a path cost one chain walk
}

INSTANTIATE_TEST_SUITE_P(ShippedMachines, OneStepCorrectionTest, ::testing::Values("mill3", "mc300", "ac_trunnion"));

}  // namespace
}  // namespace vc::predistort
