// Table lookup (ErrorTable::evaluate), built directly from its constructor: what each
// interpolation promises (error_table.hpp, model.md "One axis").
// - linear: reproduces a linear function exactly, value and slope, on even and uneven grids;
// - outside the grid the end values are held with slope 0, except a rotary grid spanning
//   360 deg, which wraps;
// - multilinear (2-D, 3-D): reproduces a multilinear function exactly, with its partial slopes;
// - cubic (natural ends): passes through the nodes, reproduces lines, is C1 and C2, matches an
//   independently solved natural spline, and its slope is the derivative of its value;
// - cubic (periodic ends): follows sin and cos of the angle and is smooth across 0/360.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "vc/tables/error_table.hpp"

namespace vc::tables {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

GridVariable variable(char axis, std::vector<double> nodes, bool rotary = false) {
  const bool periodic = rotary && std::abs(nodes.back() - nodes.front() - 360.0) < 1e-9;
  GridVariable g;
  g.axis = axis;
  g.rotary = rotary;
  g.periodic = periodic;
  g.nodes = std::move(nodes);
  return g;
}

Column column(const char* symbol) {
  const auto s = parse_error_symbol(symbol);
  EXPECT_TRUE(s.has_value()) << symbol;
  return {*s, {}};
}

using Function = std::function<double(double)>;

// A 1-D table over axis X (or C if rotary) with one column per function, sampled at the nodes.
ErrorTable table_1d(const std::vector<double>& nodes, const std::vector<Function>& f,
                    Interpolation interpolation = Interpolation::Linear, bool rotary = false) {
  static const char* const symbols_x[] = {"EXX", "EYX", "EZX", "EAX", "EBX", "ECX"};
  static const char* const symbols_c[] = {"EXC", "EYC", "EZC", "EAC", "EBC", "ECC"};
  std::vector<Column> columns;
  for (std::size_t c = 0; c < f.size(); ++c) columns.push_back(column((rotary ? symbols_c : symbols_x)[c]));
  std::vector<double> values;
  for (double x : nodes)
    for (const Function& fc : f) values.push_back(fc(x));
  return ErrorTable("t.csv", {variable(rotary ? 'C' : 'X', nodes, rotary)}, columns, values, interpolation);
}

struct Lookup {
  double value;
  double slope;
};

Lookup at(const ErrorTable& t, double x, int column = 0) {
  ErrorTable::Sample s;
  t.evaluate(&x, s);
  return {s.value[column], s.slope[column][0]};
}

double value_at(const ErrorTable& t, double x, int column = 0) { return at(t, x, column).value; }

// ---- linear ---------------------------------------------------------------------------------

TEST(LinearTable, ReproducesALinearFunctionOnAnUnevenGrid) {
  // Steps of 10, 90, 2.5, 402.5 and 100 mm: the lookup must search, not divide.
  const std::vector<double> nodes{-600, -590, -500, -497.5, -95, 5};
  const ErrorTable t =
      table_1d(nodes, {[](double x) { return 0.002 - 3e-6 * x; }, [](double x) { return -1e-4 + 7e-7 * x; }});
  ASSERT_EQ(t.grid()[0].uniform_step, 0.0);
  for (double x = -600; x <= 5; x += 1.7) {
    const Lookup a = at(t, x, 0), b = at(t, x, 1);
    EXPECT_NEAR(a.value, 0.002 - 3e-6 * x, 1e-15) << x;
    EXPECT_NEAR(a.slope, -3e-6, 1e-15) << x;
    EXPECT_NEAR(b.value, -1e-4 + 7e-7 * x, 1e-15) << x;
    EXPECT_NEAR(b.slope, 7e-7, 1e-15) << x;
  }
  for (double x : nodes) EXPECT_NEAR(value_at(t, x), 0.002 - 3e-6 * x, 1e-15) << "node " << x;
}

TEST(LinearTable, ReproducesALinearFunctionOnAnEvenGrid) {
  std::vector<double> nodes;
  for (int i = 0; i <= 24; ++i) nodes.push_back(-300.0 + 12.5 * i);
  const ErrorTable t = table_1d(nodes, {[](double x) { return 5e-3 + 4e-6 * x; }});
  ASSERT_DOUBLE_EQ(t.grid()[0].uniform_step, 12.5);  // the O(1) lookup path
  for (double x = -300; x <= 0; x += 0.37) {
    const Lookup a = at(t, x);
    EXPECT_NEAR(a.value, 5e-3 + 4e-6 * x, 1e-15) << x;
    EXPECT_NEAR(a.slope, 4e-6, 1e-15) << x;
  }
}

TEST(LinearTable, FindsTheRightCellOnAnEvenGrid) {
  // Curved data on an even grid: the chord of the right cell (a neighbouring cell's chord,
  // extended, would give a different value).
  std::vector<double> nodes;
  for (int i = 0; i <= 10; ++i) nodes.push_back(-50.0 + 10.0 * i);
  auto f = [](double x) { return 1e-6 * x * x; };
  const ErrorTable t = table_1d(nodes, {f});
  ASSERT_DOUBLE_EQ(t.grid()[0].uniform_step, 10.0);
  for (double x = -50; x <= 50; x += 0.7) {
    const double left = std::min(std::floor((x + 50) / 10), 9.0) * 10 - 50, right = left + 10;
    const double chord = (f(right) - f(left)) / 10;
    EXPECT_NEAR(value_at(t, x), f(left) + chord * (x - left), 1e-15) << x;
    EXPECT_NEAR(at(t, x).slope, chord, 1e-15) << x;
  }
}

TEST(LinearTable, InterpolatesBetweenNodesOfACurve) {
  // Data that is not linear: the lookup is the chord of each cell, slope the chord's slope.
  const ErrorTable t = table_1d({0, 10, 40}, {[](double x) { return x * x * 1e-5; }});
  EXPECT_NEAR(value_at(t, 5), 0.5e-3, 1e-15);   // midway 0 .. 1e-3
  EXPECT_NEAR(at(t, 5).slope, 1e-4, 1e-15);     // 1e-3 / 10
  EXPECT_NEAR(value_at(t, 25), 8.5e-3, 1e-15);  // midway 1e-3 .. 16e-3
  EXPECT_NEAR(at(t, 25).slope, 15e-3 / 30, 1e-15);
}

TEST(LinearTable, HoldsEndValuesOutsideTheGridWithSlopeZero) {
  const ErrorTable t = table_1d({0, 10, 20}, {[](double x) { return 1e-3 + 2e-5 * x * x; }});
  for (double x : {-1e6, -5.0, -1e-9}) {
    const Lookup a = at(t, x);
    EXPECT_EQ(a.value, 1e-3) << x;
    EXPECT_EQ(a.slope, 0.0) << x;
  }
  for (double x : {20.0 + 1e-9, 25.0, 1e6}) {
    const Lookup a = at(t, x);
    EXPECT_DOUBLE_EQ(a.value, 1e-3 + 2e-5 * 400) << x;
    EXPECT_EQ(a.slope, 0.0) << x;
  }
  // Inside, the slope is not zero: the hold starts at the end nodes, not before.
  EXPECT_NEAR(at(t, 19.9).slope, (2e-5 * 400 - 2e-5 * 100) / 10, 1e-15);
  EXPECT_NEAR(at(t, 0.1).slope, 2e-5 * 100 / 10, 1e-15);
}

TEST(LinearTable, ARotaryGridShorterThan360DegHoldsItsEnds) {
  // B of a tilting table: -120 .. 30 deg is not periodic.
  const ErrorTable t = table_1d({-120, -60, 0, 30}, {[](double b) { return 1e-5 * b; }}, Interpolation::Linear, true);
  ASSERT_FALSE(t.grid()[0].periodic);
  EXPECT_EQ(value_at(t, 40), value_at(t, 30));
  EXPECT_EQ(at(t, 40).slope, 0.0);
  EXPECT_EQ(value_at(t, -200), value_at(t, -120));
}

TEST(LinearTable, PeriodicRotaryGridWraps) {
  std::vector<double> nodes;
  for (int c = 0; c <= 360; c += 30) nodes.push_back(c);
  const ErrorTable t =
      table_1d(nodes, {[](double c) { return 1e-3 * std::sin(c * kDeg); }}, Interpolation::Linear, true);
  ASSERT_TRUE(t.grid()[0].periodic);
  // Where the held-ends rule would give 0 (the end value), the wrap gives the value across 0.
  const double chord = 1e-3 * std::sin(30 * kDeg) / 30;  // slope of the cells next to 0
  EXPECT_NEAR(value_at(t, 10), 10 * chord, 1e-15);
  EXPECT_NEAR(value_at(t, 370), 10 * chord, 1e-15);
  EXPECT_NEAR(at(t, 370).slope, chord, 1e-15);
  EXPECT_NEAR(value_at(t, 350), -10 * chord, 1e-15);
  EXPECT_NEAR(value_at(t, -10), -10 * chord, 1e-15);
  EXPECT_NEAR(at(t, -10).slope, chord, 1e-15);
  for (double c : {5.0, 47.0, 123.4, 299.0, 359.5}) {
    for (int turns : {-3, -1, 1, 2, 10}) {
      const Lookup a = at(t, c), b = at(t, c + 360.0 * turns);
      EXPECT_NEAR(b.value, a.value, 1e-15) << c << " + " << turns << " turns";
      EXPECT_NEAR(b.slope, a.slope, 1e-15) << c << " + " << turns << " turns";
    }
  }
}

TEST(LinearTable, PeriodicGridNotStartingAtZeroWraps) {
  // -180 .. 180 deg, uneven steps.
  const std::vector<double> nodes{-180, -100, -45, 0, 30, 120, 180};
  const ErrorTable t =
      table_1d(nodes, {[](double c) { return 1e-3 * std::cos(c * kDeg); }}, Interpolation::Linear, true);
  ASSERT_TRUE(t.grid()[0].periodic);
  EXPECT_NEAR(value_at(t, 190), value_at(t, -170), 1e-15);
  EXPECT_NEAR(value_at(t, -190), value_at(t, 170), 1e-15);
  // 190 deg wraps to -170, 10/80 of the way into the cell -180 .. -100.
  const double y0 = 1e-3 * std::cos(-180 * kDeg), y1 = 1e-3 * std::cos(-100 * kDeg);
  EXPECT_NEAR(value_at(t, 190), y0 + (y1 - y0) * 10.0 / 80.0, 1e-15);
}

// ---- multilinear ----------------------------------------------------------------------------

TEST(MultilinearTable, TwoDimensionsReproduceABilinearFunction) {
  // f = a + b x + c y + d x y on an uneven Z-by-Y grid (first variable slowest).
  const double a = 2e-3, b = -4e-6, c = 3e-6, d = 5e-9;
  auto f = [&](double z, double y) { return a + b * z + c * y + d * z * y; };
  const std::vector<double> zs{-300, -220, -100, -97, 0}, ys{0, 12.5, 150, 300};
  std::vector<double> values;
  for (double z : zs)
    for (double y : ys) values.push_back(f(z, y));
  const ErrorTable t("t.csv", {variable('Z', zs), variable('Y', ys)}, {column("EZZ")}, values, Interpolation::Linear);
  const double h = 1e-3;
  for (double z = -300; z <= 0; z += 13.7)
    for (double y = 0; y <= 300; y += 21.1) {
      const double p[2] = {z, y};
      ErrorTable::Sample s;
      t.evaluate(p, s);
      EXPECT_NEAR(s.value[0], f(z, y), 1e-15) << z << ", " << y;
      EXPECT_NEAR(s.slope[0][0], b + d * y, 1e-15) << z << ", " << y;
      EXPECT_NEAR(s.slope[0][1], c + d * z, 1e-15) << z << ", " << y;
      // The slopes are the derivatives of the table's own values (central differences; the
      // table is linear along each variable inside a cell, so this is exact up to rounding).
      if (z - h < -300 || z + h > 0 || y - h < 0 || y + h > 300) continue;
      ErrorTable::Sample lo, hi;
      const double pz0[2] = {z - h, y}, pz1[2] = {z + h, y}, py0[2] = {z, y - h}, py1[2] = {z, y + h};
      t.evaluate(pz0, lo);
      t.evaluate(pz1, hi);
      EXPECT_NEAR(s.slope[0][0], (hi.value[0] - lo.value[0]) / (2 * h), 1e-11);
      t.evaluate(py0, lo);
      t.evaluate(py1, hi);
      EXPECT_NEAR(s.slope[0][1], (hi.value[0] - lo.value[0]) / (2 * h), 1e-11);
    }
}

TEST(MultilinearTable, TwoDimensionsHoldEachVariableSeparately) {
  // Outside the grid along Y only: Y is held (slope 0), Z still interpolates.
  auto f = [](double z, double y) { return 1e-3 + 2e-6 * z - 1e-6 * y + 1e-8 * z * y; };
  const std::vector<double> zs{-300, 0}, ys{0, 100, 300};
  std::vector<double> values;
  for (double z : zs)
    for (double y : ys) values.push_back(f(z, y));
  const ErrorTable t("t.csv", {variable('Z', zs), variable('Y', ys)}, {column("EZZ")}, values, Interpolation::Linear);
  const double p[2] = {-120, 450};
  ErrorTable::Sample s;
  t.evaluate(p, s);
  EXPECT_NEAR(s.value[0], f(-120, 300), 1e-15);
  EXPECT_NEAR(s.slope[0][0], 2e-6 + 1e-8 * 300, 1e-15);
  EXPECT_EQ(s.slope[0][1], 0.0);
  const double q[2] = {-400, -50};  // outside along both
  t.evaluate(q, s);
  EXPECT_NEAR(s.value[0], f(-300, 0), 1e-15);
  EXPECT_EQ(s.slope[0][0], 0.0);
  EXPECT_EQ(s.slope[0][1], 0.0);
}

TEST(MultilinearTable, ThreeDimensionsReproduceATrilinearFunction) {
  const std::vector<double> xs{0, 50, 75, 200}, ys{-10, 0, 30}, zs{-300, -100, 0};
  auto f = [](double x, double y, double z) {
    return 1e-3 + 2e-6 * x - 3e-6 * y + 4e-9 * x * y + 1e-6 * z + 5e-9 * x * z - 2e-9 * y * z - 2e-11 * x * y * z;
  };
  auto fx = [](double, double y, double z) { return 2e-6 + 4e-9 * y + 5e-9 * z - 2e-11 * y * z; };
  auto fy = [](double x, double, double z) { return -3e-6 + 4e-9 * x - 2e-9 * z - 2e-11 * x * z; };
  auto fz = [](double x, double y, double) { return 1e-6 + 5e-9 * x - 2e-9 * y - 2e-11 * x * y; };
  std::vector<double> values;  // two columns: f and -2 f
  for (double x : xs)
    for (double y : ys)
      for (double z : zs) {
        values.push_back(f(x, y, z));
        values.push_back(-2 * f(x, y, z));
      }
  const ErrorTable t("t.csv", {variable('X', xs), variable('Y', ys), variable('Z', zs)}, {column("EZX"), column("EYX")},
                     values, Interpolation::Linear);
  const double h = 1e-3;
  for (double x : {0.0, 3.0, 50.0, 60.0, 199.0})
    for (double y : {-7.0, 0.5, 12.5, 29.0})
      for (double z : {-250.0, -100.0, -1.0}) {
        const double p[3] = {x, y, z};
        ErrorTable::Sample s;
        t.evaluate(p, s);
        EXPECT_NEAR(s.value[0], f(x, y, z), 1e-15);
        EXPECT_NEAR(s.value[1], -2 * f(x, y, z), 2e-15);
        EXPECT_NEAR(s.slope[0][0], fx(x, y, z), 1e-15);
        EXPECT_NEAR(s.slope[0][1], fy(x, y, z), 1e-15);
        EXPECT_NEAR(s.slope[0][2], fz(x, y, z), 1e-15);
        EXPECT_NEAR(s.slope[1][2], -2 * fz(x, y, z), 2e-15);
        // Against central differences of f (exact for a function linear in each variable).
        EXPECT_NEAR(s.slope[0][0], (f(x + h, y, z) - f(x - h, y, z)) / (2 * h), 1e-11);
        EXPECT_NEAR(s.slope[0][1], (f(x, y + h, z) - f(x, y - h, z)) / (2 * h), 1e-11);
        EXPECT_NEAR(s.slope[0][2], (f(x, y, z + h) - f(x, y, z - h)) / (2 * h), 1e-11);
      }
}

TEST(MultilinearTable, APeriodicVariableWrapsInACrossAxisTable) {
  // A table over C (0 .. 360, periodic) and X: C wraps, X holds.
  const std::vector<double> cs{0, 90, 180, 270, 360}, xs{0, 100};
  auto f = [](double c, double x) { return 1e-3 * std::sin(c * kDeg) * (1 + x / 100); };
  std::vector<double> values;
  for (double c : cs)
    for (double x : xs) values.push_back(f(c, x));
  const ErrorTable t("t.csv", {variable('C', cs, true), variable('X', xs)}, {column("EXC")}, values,
                     Interpolation::Linear);
  ASSERT_TRUE(t.grid()[0].periodic);
  ErrorTable::Sample a, b;
  const double p[2] = {30, 50}, q[2] = {390, 50}, r[2] = {-330, 150};
  t.evaluate(p, a);
  t.evaluate(q, b);
  EXPECT_NEAR(a.value[0], 1e-3 * (30.0 / 90.0) * 1.5, 1e-15);
  EXPECT_NEAR(b.value[0], a.value[0], 1e-15);
  EXPECT_NEAR(b.slope[0][0], a.slope[0][0], 1e-15);
  EXPECT_NEAR(b.slope[0][1], a.slope[0][1], 1e-15);
  t.evaluate(r, b);  // -330 = 30 deg, x beyond the grid: held at x = 100
  EXPECT_NEAR(b.value[0], 1e-3 * (30.0 / 90.0) * 2.0, 1e-15);
  EXPECT_EQ(b.slope[0][1], 0.0);
}

// ---- cubic spline ---------------------------------------------------------------------------

// Reference natural spline, solved independently: unknowns are the second derivatives at all
// nodes, with m_0 = m_{n-1} = 0, by dense Gaussian elimination.
std::vector<double> reference_natural_curvature(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  std::vector<std::vector<double>> a(n, std::vector<double>(n + 1, 0.0));
  a[0][0] = 1.0;
  a[n - 1][n - 1] = 1.0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
    a[i][i - 1] = h0 / 6;
    a[i][i] = (h0 + h1) / 3;
    a[i][i + 1] = h1 / 6;
    a[i][n] = (y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0;
  }
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    std::swap(a[c], a[pivot]);
    for (std::size_t r = 0; r < n; ++r) {
      if (r == c) continue;
      const double k = a[r][c] / a[c][c];
      for (std::size_t k2 = c; k2 <= n; ++k2) a[r][k2] -= k * a[c][k2];
    }
  }
  std::vector<double> m(n);
  for (std::size_t i = 0; i < n; ++i) m[i] = a[i][n] / a[i][i];
  return m;
}

