// The chain walk's own sines and cosines against independent computations: the library's for
// small angles, long double arithmetic for rotary joint positions in degrees.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "vc/machine/trigonometry.hpp"

namespace vc::machine {
namespace {

// The small-angle sin and cos of the chain walk against the library's, to an ulp.
TEST(SinCos, WithinAnUlpOfTheLibrary) {
  std::mt19937_64 rng(9);
  for (int k = 0; k < 100000; ++k) {
    const double x = std::uniform_real_distribution<double>(-1.2e-3, 1.2e-3)(rng);
    double s, c;
    sin_cos(x, s, c);
    ASSERT_LE(std::abs(s - std::sin(x)), std::abs(std::nextafter(std::sin(x), 1.0) - std::sin(x))) << x;
    ASSERT_LE(std::abs(c - std::cos(x)), std::abs(std::nextafter(std::cos(x), 0.0) - std::cos(x))) << x;
  }
}

// sin and cos of deg degrees in long double (64-bit mantissa: 11 bits beyond a double's).
void exact(double deg, long double& s, long double& c) {
  const long double pi = 3.14159265358979323846264338327950288L;
  const long double x = static_cast<long double>(deg) * (pi / 180.0L);
  s = sinl(x);
  c = cosl(x);
}

// Within 2 ulp of the true value (the ulp of values in [1/2, 1): an absolute 1.1e-16, as a
// rotation matrix's entries need) over ten turns, at random angles and at every multiple of
// 15 deg: 1.47 ulp at most here, the rounding of r * pi / 180 and of the series. More exact
// than the library's sin and cos of deg * pi / 180 (21 ulp here): that product's rounding
// grows with the angle.
TEST(SinCosDeg, WithinTwoUlpOfTheTrueValuesOverTenTurns) {
  const double ulp = std::numeric_limits<double>::epsilon() / 2;
  std::mt19937_64 rng(11);
  double worst = 0.0, library_worst = 0.0;
  auto check = [&](double deg) {
    double s, c;
    sin_cos_deg(deg, s, c);
    long double es, ec;
    exact(deg, es, ec);
    const double error = static_cast<double>(std::max(std::abs(s - es), std::abs(c - ec)));
    const double x = deg * tables::kDegToRad;
    library_worst =
        std::max(library_worst, static_cast<double>(std::max(std::abs(std::sin(x) - es), std::abs(std::cos(x) - ec))));
    worst = std::max(worst, error);
    return error;
  };
  for (int k = 0; k < 400000; ++k) {
    const double deg = std::uniform_real_distribution<double>(-1800.0, 1800.0)(rng);
    ASSERT_LE(check(deg), 2.0 * ulp) << deg;
  }
  for (int k = -120; k <= 120; ++k) ASSERT_LE(check(15.0 * k), 2.0 * ulp) << 15.0 * k;
  RecordProperty("worst_ulp", std::to_string(worst / ulp));
  RecordProperty("library_worst_ulp", std::to_string(library_worst / ulp));
  EXPECT_GT(worst, 0.0);  // the comparison above compares something
  EXPECT_LT(worst, library_worst);
}

// Quarter turns are exact in degrees, and the identity sin^2 + cos^2 = 1 holds to rounding.
TEST(SinCosDeg, QuarterTurnsExactAndOnTheUnitCircle) {
  const double expected[4][2] = {{0, 1}, {1, 0}, {0, -1}, {-1, 0}};
  for (int k = -8; k <= 8; ++k) {
    double s, c;
    sin_cos_deg(90.0 * k, s, c);
    const int quadrant = ((k % 4) + 4) % 4;
    EXPECT_EQ(s, expected[quadrant][0]) << 90 * k;
    EXPECT_EQ(c, expected[quadrant][1]) << 90 * k;
  }
  std::mt19937_64 rng(12);
  for (int k = 0; k < 10000; ++k) {
    double s, c;
    sin_cos_deg(std::uniform_real_distribution<double>(-720.0, 720.0)(rng), s, c);
    ASSERT_NEAR(s * s + c * c, 1.0, 4 * std::numeric_limits<double>::epsilon());
  }
}

// Far outside any travel and not finite: the library's answers (NaN for NaN and infinity).
TEST(SinCosDeg, HugeAndNonFiniteAnglesAsTheLibrary) {
  double s, c;
  sin_cos_deg(std::numeric_limits<double>::quiet_NaN(), s, c);
  EXPECT_TRUE(std::isnan(s) && std::isnan(c));
  sin_cos_deg(std::numeric_limits<double>::infinity(), s, c);
  EXPECT_TRUE(std::isnan(s) && std::isnan(c));
  sin_cos_deg(3e15, s, c);
  EXPECT_EQ(s, std::sin(3e15 * tables::kDegToRad));
  EXPECT_EQ(c, std::cos(3e15 * tables::kDegToRad));
}

}  // namespace
}  // namespace vc::machine
