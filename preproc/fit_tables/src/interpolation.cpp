#include "vc/fit_tables/interpolation.hpp"

#include <algorithm>
#include <cmath>

namespace vc::fit_tables {

NodeWeights node_weights(const std::vector<double>& nodes, bool modulo, double position) {
  const double first = nodes.front(), last = nodes.back();
  const int cells = static_cast<int>(nodes.size()) - 1;
  if (modulo) {
    position = first + std::fmod(position - first, last - first);
    if (position < first) position += last - first;
  }
  NodeWeights w;
  if (position <= first) return w;  // held: the first value
  if (position >= last) {           // held: the last value
    w.low = w.high = cells;
    return w;
  }
  const double step = (last - first) / cells;
  const int k = std::min(cells - 1, static_cast<int>(std::floor((position - first) / step)));
  w.low = k;
  w.high = k + 1;
  w.w_high = (position - nodes[static_cast<std::size_t>(k)]) / step;
  w.w_low = 1.0 - w.w_high;
  return w;
}

std::vector<double> equally_spaced(double first, double last, int count) {
  std::vector<double> out(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k)
    out[static_cast<std::size_t>(k)] = k == count - 1 ? last : first + (last - first) * k / (count - 1);
  return out;
}

}  // namespace vc::fit_tables