double reference_spline(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& m,
                        double at) {
  std::size_t i = 0;
  while (i + 2 < x.size() && at > x[i + 1]) ++i;
  const double h = x[i + 1] - x[i], a = (x[i + 1] - at) / h, b = (at - x[i]) / h;
  return a * y[i] + b * y[i + 1] + ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6;
}

// The second derivative just left and just right of x, from values on one side only. On a
// cubic piece a second difference is exact at its middle point and the second derivative is
// linear, so 2 D(g) - D(2 g) is the one-sided limit at x (up to rounding).
struct SecondDerivatives {
  double left, right;
};
SecondDerivatives one_sided_second_derivatives(const ErrorTable& t, double x, double g, int column = 0) {
  auto left = [&](double s) {
    return (value_at(t, x, column) - 2 * value_at(t, x - s, column) + value_at(t, x - 2 * s, column)) / (s * s);
  };
  auto right = [&](double s) {
    return (value_at(t, x + 2 * s, column) - 2 * value_at(t, x + s, column) + value_at(t, x, column)) / (s * s);
  };
  return {2 * left(g) - left(2 * g), 2 * right(g) - right(2 * g)};
}

const std::vector<double> kUnevenNodes{0, 10, 25, 30, 50, 80, 100};
double curve(double x) { return 1e-2 * std::sin(x / 15.0) + 2e-4 * x; }

