// The pre-distorter's correction on a three-linear-axis machine against the core's: the same
// corrected joints, and the contraction bound it takes steps on holds (the residual after a
// step, computed exactly, is within kappa times the residual before it).
#include <gtest/gtest.h>

#include <random>

#include "test_support.hpp"
#include "vc/machine/correct.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/linear_correction.hpp"

namespace vc::predistort {
namespace {

using machine::Joints;
using machine::Machine;

TEST(LinearCorrection, AgreesWithTheCoreAndItsContractionBoundHolds) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  LinearCorrection linear(model);
  ASSERT_TRUE(linear.applies());
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int fast = 0;
  double worst_ratio = 0.0, worst_difference = 0.0;
  for (double L : {model.tool_length_mm, 150.0}) {
    const double kappa = linear.contraction(L);
    EXPECT_GT(kappa, 0.0);
    EXPECT_LT(kappa, 1e-2);
    for (int i = 0; i < 2000; ++i) {
      Joints target(3);
      for (int j = 0; j < 3; ++j)
        target[j] = model.axes[j].travel_min + unit(random) * (model.axes[j].travel_max - model.axes[j].travel_min);
      // Seeded as along a path: the corrections 0.5 and 1 mm back along a random direction,
      // extrapolated (PathCorrector::seed_for).
      Joints u(3);
      for (int j = 0; j < 3; ++j) u[j] = 2 * unit(random) - 1;
      u.normalize();
      const Joints back1 = target - 0.5 * u, back2 = target - 1.0 * u;
      const Joints offset1 = machine::correct(model, back1, L).joints - back1;
      const Joints offset2 = machine::correct(model, back2, L).joints - back2;
      const Joints seed = target + offset1 + (offset1 - offset2);
      const machine::Correction core = machine::correct(model, target, L);
      ASSERT_EQ(core.status, machine::Status::Ok);
      Joints corrected;
      ASSERT_TRUE(linear.correct(target, L, seed, corrected));
      const Eigen::Vector3d ideal = machine::tool_pose(model, Machine::Ideal, target, L).tip_mm;
      const double residual = (machine::tool_pose(model, Machine::Real, corrected, L).tip_mm - ideal).norm();
      EXPECT_LE(residual, LinearCorrection::kAcceptedResidualMm);
      worst_difference = std::max(worst_difference, (corrected - core.joints).cwiseAbs().maxCoeff());
      // One step from the seed, evaluated exactly.
      const Eigen::Vector3d before = machine::tool_pose(model, Machine::Real, seed, L).tip_mm - ideal;
      machine::PoseDerivatives d;
      machine::tool_pose(model, Machine::Ideal, seed, L, d);
      const Joints stepped = seed - Joints(d.tip.leftCols<3>().lu().solve(before));
      const double after = (machine::tool_pose(model, Machine::Real, stepped, L).tip_mm - ideal).norm();
      EXPECT_LE(after, kappa * before.norm() + 1e-13);
      if (before.norm() > 1e-9) worst_ratio = std::max(worst_ratio, after / (kappa * before.norm()));
      fast += kappa * before.norm() <= LinearCorrection::kAcceptedResidualMm;
    }
  }
  std::printf("kappa %.3g (L = %.0f mm); residual after a step / its bound: largest %.3f; "
              "%d of 4000 seeds within one unverified step; largest joint difference to the core %.2e mm\n",
              linear.contraction(model.tool_length_mm), model.tool_length_mm, worst_ratio, fast, worst_difference);
  EXPECT_LE(worst_difference, 1e-8);
  EXPECT_GT(fast, 2000);  // most points of a path cost one chain walk
}

}  // namespace
}  // namespace vc::predistort
