#include "vc/tables/slope.hpp"

#include <algorithm>
#include <cmath>

namespace vc::tables {

namespace {

double limit_of(const Column& c, const SlopeLimits& limits) {
  return c.symbol.quantity() == Quantity::Length ? limits.translation : limits.rotation;
}

// Largest |S'| of a cubic spline segment: S' is quadratic in the cell, so its extremes are at
// the ends or where S'' = 0 (S'' is linear between the node curvatures m0 and m1).
double max_spline_slope(double h, double y0, double y1, double m0, double m1) {
  auto slope_at = [&](double t) {
    const double a = 1.0 - t, b = t;
    return (y1 - y0) / h + ((1.0 - 3.0 * a * a) * m0 + (3.0 * b * b - 1.0) * m1) * h / 6.0;
  };
  double best = std::max(std::abs(slope_at(0.0)), std::abs(slope_at(1.0)));
  if (m0 != m1) {
    const double t = m0 / (m0 - m1);
    if (t > 0.0 && t < 1.0) best = std::max(best, std::abs(slope_at(t)));
  }
  return best;
}

}  // namespace

SteepestSlope steepest_slope(const ErrorTable& table, const SlopeLimits& limits) {
  SteepestSlope steepest;
  if (table.interpolation() == Interpolation::Cubic) {
    if (table.grid()[0].is_temperature()) return steepest;  // (see below)
    const std::vector<double>& x = table.grid()[0].nodes;
    for (int c = 0; c < static_cast<int>(table.columns().size()); ++c)
      for (int i = 0; i + 1 < static_cast<int>(x.size()); ++i) {
        const double f = max_spline_slope(x[i + 1] - x[i], table.value(i, c), table.value(i + 1, c),
                                          table.curvature(i, c), table.curvature(i + 1, c)) /
                         limit_of(table.columns()[c], limits);
        if (f > steepest.fraction) steepest = {f, c, i, i + 1, 0};
      }
    return steepest;
  }
  const auto& grid = table.grid();
  const auto& columns = table.columns();
  const int dims = static_cast<int>(grid.size());
  for (int node = 0; node < table.node_count(); ++node) {
    int stride = 1;
    for (int d = dims - 1; d >= 0; --d) {
      const int size = static_cast<int>(grid[d].nodes.size());
      const int i = (node / stride) % size;
      // Along a temperature there is no limit: the correction is solved for the joints at the
      // temperature of the moment, so only the slopes along axis positions must keep it invertible.
      if (i + 1 < size && !grid[d].is_temperature()) {
        const double dx = grid[d].nodes[i + 1] - grid[d].nodes[i];
        for (int c = 0; c < static_cast<int>(columns.size()); ++c) {
          const double f =
              std::abs(table.value(node + stride, c) - table.value(node, c)) / dx / limit_of(columns[c], limits);
          if (f > steepest.fraction) steepest = {f, c, node, node + stride, d};
        }
      }
      stride *= size;
    }
  }
  return steepest;
}

}  // namespace vc::tables
