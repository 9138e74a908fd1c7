// The one number formatter: its texts are printf's in the C locale, rounding cases included.
#include <gtest/gtest.h>

#include <cstdio>

#include "vc/tables/number_text.hpp"

namespace vc {
namespace {

std::string printed(const char* format, double v) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

TEST(NumberText, FixedAndSignificantAsPrintf) {
  for (const double v : {0.00005, -0.00005, 0.000049999, 0.125, 0.25, 2.5, -2.5, 1.45, -0.0, 0.0, 1e-7, 1e21,
                         123456.789, -1234567.0, 0.1 + 0.2}) {
    EXPECT_EQ(fixed_text(v, 0), printed("%.0f", v)) << v;
    EXPECT_EQ(fixed_text(v, 1), printed("%.1f", v)) << v;
    EXPECT_EQ(fixed_text(v, 3), printed("%.3f", v)) << v;
    EXPECT_EQ(fixed_text(v, 4), printed("%.4f", v)) << v;
    EXPECT_EQ(significant_text(v, 6), printed("%.6g", v)) << v;
    EXPECT_EQ(significant_text(v, 12), printed("%.12g", v)) << v;
    EXPECT_EQ(with_sign(fixed_text(v, 3)), printed("%+.3f", v)) << v;
    EXPECT_EQ(scientific_text(v, 1), printed("%.1e", v)) << v;
  }
  EXPECT_EQ(fixed_text(1e308, 2).size(), 312u);
}

TEST(NumberText, Shortest) {
  EXPECT_EQ(number_text(100), "100");
  EXPECT_EQ(number_text(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(number_text(-0.0), "-0");
}

TEST(NumberText, WithoutNegativeZero) {
  EXPECT_EQ(without_negative_zero(number_text(-0.0)), "0");
  EXPECT_EQ(without_negative_zero(fixed_text(-0.00004, 4)), "0.0000");
  EXPECT_EQ(without_negative_zero(fixed_text(-0.00005, 4)), "-0.0001");
  EXPECT_EQ(without_negative_zero("-1e-300"), "-1e-300");
  EXPECT_EQ(without_negative_zero("-nan"), "-nan");
  EXPECT_EQ(without_negative_zero("0.5"), "0.5");
}

TEST(NumberText, WithSign) {
  EXPECT_EQ(with_sign("1.5"), "+1.5");
  EXPECT_EQ(with_sign("-2"), "-2");
  EXPECT_EQ(with_sign(fixed_text(-0.0, 3)), "-0.000");
}

TEST(NumberText, WithoutTrailingZeros) {
  EXPECT_EQ(without_trailing_zeros("7.100000"), "7.1");
  EXPECT_EQ(without_trailing_zeros("5.000000"), "5");
  EXPECT_EQ(without_trailing_zeros("500"), "500");
  EXPECT_EQ(without_trailing_zeros("5", 1), "5.0");
  EXPECT_EQ(without_trailing_zeros("-200.000", 1), "-200.0");
  EXPECT_EQ(without_trailing_zeros("0.003", 1), "0.003");
  EXPECT_EQ(without_trailing_zeros("inf"), "inf");
  EXPECT_EQ(without_negative_zero(without_trailing_zeros(fixed_text(-0.0000001, 6))), "0");
}

}  // namespace
}  // namespace vc
