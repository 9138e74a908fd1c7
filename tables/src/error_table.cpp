#include "vc/tables/error_table.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "spline.hpp"

namespace vc::tables {
namespace {

// Where a position falls on one grid variable: cell index, fraction in the cell and its rate.
struct Cell {
  int index;     // left node of the cell
  double t;      // 0..1 within the cell
  double h;      // cell width
  double dt_dx;  // d t / d position; 0 where the table holds its end value
};

// Inline and without division: this runs for every table of every axis in every chain walk.
// On an evenly spaced grid it reads the grid variable alone, not its nodes (fewer cache lines
// in the servo thread). (On a cell boundary the cell may be either neighbour: both give the
// node's value.)
inline Cell locate(const GridVariable& g, double x) noexcept {
  const int last = static_cast<int>(g.nodes.size()) - 1;
  const double step = g.uniform_step;
  if (g.periodic) {
    x = g.first + std::fmod(x - g.first, 360.0);
    if (x < g.first) x += 360.0;
  } else if (x < g.first) {
    return {0, 0.0, step > 0.0 ? step : g.nodes[1] - g.nodes[0], 0.0};
  } else if (x > g.last) {
    return {last - 1, 1.0, step > 0.0 ? step : g.nodes[last] - g.nodes[last - 1], 0.0};
  }
  if (step > 0.0) {
    const double u = (x - g.first) * g.inverse_step;
    // Converted only inside [0, last): a NaN position (a broken input upstream) must give a NaN
    // value, not undefined behaviour in the conversion.
    const int i = u >= 0.0 && u < last ? static_cast<int>(u) : (u >= last ? last - 1 : 0);
    return {i, u - i, step, g.inverse_step};
  }
  const std::vector<double>& n = g.nodes;
  const int i = std::clamp(static_cast<int>(std::upper_bound(n.begin(), n.end(), x) - n.begin()) - 1, 0, last - 1);
  const double inverse = g.inverse_width[static_cast<std::size_t>(i)];
  return {i, (x - n[i]) * inverse, n[i + 1] - n[i], inverse};
}

}  // namespace

std::string GridVariable::name() const {
  if (is_temperature()) return temperature;
  return std::string(1, static_cast<char>(std::tolower(static_cast<unsigned char>(axis))));
}

ErrorTable::ErrorTable(std::string path, std::vector<GridVariable> grid, std::vector<Column> columns,
                       std::vector<double> values, Interpolation interpolation)
    : grid_(std::move(grid)),
      columns_(std::move(columns)),
      values_(std::move(values)),
      interpolation_(interpolation),
      path_(std::move(path)) {
  for (GridVariable& g : grid_) {
    const double step = (g.nodes.back() - g.nodes.front()) / static_cast<double>(g.nodes.size() - 1);
    bool uniform = true;
    for (std::size_t i = 0; i < g.nodes.size(); ++i)
      uniform &= std::abs(g.nodes[i] - (g.nodes.front() + step * static_cast<double>(i))) <= 1e-12 * step;
    g.uniform_step = uniform ? step : 0.0;
    g.inverse_step = uniform ? 1.0 / step : 0.0;
    g.first = g.nodes.front();
    g.last = g.nodes.back();
    g.inverse_width.resize(g.nodes.size() - 1);
    for (std::size_t i = 0; i + 1 < g.nodes.size(); ++i) g.inverse_width[i] = 1.0 / (g.nodes[i + 1] - g.nodes[i]);
  }
  refresh();
}

void ErrorTable::set_value(int node, int column, double value) {
  values_[static_cast<std::size_t>(node) * columns_.size() + static_cast<std::size_t>(column)] = value;
  if (!by_component_.empty()) by_component_[component_slot(node, column)] = value;
  if (interpolation_ == Interpolation::Cubic) refresh();  // the spline's curvatures depend on every node
}

void ErrorTable::refresh() {
  if (interpolation_ == Interpolation::Linear && grid_.size() == 1) {
    const int ncol = static_cast<int>(columns_.size());
    by_component_.assign(static_cast<std::size_t>(node_count() * kMaxColumns), 0.0);
    for (int node = 0; node < node_count(); ++node)
      for (int c = 0; c < ncol; ++c)
        by_component_[component_slot(node, c)] = values_[static_cast<std::size_t>(node * ncol + c)];
  }
  if (interpolation_ != Interpolation::Cubic) return;
  const GridVariable& g = grid_.front();
  const int n = static_cast<int>(g.nodes.size());
  const int ncol = static_cast<int>(columns_.size());
  curvature_.assign(values_.size(), 0.0);
  std::vector<double> y(n), m;
  for (int c = 0; c < ncol; ++c) {
    for (int i = 0; i < n; ++i) y[i] = values_[i * ncol + c];
    m = g.periodic ? periodic_spline_curvature(g.nodes, y) : natural_spline_curvature(g.nodes, y);
    for (int i = 0; i < n; ++i) curvature_[i * ncol + c] = m[i];
  }
}

void ErrorTable::evaluate(const double* positions, Sample& out, bool with_slopes) const noexcept {
  if (interpolation_ == Interpolation::Cubic)
    evaluate_cubic(positions[0], out, with_slopes);
  else
    evaluate_linear(positions, out, with_slopes);
}

void ErrorTable::evaluate_linear(const double* positions, Sample& out, bool with_slopes) const noexcept {
  const int dims = static_cast<int>(grid_.size());
  const int ncol = static_cast<int>(columns_.size());
  if (dims == 1) {  // the common table: one straight piece between two nodes
    const Cell cell = locate(grid_.front(), positions[0]);
    const double* v0 = &values_[static_cast<std::size_t>(cell.index * ncol)];
    const double* v1 = v0 + ncol;
    for (int c = 0; c < ncol; ++c) out.value[c] = (1.0 - cell.t) * v0[c] + cell.t * v1[c];
    if (!with_slopes) return;
    for (int c = 0; c < ncol; ++c) out.slope[c] = {(v1[c] - v0[c]) * cell.dt_dx, 0.0, 0.0};
    return;
  }
  std::array<Cell, kMaxVariables> cell{};
  std::array<int, kMaxVariables> stride{};
  int s = 1;
  for (int d = dims - 1; d >= 0; --d) {
    cell[d] = locate(grid_[d], positions[d]);
    stride[d] = s;
    s *= static_cast<int>(grid_[d].nodes.size());
  }
  for (int c = 0; c < ncol; ++c) {
    out.value[c] = 0.0;
    if (with_slopes) out.slope[c] = {0.0, 0.0, 0.0};
  }
  // Multilinear: sum over the 2^dims corners of the cell.
  for (int corner = 0; corner < (1 << dims); ++corner) {
    int node = 0;
    double weight = 1.0;
    std::array<double, kMaxVariables> dweight{1.0, 1.0, 1.0};
    for (int d = 0; d < dims; ++d) {
      const bool upper = (corner >> d) & 1;
      node += (cell[d].index + upper) * stride[d];
      const double w = upper ? cell[d].t : 1.0 - cell[d].t;
      const double dw = upper ? cell[d].dt_dx : -cell[d].dt_dx;
      for (int e = 0; e < dims; ++e) dweight[e] *= (e == d) ? dw : w;
      weight *= w;
    }
    const double* v = &values_[node * ncol];
    for (int c = 0; c < ncol; ++c) out.value[c] += weight * v[c];
    if (with_slopes)
      for (int c = 0; c < ncol; ++c)
        for (int d = 0; d < dims; ++d) out.slope[c][d] += dweight[d] * v[c];
  }
}

void ErrorTable::add_components(const double* positions, std::array<double, kMaxColumns>& components) const noexcept {
  if (!by_component_.empty()) {  // as evaluate_linear's 1-D case, on every component at once
    const Cell cell = locate(grid_.front(), positions[0]);
    const double* v0 = &by_component_[static_cast<std::size_t>(cell.index * kMaxColumns)];
    const double* v1 = v0 + kMaxColumns;
    for (int k = 0; k < kMaxColumns; ++k) components[k] += (1.0 - cell.t) * v0[k] + cell.t * v1[k];
    return;
  }
  Sample sample;
  evaluate(positions, sample, false);
  for (std::size_t c = 0; c < columns_.size(); ++c) components[columns_[c].symbol.component] += sample.value[c];
}

void ErrorTable::evaluate_cubic(double position, Sample& out, bool with_slopes) const noexcept {
  const Cell cell = locate(grid_.front(), position);
  const int ncol = static_cast<int>(columns_.size());
  const int i = cell.index;
  const double h = cell.h, a = 1.0 - cell.t, b = cell.t, dt_dx = cell.dt_dx;
  for (int c = 0; c < ncol; ++c) {
    const double y0 = values_[i * ncol + c], y1 = values_[(i + 1) * ncol + c];
    const double m0 = curvature_[i * ncol + c], m1 = curvature_[(i + 1) * ncol + c];
    // Standard cubic spline segment in terms of the end values and curvatures.
    out.value[c] = a * y0 + b * y1 + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6.0;
    if (!with_slopes) continue;
    const double dvalue_dt = y1 - y0 + ((1.0 - 3.0 * a * a) * m0 + (3.0 * b * b - 1.0) * m1) * h * h / 6.0;
    out.slope[c] = {dvalue_dt * dt_dx, 0.0, 0.0};
  }
}

}  // namespace vc::tables
