// Table lookup: what each interpolation promises. Linear reproduces linear functions exactly
// (value and slope), multilinear reproduces multilinear functions, end values are held
// outside the grid, a 360-deg rotary grid wraps, the cubic spline is C2 and reproduces
// linear data, the periodic spline follows a smooth periodic function.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "vc/tables/error_table.hpp"

namespace vc::tables {
namespace {

GridVariable variable(char axis, std::vector<double> nodes, bool rotary = false) {
  const bool periodic = rotary && std::abs(nodes.back() - nodes.front() - 360.0) < 1e-9;
  return {axis, rotary, periodic, std::move(nodes), {}, 0.0};
}

Column column(const char* symbol) { return {*parse_error_symbol(symbol), {}}; }

// A 1-D table of f sampled at the nodes.
ErrorTable table_1d(const std::vector<double>& nodes, const std::function<double(double)>& f,
                    Interpolation interpolation = Interpolation::Linear, bool rotary = false) {
  std::vector<double> values;
  for (double x : nodes) values.push_back(f(x));
  return ErrorTable("t.csv", {variable('X', nodes, rotary)}, {column("EXX")}, values, interpolation);
}

double value_at(const ErrorTable& t, double x, double* slope = nullptr) {
  ErrorTable::Sample s;
  t.evaluate(&x, s);
  if (slope) *slope = s.slope[0][0];
  return s.value[0];
}

TEST(ErrorTable, LinearReproducesLinearFunctionsOnUnevenGrids) {
  const ErrorTable t = table_1d({-600, -590, -500, -497.5, -100, 0}, [](double x) { return 0.002 - 3e-6 * x; });
  for (double x = -600; x <= 0; x += 7.3) {
    double slope;
    EXPECT_NEAR(value_at(t, x, &slope), 0.002 - 3e-6 * x, 1e-15) << x;
    EXPECT_NEAR(slope, -3e-6, 1e-15) << x;
  }
}

TEST(ErrorTable, HoldsEndValuesOutsideTheGrid) {
  const ErrorTable t = table_1d({0, 10, 20}, [](double x) { return x * x; });
  double slope;
  EXPECT_EQ(value_at(t, -5, &slope), 0.0);
  EXPECT_EQ(slope, 0.0);
  EXPECT_EQ(value_at(t, 25, &slope), 400.0);
  EXPECT_EQ(slope, 0.0);
  EXPECT_EQ(value_at(t, 15), 250.0);  // linear between nodes
}

TEST(ErrorTable, PeriodicRotaryGridWraps) {
  std::vector<double> nodes;
  for (int c = 0; c <= 360; c += 30) nodes.push_back(c);
  const ErrorTable t = table_1d(nodes, [](double c) { return std::sin(c * M_PI / 180.0); },
                                Interpolation::Linear, true);
  ASSERT_TRUE(t.grid()[0].periodic);
  EXPECT_NEAR(value_at(t, 370), value_at(t, 10), 1e-15);
  EXPECT_NEAR(value_at(t, -10), value_at(t, 350), 1e-15);
  EXPECT_NEAR(value_at(t, 725), value_at(t, 5), 1e-15);
}

TEST(ErrorTable, MultilinearReproducesMultilinearFunctionsWithSlopes) {
  const std::vector<double> xs{0, 50, 75, 200}, ys{-10, 0, 30}, zs{-300, -100, 0};
  auto f = [](double x, double y, double z) {
    return 1 + 2e-3 * x - 3e-3 * y + 4e-6 * x * y + 1e-3 * z + 5e-7 * x * z - 2e-8 * x * y * z;
  };
  std::vector<double> values;
  for (double x : xs)
    for (double y : ys)
      for (double z : zs) values.push_back(f(x, y, z));
  const ErrorTable t("t.csv", {variable('X', xs), variable('Y', ys), variable('Z', zs)}, {column("EZZ")},
                     values, Interpolation::Linear);
  for (double x : {3.0, 60.0, 199.0})
    for (double y : {-7.0, 12.5})
      for (double z : {-250.0, -1.0}) {
        const double p[3] = {x, y, z};
        ErrorTable::Sample s;
        t.evaluate(p, s);
        EXPECT_NEAR(s.value[0], f(x, y, z), 1e-12);
        const double h = 1e-4;
        EXPECT_NEAR(s.slope[0][0], (f(x + h, y, z) - f(x - h, y, z)) / (2 * h), 1e-9);
        EXPECT_NEAR(s.slope[0][1], (f(x, y + h, z) - f(x, y - h, z)) / (2 * h), 1e-9);
        EXPECT_NEAR(s.slope[0][2], (f(x, y, z + h) - f(x, y, z - h)) / (2 * h), 1e-9);
      }
}

TEST(ErrorTable, CubicSplinePassesThroughNodesReproducesLinesAndIsC2) {
  const std::vector<double> nodes{0, 10, 25, 30, 50, 80, 100};
  const ErrorTable line = table_1d(nodes, [](double x) { return 0.5 - 0.01 * x; }, Interpolation::Cubic);
  for (double x = 0; x <= 100; x += 3.7) EXPECT_NEAR(value_at(line, x), 0.5 - 0.01 * x, 1e-14);

  auto f = [](double x) { return std::sin(x / 15.0) * 1e-3; };
  const ErrorTable t = table_1d(nodes, f, Interpolation::Cubic);
  for (double x : nodes) EXPECT_NEAR(value_at(t, x), f(x), 1e-15);
  // Slope against central differences, and the second derivative continuous at inner nodes.
  const double h = 1e-3;
  for (double x = 1; x < 100; x += 4.9) {
    double slope;
    value_at(t, x, &slope);
    EXPECT_NEAR(slope, (value_at(t, x + h) - value_at(t, x - h)) / (2 * h), 1e-9) << x;
  }
  for (std::size_t i = 1; i + 1 < nodes.size(); ++i) {
    const double x = nodes[i], g = 1e-2;
    const double left = (value_at(t, x) - 2 * value_at(t, x - g) + value_at(t, x - 2 * g)) / (g * g);
    const double right = (value_at(t, x + 2 * g) - 2 * value_at(t, x + g) + value_at(t, x)) / (g * g);
    EXPECT_NEAR(left, right, 1e-7) << "second derivative jumps at node " << x;
  }
}

TEST(ErrorTable, PeriodicCubicFollowsASmoothPeriodicFunction) {
  std::vector<double> nodes;
  for (int c = 0; c <= 360; c += 15) nodes.push_back(c);
  auto f = [](double c) { return std::sin(c * M_PI / 180.0) + 0.3 * std::cos(2 * c * M_PI / 180.0); };
  const ErrorTable t = table_1d(nodes, f, Interpolation::Cubic, true);
  for (double c = 0; c < 360; c += 2.5) EXPECT_NEAR(value_at(t, c), f(c), 2e-4) << c;
  // Smooth across 0/360: slopes on both sides agree.
  double before, after;
  value_at(t, 359.999, &before);
  value_at(t, 0.001, &after);
  EXPECT_NEAR(before, after, 1e-6);
}

TEST(ErrorTable, SlopesCanBeSkipped) {
  const ErrorTable t = table_1d({0, 10}, [](double x) { return x; });
  ErrorTable::Sample s;
  s.slope[0][0] = 42.0;
  const double x = 5.0;
  t.evaluate(&x, s, false);
  EXPECT_EQ(s.value[0], 5.0);
  EXPECT_EQ(s.slope[0][0], 42.0);  // untouched
}

}  // namespace
}  // namespace vc::tables