TEST(CubicTable, ReproducesLinearDataExactly) {
  const ErrorTable t = table_1d(kUnevenNodes, {[](double x) { return 0.005 - 4e-5 * x; }}, Interpolation::Cubic);
  for (double x = 0; x <= 100; x += 0.93) {
    const Lookup a = at(t, x);
    EXPECT_NEAR(a.value, 0.005 - 4e-5 * x, 1e-15) << x;
    EXPECT_NEAR(a.slope, -4e-5, 1e-15) << x;
  }
}

TEST(CubicTable, PassesThroughTheNodes) {
  const ErrorTable t = table_1d(kUnevenNodes, {curve}, Interpolation::Cubic);
  for (double x : kUnevenNodes) EXPECT_NEAR(value_at(t, x), curve(x), 1e-15) << x;
}

TEST(CubicTable, IsTheNaturalSplineOfTheData) {
  // Against an independent solve; between nodes it is not the chord (that would be linear).
  const ErrorTable t = table_1d(kUnevenNodes, {curve}, Interpolation::Cubic);
  std::vector<double> y;
  for (double x : kUnevenNodes) y.push_back(curve(x));
  const std::vector<double> m = reference_natural_curvature(kUnevenNodes, y);
  for (double x = 0; x <= 100; x += 0.77)
    EXPECT_NEAR(value_at(t, x), reference_spline(kUnevenNodes, y, m, x), 1e-15) << x;
  const double chord = y[0] + (y[1] - y[0]) * 0.5;
  EXPECT_GT(std::abs(value_at(t, 5) - chord), 1e-5);
}

