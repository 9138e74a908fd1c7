#include "vc/tables/slope.hpp"

#include <cmath>

namespace vc::tables {

SteepestSlope steepest_slope(const ErrorTable& table, const SlopeLimits& limits) {
  SteepestSlope steepest;
  const auto& grid = table.grid();
  const auto& columns = table.columns();
  const int dims = static_cast<int>(grid.size());
  for (int node = 0; node < table.node_count(); ++node) {
    int stride = 1;
    for (int d = dims - 1; d >= 0; --d) {
      const int size = static_cast<int>(grid[d].nodes.size());
      const int i = (node / stride) % size;
      if (i + 1 < size) {
        const double dx = grid[d].nodes[i + 1] - grid[d].nodes[i];
        for (int c = 0; c < static_cast<int>(columns.size()); ++c) {
          const double limit = columns[c].symbol.quantity() == Quantity::Length ? limits.translation
                                                                                 : limits.rotation;
          const double f = std::abs(table.value(node + stride, c) - table.value(node, c)) / dx / limit;
          if (f > steepest.fraction) steepest = {f, c};
        }
      }
      stride *= size;
    }
  }
  return steepest;
}

}  // namespace vc::tables
