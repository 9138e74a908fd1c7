// The block-triangular solve of the ideal Jacobian against Eigen's LU of the same matrix
// (correction_jacobian, another code path), over the travel of the shipped machines with rotary
// joints, for the full correction and for the position alone, and its refusals.
#include "vc/machine/ideal_jacobian_solver.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cstdio>
#include <random>

#include "test_support.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::machine {
namespace {

struct Case {
  const char* machine;
  bool full;  // the full correction's equations, else the position's (linear joints alone)
};

class IdealJacobianSolverTest : public ::testing::TestWithParam<Case> {};

TEST_P(IdealJacobianSolverTest, SolvesAsTheLuDoes) {
  const Model model = load_machine(test::machine_path(GetParam().machine));
  const int n = model.joint_count();
  std::array<int, kMaxAxes> unknowns{};
  int count = 0;
  for (int j = 0; j < n; ++j)
    if (GetParam().full || model.axes[j].type == AxisType::Linear) unknowns[count++] = j;
  IdealJacobianSolver solver(model, GetParam().full ? model.rotary_count() : 0);
  ASSERT_TRUE(solver.applies());
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int solved = 0;
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    Joints q(n), r(count);
    for (int j = 0; j < n; ++j)
      q[j] = model.axes[j].travel_min + unit(random) * (model.axes[j].travel_max - model.axes[j].travel_min);
    for (int k = 0; k < count; ++k) r[k] = 2 * unit(random) - 1;
    PoseDerivatives d;
    const ToolPose ideal = tool_pose(model, Machine::Ideal, q, model.tool_length_mm, d);
    const CorrectionTarget target = GetParam().full ? full_target(model, ideal, d) : position_target(ideal);
    const SquareMatrix b = correction_jacobian(target, d, unknowns, count);
    const Eigen::PartialPivLU<SquareMatrix> lu(b);
    if (!solver.factorize(target, d)) {  // only at a pole, where B is singular
      EXPECT_LT(std::abs(lu.determinant()), 1e-9) << "refused at a regular point";
      continue;
    }
    const Joints all = solver.solve(r), expected = lu.solve(r);
    Joints x(count);
    for (int k = 0; k < count; ++k) x[k] = all[unknowns[k]];
    EXPECT_DOUBLE_EQ(all.norm(), x.norm()) << "a held joint moved";
    // Relative to the size of the answer (B^-1 grows towards a pole).
    const double difference = (x - expected).norm() / expected.norm();
    worst = std::max(worst, difference);
    EXPECT_LE(difference, 1e-11) << "at q = " << q.transpose();
    EXPECT_LE((b * x - r).norm(), 1e-9 * x.norm());
    ++solved;
  }
  std::printf("%s, %s: %d of 2000 solved, largest relative difference to the LU %.2e\n", GetParam().machine,
              GetParam().full ? "full correction" : "position", solved, worst);
  EXPECT_GT(solved, 1900);
}

INSTANTIATE_TEST_SUITE_P(ShippedMachines, IdealJacobianSolverTest,
                         ::testing::Values(Case{"mc300", true}, Case{"ac_trunnion", true}, Case{"mc300", false},
                                           Case{"mill3", false}));

TEST(IdealJacobianSolver, RefusesTheRealMachinesDerivativesAndASingularBlock) {
  const Model model = load_machine(test::machine_path("mc300"));
  IdealJacobianSolver solver(model, 2);
  const Joints q = (Joints(5) << -300.0, -150.0, -200.0, -40.0, 30.0).finished();
  PoseDerivatives ideal, real;
  const ToolPose pose = tool_pose(model, Machine::Ideal, q, model.tool_length_mm, ideal);
  tool_pose(model, Machine::Real, q, model.tool_length_mm, real);
  const CorrectionTarget target = full_target(model, pose, ideal);
  EXPECT_TRUE(solver.factorize(target, ideal));
  EXPECT_FALSE(solver.factorize(target, real))
      << "the real machine's linear joints turn the tool: not block triangular";
  PoseDerivatives flat = ideal;
  flat.direction.col(4).setZero();  // C would not turn the tool: D singular
  EXPECT_FALSE(solver.factorize(target, flat));
  EXPECT_FALSE(solver.factorize(position_target(pose), ideal)) << "direction equations not the solver's";
}

TEST(IdealJacobianSolver, NeedsThreeLinearJointsAndTheRotaryOnesItSolves) {
  const Model mill3 = load_machine(test::machine_path("mill3"));
  EXPECT_TRUE(IdealJacobianSolver(mill3, 0).applies());
  EXPECT_FALSE(IdealJacobianSolver(mill3, 1).applies());
  const Model mc300 = load_machine(test::machine_path("mc300"));
  EXPECT_TRUE(IdealJacobianSolver(mc300, 2).applies());
  EXPECT_FALSE(IdealJacobianSolver(mc300, 3).applies());
}

}  // namespace
}  // namespace vc::machine
