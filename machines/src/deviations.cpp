#include "vc/machine/deviations.hpp"

#include <algorithm>
#include <stdexcept>

namespace vc::machine {
namespace {

std::string location_symbol(int component, char line) { return tables::ErrorSymbol{component, line, true}.name(); }

// Location errors of a line: d0 (mm) and e0 (rad), components X Y Z A B C.
double& location_component(Eigen::Vector3d& d0, Eigen::Vector3d& e0, int k) { return k < 3 ? d0[k] : e0[k - 3]; }

void list_locations(Eigen::Vector3d d0, Eigen::Vector3d e0, char line, std::vector<std::string>& out) {
  for (int k = 0; k < 6; ++k)
    if (location_component(d0, e0, k) != 0.0) out.push_back(location_symbol(k, line));
}

template <typename KeepFn>
void zero_locations(Eigen::Vector3d& d0, Eigen::Vector3d& e0, char line, const KeepFn& kept) {
  for (int k = 0; k < 6; ++k)
    if (!kept(location_symbol(k, line))) location_component(d0, e0, k) = 0.0;
}

}  // namespace

std::vector<std::string> deviation_symbols(const Model& model) {
  std::vector<std::string> out;
  for (const Axis& axis : model.axes) {
    for (int t : axis.tables)
      for (const auto& c : model.tables[t].table.columns()) out.push_back(c.symbol.name());
    list_locations(axis.location_mm, axis.location_rad, axis.letter, out);
  }
  list_locations(model.spindle.location_mm, model.spindle.location_rad, 'S', out);
  return out;
}

Model keep_only(const Model& model, const std::vector<std::string>& keep) {
  for (const std::string& s : keep) {
    const auto symbol = tables::parse_error_symbol(s);
    if (!symbol || (symbol->axis != 'S' && model.joint_of(symbol->axis) < 0))
      throw std::invalid_argument(
          "'" + s +
          "' is not a deviation of this machine (component errors such as EXX, location errors such as EC0Y)");
  }
  auto kept = [&](const std::string& s) { return std::find(keep.begin(), keep.end(), s) != keep.end(); };

  Model out = model;
  for (Axis& axis : out.axes) {
    zero_locations(axis.location_mm, axis.location_rad, axis.letter, kept);
    axis.real_base = line_placement(axis.pole_mm, axis.location_mm, axis.location_rad);
  }
  Spindle& spindle = out.spindle;
  zero_locations(spindle.location_mm, spindle.location_rad, 'S', kept);
  spindle.real = line_placement(spindle.gauge_point_mm, spindle.location_mm, spindle.location_rad);
  for (BoundTable& bound : out.tables) {
    tables::ErrorTable& table = bound.table;
    const auto& columns = table.columns();
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (kept(columns[c].symbol.name())) continue;
      for (int node = 0; node < table.node_count(); ++node) table.set_value(node, static_cast<int>(c), 0.0);
    }
  }
  return out;
}

}  // namespace vc::machine
