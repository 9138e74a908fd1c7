#include <cmath>
#include <filesystem>
#include <random>

#include "vc/shop/machine_file_writer.hpp"

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
        // (once round on a full turn: a periodic table stays periodic)
        const double turns = original.grid().front().periodic ? 2.0 : 1.0;
        for (int node = 0; node < original.node_count(); ++node) {
          const double x = first[static_cast<std::size_t>(node) / inner];
          const double t01 = (x - first.front()) / (first.back() - first.front());
          const double f = sign * (mid + swing * std::sin(turns * M_PI * t01 + phase));
          table.set_value(node, static_cast<int>(c), f * original.value(node, static_cast<int>(c)));
        }
      }
      extras.push_back(
          {j, "perturbation_" + std::filesystem::path(original.path()).filename().string(), std::move(table)});
    }
  return extras;
}

std::vector<LocationValue> perturbation_locations(const machine::Model& model, double low, double high, unsigned seed) {
  std::mt19937 random(seed + 7919);  // (its own stream: the tables' stay as they were)
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<LocationValue> out;
  for (int j = 0; j < model.joint_count(); ++j) {
    const machine::Axis& axis = model.axes[static_cast<std::size_t>(j)];
    for (int c = 0; c < 6; ++c) {
      const double v = c < 3 ? axis.location_mm[c] : axis.location_rad[c - 3];
      if (v == 0.0) continue;
      const double sign = unit(random) < 0.5 ? -1.0 : 1.0;
      out.push_back({j, c, v * (1.0 + sign * (low + (high - low) * unit(random)))});
    }
  }
  return out;
}

}  // namespace vc::shop