TEST(CubicTable, SlopeIsTheDerivativeOfTheValue) {
  const ErrorTable t = table_1d(kUnevenNodes, {curve}, Interpolation::Cubic);
  const double h = 1e-4;
  for (double x = 0.5; x < 100; x += 1.3) {
    const double fd = (value_at(t, x + h) - value_at(t, x - h)) / (2 * h);
    EXPECT_NEAR(at(t, x).slope, fd, 1e-10) << x;
  }
}

TEST(CubicTable, IsC1AndC2AtTheNodes) {
  const ErrorTable t = table_1d(kUnevenNodes, {curve}, Interpolation::Cubic);
  std::vector<double> y;
  for (double x : kUnevenNodes) y.push_back(curve(x));
  const std::vector<double> m = reference_natural_curvature(kUnevenNodes, y);
  const double g = 1e-3;
  for (std::size_t i = 1; i + 1 < kUnevenNodes.size(); ++i) {
    const double x = kUnevenNodes[i];
    // C1: slopes just left and just right of the node agree.
    EXPECT_NEAR(at(t, x - 1e-7).slope, at(t, x + 1e-7).slope, 1e-11) << "slope jumps at node " << x;
    // C2: one-sided second differences agree, and are the (non-zero) curvature of the spline.
    const SecondDerivatives d = one_sided_second_derivatives(t, x, g);
    EXPECT_NEAR(d.left, d.right, 1e-8) << "second derivative jumps at node " << x;
    EXPECT_NEAR(d.left, m[i], 1e-8) << x;
    EXPECT_GT(std::abs(m[i]), 1e-6) << "the test data must be curved at node " << x;
  }
  // Natural ends: no curvature at the first and last node.
  EXPECT_NEAR(one_sided_second_derivatives(t, 0, g).right, 0.0, 1e-8);
  EXPECT_NEAR(one_sided_second_derivatives(t, 100, g).left, 0.0, 1e-8);
}

