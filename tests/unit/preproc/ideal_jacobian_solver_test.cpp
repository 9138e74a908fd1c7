// The block-triangular solve of the ideal Jacobian against Eigen's LU of the same matrix,
// over the travel of the shipped machines with rotary joints, and its refusals.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

#include "test_support.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/ideal_jacobian_solver.hpp"

namespace vc::predistort {
namespace {

using machine::Joints;
using machine::SquareMatrix;

SquareMatrix ideal_jacobian(const machine::Model& model, const Joints& q) {
  machine::PoseDerivatives d;
  const machine::ToolPose ideal = machine::tool_pose(model, machine::Machine::Ideal, q, model.tool_length_mm, d);
  const std::array<int, machine::kMaxAxes> all{0, 1, 2, 3, 4, 5};
  return machine::correction_jacobian(machine::full_target(model, ideal, d), d, all, model.joint_count());
}

class IdealJacobianSolverTest : public ::testing::TestWithParam<const char*> {};

TEST_P(IdealJacobianSolverTest, SolvesAsTheLuDoes) {
  const machine::Model model = machine::load_machine(test::machine_path(GetParam()));
  const int n = model.joint_count();
  IdealJacobianSolver solver(model);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int solved = 0;
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    Joints q(n), r(n);
    for (int j = 0; j < n; ++j) {
      q[j] = model.axes[j].travel_min + unit(random) * (model.axes[j].travel_max - model.axes[j].travel_min);
      r[j] = 2 * unit(random) - 1;
    }
    const SquareMatrix b = ideal_jacobian(model, q);
    const Eigen::PartialPivLU<SquareMatrix> lu(b);
    if (!solver.factorize(b)) {  // only at a pole, where B is singular
      EXPECT_LT(std::abs(lu.determinant()), 1e-9) << "refused at a regular point";
      continue;
    }
    const Joints x = solver.solve(r), expected = lu.solve(r);
    // Relative to the size of the answer (B^-1 grows towards a pole).
    const double difference = (x - expected).norm() / expected.norm();
    worst = std::max(worst, difference);
    EXPECT_LE(difference, 1e-11) << "at q = " << q.transpose();
    EXPECT_LE((b * x - r).norm(), 1e-9 * x.norm());
    ++solved;
  }
  std::printf("%s: %d of 2000 solved, largest relative difference to the LU %.2e\n", GetParam(), solved, worst);
  EXPECT_GT(solved, 1900);
}

INSTANTIATE_TEST_SUITE_P(ShippedMachines, IdealJacobianSolverTest, ::testing::Values("mc300", "ac_trunnion"));

TEST(IdealJacobianSolver, RefusesAMatrixThatIsNotBlockTriangularOrSingular) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  IdealJacobianSolver solver(model);
  SquareMatrix b = SquareMatrix::Identity(5, 5);
  EXPECT_TRUE(solver.factorize(b));
  b(3, 0) = 1e-3;  // a linear joint that would turn the tool
  EXPECT_FALSE(solver.factorize(b));
  b = SquareMatrix::Identity(5, 5);
  b(4, 4) = 0.0;
  EXPECT_FALSE(solver.factorize(b));
}

TEST(IdealJacobianSolver, NeedsThreeLinearAndOneOrTwoRotaryJoints) {
  EXPECT_THROW(IdealJacobianSolver(machine::load_machine(test::machine_path("mill3"))), std::logic_error);
}

}  // namespace
}  // namespace vc::predistort
