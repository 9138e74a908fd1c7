// One error table: component errors of one axis sampled on a grid of 1 to 3 variables: axis
// positions and temperatures (a temperature input of the machine file, in degC).
//
// Errors are stored as error = actual - nominal (ISO 230-1), in core units (mm, rad), after
// the unit conversion and scale factors of the loader. Grid positions are in the variable's
// axis unit (mm for a linear axis, deg for a rotary one), strictly increasing.
//
// Lookup (evaluate) returns the value and the slope along each grid variable, because the
// Newton correction needs both. Outside the grid a table holds its end values (slope 0),
// except a rotary grid spanning exactly 360 deg, which is periodic (model.md, One axis).
// Interpolation is linear (multilinear on 2-D and 3-D grids), or a C2 cubic spline on 1-D
// tables (natural ends; periodic ends on a periodic grid).
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "vc/tables/source_error.hpp"
#include "vc/tables/symbols.hpp"

namespace vc::tables {

enum class Interpolation { Linear, Cubic };

struct GridVariable {
  // What a lookup reads comes first (one cache line: the servo thread's cycle touches every
  // table's, and between cycles other threads evict them).
  std::vector<double> nodes;  // strictly increasing, size >= 2
  double uniform_step = 0.0;  // > 0 if the nodes are equally spaced (lookup without the nodes)
  // 1 / uniform_step and 1 / (width of each cell): lookups multiply, they do not divide.
  double inverse_step = 0.0;
  double first = 0.0, last = 0.0;  // nodes.front(), nodes.back()
  bool periodic;                   // rotary grid spanning exactly 360 deg
  bool rotary;                     // positions in deg (else mm)
  char axis;                       // upper-case axis letter whose position this is; 0 for a temperature
  std::vector<double> inverse_width;
  std::string temperature;  // a temperature (degC): the input's name, as in the header; else empty
  SourceLocation where;     // header cell

  bool is_temperature() const { return !temperature.empty(); }
  // The header's name: "x" for an axis position, the input's name for a temperature.
  std::string name() const;
  std::string_view unit() const { return is_temperature() ? "degC" : rotary ? "deg" : "mm"; }
};

struct Column {
  ErrorSymbol symbol;
  SourceLocation where;  // header cell
};

class ErrorTable {
 public:
  static constexpr int kMaxVariables = 3;
  static constexpr int kMaxColumns = 6;

  // Result of one lookup, per column: value (mm or rad) and slope per grid variable
  // (per mm or per deg).
  struct Sample {
    std::array<double, kMaxColumns> value;
    std::array<std::array<double, kMaxVariables>, kMaxColumns> slope;
  };

  // Builds a table from node-major samples (values[node * columns + column], nodes in
  // row-major order, first variable slowest); precomputes the cubic spline if asked.
  ErrorTable(std::string path, std::vector<GridVariable> grid, std::vector<Column> columns, std::vector<double> values,
             Interpolation interpolation);

  // Value and (if with_slopes) slope of every column at the positions of the grid variables
  // (positions[i] belongs to grid()[i]).
  // Real-time: no allocation, no locks, O(1) per variable on an evenly spaced grid,
  // O(log nodes) otherwise.
  void evaluate(const double* positions, Sample& out, bool with_slopes = true) const noexcept;

  // The values alone, added to `components` by error component (X, Y, Z: mm; A, B, C: rad;
  // a component without a column gets nothing): the lookup of the real machine's pose,
  // without the mapping of columns to components. The same arithmetic as evaluate().
  void add_components(const double* positions, std::array<double, kMaxColumns>& components) const noexcept;

  const std::string& path() const { return path_; }
  const std::vector<GridVariable>& grid() const { return grid_; }
  const std::vector<Column>& columns() const { return columns_; }
  Interpolation interpolation() const { return interpolation_; }
  int node_count() const { return static_cast<int>(values_.size() / columns_.size()); }
  // Sample at a node, core units (for validation, re-referencing and reports).
  double value(int node, int column) const { return values_[node * columns_.size() + column]; }
  // Changes a sample (core units); what is derived from the samples follows.
  void set_value(int node, int column, double value);
  // Cubic tables: second derivative of the spline at a node (per unit position squared).
  double curvature(int node, int column) const { return curvature_[node * columns_.size() + column]; }

 private:
  void refresh();  // derived data from all samples
  // Where a sample's copy lies in by_component_.
  std::size_t component_slot(int node, int column) const {
    return static_cast<std::size_t>(node * kMaxColumns + columns_[static_cast<std::size_t>(column)].symbol.component);
  }
  void evaluate_linear(const double* positions, Sample& out, bool with_slopes) const noexcept;
  void evaluate_cubic(double position, Sample& out, bool with_slopes) const noexcept;

  // What a lookup of the real machine's pose reads first (add_components: one cache line).
  std::vector<double> by_component_;  // linear 1-D: the values, kMaxColumns per node by component
  std::vector<GridVariable> grid_;
  std::vector<Column> columns_;
  std::vector<double> values_;
  std::vector<double> curvature_;  // cubic: second derivative at each node, same layout
  Interpolation interpolation_;
  std::string path_;
};

}  // namespace vc::tables
