// libFuzzer target: any bytes as an error-table CSV through load_table, with linear and with
// cubic interpolation (the spline's own rules). Refusal (vc::LoadError) is the expected answer
// to bad input; a crash, a hang, a sanitizer report, any other exception or an accepted table
// that breaks what error_table.hpp promises is a finding: 1 to 3 grid variables, each with
// at least 2 strictly increasing finite nodes, 1 to 6 columns, finite samples, and a lookup
// at a node giving that node's samples (both interpolations pass through the nodes).
#include <algorithm>
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "vc/tables/load_table.hpp"

namespace {

using vc::tables::ErrorTable;

void check(const ErrorTable& t) {
  const auto& grid = t.grid();
  if (grid.empty() || grid.size() > ErrorTable::kMaxVariables)
    vc::fuzz::finding("accepted a grid of " + std::to_string(grid.size()) + " variables");
  if (t.columns().empty() || t.columns().size() > ErrorTable::kMaxColumns)
    vc::fuzz::finding("accepted " + std::to_string(t.columns().size()) + " columns");
  std::size_t nodes = 1;
  for (const auto& v : grid) {
    if (v.nodes.size() < 2) vc::fuzz::finding("a grid variable of fewer than 2 nodes");
    for (std::size_t i = 0; i < v.nodes.size(); ++i)
      if (!std::isfinite(v.nodes[i]) || (i > 0 && !(v.nodes[i - 1] < v.nodes[i])))
        vc::fuzz::finding("grid nodes not finite and strictly increasing");
    nodes *= v.nodes.size();
  }
  if (static_cast<std::size_t>(t.node_count()) != nodes)
    vc::fuzz::finding("sample count differs from the grid's nodes");
  const int columns = static_cast<int>(t.columns().size());
  double largest = 0.0;
  for (int n = 0; n < t.node_count(); ++n)
    for (int c = 0; c < columns; ++c) {
      if (!std::isfinite(t.value(n, c))) vc::fuzz::finding("a non-finite sample");
      largest = std::max(largest, std::abs(t.value(n, c)));
    }
  // Node n's position on each variable: row-major, the first variable slowest.
  ErrorTable::Sample sample;
  for (int n = 0; n < t.node_count(); ++n) {
    double at[ErrorTable::kMaxVariables] = {};
    std::size_t rest = static_cast<std::size_t>(n);
    for (std::size_t v = grid.size(); v-- > 0;) {
      at[v] = grid[v].nodes[rest % grid[v].nodes.size()];
      rest /= grid[v].nodes.size();
    }
    t.evaluate(at, sample);
    for (int c = 0; c < columns; ++c)
      if (!(std::abs(sample.value[static_cast<std::size_t>(c)] - t.value(n, c)) <= 1e-9 * largest + 1e-12))
        vc::fuzz::finding("the lookup at node " + std::to_string(n) + " is not its sample (column " +
                          std::to_string(c) + ")");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (vc::fuzz::scratch() / "input.csv").string();
  vc::fuzz::write_file(path, vc::fuzz::text_of(data, size));
  for (const auto interpolation : {vc::tables::Interpolation::Linear, vc::tables::Interpolation::Cubic}) {
    vc::tables::TableOptions options;
    options.interpolation = interpolation;
    try {
      check(vc::tables::load_table(path, options));
    } catch (const vc::LoadError&) {
    } catch (const std::exception& e) {
      vc::fuzz::finding(std::string("not a vc::LoadError: ") + e.what());
    }
  }
  return 0;
}
