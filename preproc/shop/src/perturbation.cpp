#include <cmath>
#include <filesystem>
#include <random>

#include "vc/shop/table_set.hpp"

namespace vc::shop {

std::vector<ExtraTable> perturbation_tables(const machine::Model& model, double low, double high, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ExtraTable> extras;
  for (int j = 0; j < model.joint_count(); ++j)
    for (int t : model.axes[static_cast<std::size_t>(j)].tables) {
      const tables::ErrorTable& original = model.tables[static_cast<std::size_t>(t)].table;
      tables::ErrorTable table = original;
      const auto& first = original.grid().front().nodes;
      std::size_t inner = 1;  // nodes per step of the first grid variable
      for (std::size_t v = 1; v < original.grid().size(); ++v) inner *= original.grid()[v].nodes.size();
      for (std::size_t c = 0; c < original.columns().size(); ++c) {
        const double sign = unit(random) < 0.5 ? -1.0 : 1.0;
        const double phase = 2 * M_PI * unit(random);
        const double mid = (low + high) / 2, swing = (high - low) / 2;
        for (int node = 0; node < original.node_count(); ++node) {
          const double x = first[static_cast<std::size_t>(node) / inner];
          const double t01 = (x - first.front()) / (first.back() - first.front());
          const double f = sign * (mid + swing * std::sin(M_PI * t01 + phase));
          table.set_value(node, static_cast<int>(c), f * original.value(node, static_cast<int>(c)));
        }
      }
      extras.push_back({j, "perturbation_" + std::filesystem::path(original.path()).filename().string(), std::move(table)});
    }
  return extras;
}

}  // namespace vc::shop