TEST(CubicTable, HoldsEndValuesOutsideTheGrid) {
  const ErrorTable t = table_1d(kUnevenNodes, {curve}, Interpolation::Cubic);
  EXPECT_EQ(value_at(t, -3), curve(0));
  EXPECT_EQ(at(t, -3).slope, 0.0);
  EXPECT_NEAR(value_at(t, 130), curve(100), 1e-18);
  EXPECT_EQ(at(t, 130).slope, 0.0);
}

TEST(PeriodicCubicTable, FollowsSinAndCosAndIsSmoothAcross360) {
  // Every 15 deg. The cubic-spline error bound (5/384) h^4 max|f''''| is 6e-5 of the amplitude
  // here (h = 15 deg, f'''' = (pi/180)^4); the test allows 1e-4.
  std::vector<double> nodes;
  for (int c = 0; c <= 360; c += 15) nodes.push_back(c);
  const double amplitude = 1.0;
  const ErrorTable t = table_1d(nodes,
                                {[&](double c) { return amplitude * std::sin(c * kDeg); },
                                 [&](double c) { return amplitude * std::cos(c * kDeg); }},
                                Interpolation::Cubic, true);
  ASSERT_TRUE(t.grid()[0].periodic);
  double worst = 0.0;
  for (double c = -30; c <= 390; c += 0.5) {
    const Lookup s = at(t, c, 0), k = at(t, c, 1);
    EXPECT_NEAR(s.value, std::sin(c * kDeg), 1e-4) << c;
    EXPECT_NEAR(k.value, std::cos(c * kDeg), 1e-4) << c;
    EXPECT_NEAR(s.slope, kDeg * std::cos(c * kDeg), 1e-4 * kDeg * 15) << c;
    EXPECT_NEAR(k.slope, -kDeg * std::sin(c * kDeg), 1e-4 * kDeg * 15) << c;
    worst = std::max(worst, std::abs(s.value - std::sin(c * kDeg)));
  }
  EXPECT_GT(worst, 1e-7);  // it is a spline, not an exact sine: the tolerance means something
  // Wrapped positions give the same lookup.
  for (double c : {10.0, 100.0, 359.0})
    for (int col : {0, 1}) {
      EXPECT_NEAR(value_at(t, c + 360, col), value_at(t, c, col), 1e-14);
      EXPECT_NEAR(value_at(t, c - 360, col), value_at(t, c, col), 1e-14);
    }
  // Smooth across 0/360: slope and curvature from either side agree (natural ends would give
  // cos zero curvature there instead of -(pi/180)^2, and the wrong slope for sin).
  const double g = 1e-2;
  for (int col : {0, 1}) {
    EXPECT_NEAR(at(t, 360 - 1e-9, col).slope, at(t, 1e-9, col).slope, 1e-12) << col;
    const SecondDerivatives d = one_sided_second_derivatives(t, 360, g, col);
    const SecondDerivatives d0 = one_sided_second_derivatives(t, 0, g, col);
    EXPECT_NEAR(d.left, d0.right, 1e-9) << col;
    EXPECT_NEAR(d.left, d.right, 1e-9) << col;
  }
  // The values there: slope of sin and curvature of cos at 0, to the spline's accuracy.
  EXPECT_NEAR(at(t, 0, 0).slope, kDeg, 1e-4 * kDeg);
  EXPECT_NEAR(one_sided_second_derivatives(t, 0, g, 1).right, -kDeg * kDeg, 1e-2 * kDeg * kDeg);
}

