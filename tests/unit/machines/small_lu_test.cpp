// SmallLu, the LU of correct()'s Newton steps, against Eigen's FullPivLU on random systems of
// 1 to kMaxAxes unknowns, row orders that need every pivot pattern included (a wrong order of
// the row swaps solved most systems needing two swaps wrong, and Newton then gained two
// digits a step instead of four), and its refusal of singular matrices.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "small_lu.hpp"

namespace vc::machine {
namespace {

TEST(SmallLu, SolvesAsEigenDoesWhateverThePivots) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < 20000; ++k) {
    const int n = 1 + k % kMaxAxes;
    SquareMatrix a(n, n);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) a(r, c) = unit(rng) * (k % 2 ? 1.0 : std::pow(10.0, 3 * unit(rng)));
    Joints b(n);
    for (int i = 0; i < n; ++i) b[i] = unit(rng);
    const Eigen::FullPivLU<SquareMatrix> reference(a);
    if (reference.rcond() < 1e-8) continue;  // too ill-conditioned to compare to 1e-8
    SmallLu lu;
    ASSERT_TRUE(lu.compute(a));
    const Joints x = lu.solve(b), expected = reference.solve(b);
    ASSERT_LT((x - expected).norm(), 1e-8 * expected.norm()) << "n = " << n << "\n" << a;
  }
}

TEST(SmallLu, RefusesASingularMatrix) {
  SquareMatrix a(3, 3);
  a << 1, 2, 3, 2, 4, 6, 0, 1, 1;
  SmallLu lu;
  EXPECT_FALSE(lu.compute(a));
  EXPECT_FALSE(lu.ok());
}

}  // namespace
}  // namespace vc::machine