TEST(ErrorTable, SlopesCanBeSkipped) {
  const ErrorTable t = table_1d({0, 10}, {[](double x) { return x * 1e-3; }});
  ErrorTable::Sample s;
  s.slope[0][0] = 42.0;
  const double x = 5.0;
  t.evaluate(&x, s, false);
  EXPECT_EQ(s.value[0], 5e-3);
  EXPECT_EQ(s.slope[0][0], 42.0);  // untouched
}

// add_components: each column's value (to rounding: an FMA may join a product and a sum in
// one function and not the other) added at its component; components
// without a column get nothing. Columns out of component order, 1-D (its own layout) and 2-D
// (through evaluate), and after set_value.
void expect_components_match(const ErrorTable& t, const double* p, const char* where) {
  ErrorTable::Sample s;
  t.evaluate(p, s, false);
  std::array<double, ErrorTable::kMaxColumns> before{1.0, 2.0, 3.0, 4.0, 5.0, 6.0}, sum = before;
  t.add_components(p, sum);
  std::array<double, ErrorTable::kMaxColumns> expected = before;
  for (std::size_t c = 0; c < t.columns().size(); ++c) expected[t.columns()[c].symbol.component] += s.value[c];
  for (int k = 0; k < ErrorTable::kMaxColumns; ++k)
    EXPECT_DOUBLE_EQ(sum[k], expected[k]) << where << " component " << k;
}

TEST(ErrorTable, AddComponentsAddsEachColumnAtItsComponent) {
  const std::vector<double> xs{0, 10, 25, 40};
  std::vector<double> values;
  for (double x : xs) values.insert(values.end(), {1e-3 + 1e-5 * x, -2e-6 * x, 3e-4 - 1e-6 * x * x});
  ErrorTable one("t.csv", {variable('X', xs)}, {column("ECX"), column("EYX"), column("EXX")}, values,
                 Interpolation::Linear);
  for (double x : {-5.0, 0.0, 3.3, 10.0, 31.7, 40.0, 55.0}) expect_components_match(one, &x, "1-D");
  one.set_value(2, 1, 7e-3);  // EYX at x = 25
  for (double x : {20.0, 25.0, 30.0}) expect_components_match(one, &x, "1-D after set_value");
  const double y25 = 25.0;
  std::array<double, ErrorTable::kMaxColumns> sum{};
  one.add_components(&y25, sum);
  EXPECT_DOUBLE_EQ(sum[1], 7e-3);

  const std::vector<double> zs{-100, 0}, ys{0, 50, 100};
  std::vector<double> grid_values;
  for (double z : zs)
    for (double y : ys) grid_values.insert(grid_values.end(), {1e-6 * z, 2e-6 * y});
  const ErrorTable two("t.csv", {variable('Z', zs), variable('Y', ys)}, {column("EBZ"), column("EZZ")}, grid_values,
                       Interpolation::Linear);
  const double p[2] = {-30.0, 70.0};
  expect_components_match(two, p, "2-D");
}

TEST(ErrorTable, SetValueRecomputesTheSpline) {
  ErrorTable t = table_1d(kUnevenNodes, {[](double) { return 0.0; }}, Interpolation::Cubic);
  for (int node = 0; node < t.node_count(); ++node) t.set_value(node, 0, curve(kUnevenNodes[node]));
  const ErrorTable fresh = table_1d(kUnevenNodes, {curve}, Interpolation::Cubic);
  for (double x = 0; x <= 100; x += 3.1) EXPECT_NEAR(value_at(t, x), value_at(fresh, x), 1e-15) << x;
}

}  // namespace
}  // namespace vc::tables
