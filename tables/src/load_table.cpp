#include "vc/tables/load_table.hpp"

#include "vc/tables/csv.hpp"
#include "vc/tables/number_text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace vc::tables {
namespace {

struct HeaderCell {
  std::string name;
  std::string unit;
};

HeaderCell parse_header_cell(const std::string& path, int line, const CsvCell& cell) {
  const std::size_t open = cell.text.find('[');
  const std::size_t close = cell.text.find(']');
  if (open == std::string::npos || close != cell.text.size() - 1 || close < open)
    throw LoadError({path, line, cell.column},
                    "column '" + cell.text + "' needs a unit in brackets, as in x[mm] or EXX[um]");
  return {cell.text.substr(0, open), cell.text.substr(open + 1, close - open - 1)};
}

class TableReader {
 public:
  TableReader(std::string path, const TableOptions& options) : path_(std::move(path)), options_(options) {}

  ErrorTable read() {
    rows_ = read_csv_rows(path_, "table file");
    if (rows_.empty()) throw LoadError({path_}, "the table is empty: it needs a header line");
    read_header();
    read_values();
    read_grid_structure();
    check_periodic_ends();
    if (options_.interpolation == Interpolation::Cubic) check_cubic();
    return build();
  }

 private:
  void read_header() {
    const CsvRow& header = rows_.front();
    for (const CsvCell& cell : header.cells) {
      const HeaderCell h = parse_header_cell(path_, header.line, cell);
      const SourceLocation where{path_, header.line, cell.column};
      // A temperature input: anything in degC, or a lower-case name longer than an axis letter
      // whose unit is none of the lengths and angles (x_screw[C]: a temperature in the wrong unit,
      // not an unknown error symbol).
      const bool is_temperature =
          h.unit == "degC" ||
          (h.name.size() > 1 && std::islower(static_cast<unsigned char>(h.name[0])) && !find_unit(h.unit));
      if (is_temperature) {
        read_temperature_variable(h, where);
        continue;
      }
      const bool is_variable = h.name.size() == 1 && std::islower(static_cast<unsigned char>(h.name[0]));
      if (is_variable) {
        const char axis = static_cast<char>(std::toupper(static_cast<unsigned char>(h.name[0])));
        if (kAxisLetters.find(axis) == std::string_view::npos)
          throw LoadError(where, "'" + h.name + "' is not an axis letter (x y z a b c u v w)");
        if (!columns_.empty())
          throw LoadError(where, "grid column '" + h.name + "' after an error column: grid positions come first");
        if (h.unit != "mm" && h.unit != "deg")
          throw LoadError(where, "unit '" + h.unit + "' of grid column '" + h.name +
                                     "': positions are in mm (linear axis) or deg (rotary axis)");
        for (const GridVariable& g : grid_)
          if (g.axis == axis) throw LoadError(where, "grid column '" + h.name + "' appears twice");
        if (grid_.size() == ErrorTable::kMaxVariables)
          throw LoadError(where, "more than 3 grid columns: a table depends on at most 3 axes and temperatures");
        GridVariable& g = grid_.emplace_back();
        g.axis = axis;
        g.rotary = h.unit == "deg";
        g.periodic = false;
        g.where = where;
        continue;
      }
      const auto symbol = parse_error_symbol(h.name);
      if (!symbol || symbol->location)
        throw LoadError(where, "unknown error symbol '" + h.name +
                                   "': expected a grid axis (x, y, ...) or an ISO 230-1 component "
                                   "error such as EXX, EYX, EAX (E, component X Y Z A B C, axis)");
      const auto unit = find_unit(h.unit);
      if (!unit)
        throw LoadError(where, "unknown unit '" + h.unit + "' for " + h.name + " (use " +
                                   std::string(unit_names(symbol->quantity())) + ")");
      if (unit->quantity != symbol->quantity())
        throw LoadError(where, "unit '" + h.unit + "' does not fit " + h.name + ", which is " +
                                   (symbol->quantity() == Quantity::Length ? "a length (use " : "an angle (use ") +
                                   std::string(unit_names(symbol->quantity())) + ")");
      for (const Column& c : columns_)
        if (c.symbol.component == symbol->component && c.symbol.axis == symbol->axis)
          throw LoadError(where, "error column " + h.name + " appears twice");
      if (columns_.size() == ErrorTable::kMaxColumns) throw LoadError(where, "more than 6 error columns");
      double factor = unit->to_core;
      if (auto it = options_.scale.find(h.name); it != options_.scale.end()) factor *= it->second;
      columns_.push_back({*symbol, where});
      factors_.push_back(factor);
    }
    if (grid_.empty())
      throw LoadError({path_, header.line, 1}, "the first column must be a grid position, as in x[mm] or b[deg]");
    if (columns_.empty()) throw LoadError({path_, header.line, 1}, "the table has no error column (EXX[um], ...)");
  }

  // A grid column over a temperature input of the machine file, "x_screw[degC]" (the machine
  // file binds the name; here only its form).
  void read_temperature_variable(const HeaderCell& h, const SourceLocation& where) {
    if (h.unit != "degC")
      throw LoadError(where, "unit '" + h.unit + "' of temperature column '" + h.name +
                                 "': temperatures are in degC, as in " + h.name + "[degC]");
    const bool name_ok = !h.name.empty() && std::all_of(h.name.begin(), h.name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
    });
    if (!name_ok)
      throw LoadError(
          where, "temperature column '" + h.name + "': the name of a temperature input is letters, digits, '_' or '-'");
    if (!columns_.empty())
      throw LoadError(where,
                      "grid column '" + h.name + "' after an error column: grid positions and temperatures come first");
    for (const GridVariable& g : grid_)
      if (g.temperature == h.name) throw LoadError(where, "grid column '" + h.name + "' appears twice");
    if (grid_.size() == ErrorTable::kMaxVariables)
      throw LoadError(where, "more than 3 grid columns: a table depends on at most 3 axes and temperatures");
    GridVariable& g = grid_.emplace_back();
    g.axis = 0;
    g.rotary = false;
    g.periodic = false;
    g.temperature = h.name;
    g.where = where;
  }

  void read_values() {
    const std::size_t width = grid_.size() + columns_.size();
    for (std::size_t r = 1; r < rows_.size(); ++r) {
      const CsvRow& row = rows_[r];
      if (row.cells.size() < width) {
        const CsvCell& last = row.cells.back();
        throw LoadError({path_, row.line, last.column + static_cast<int>(last.text.size())},
                        "expected " + std::to_string(width) + " cells, found " + std::to_string(row.cells.size()) +
                            ": no value for " + header_name(row.cells.size()));
      }
      if (row.cells.size() > width)
        throw LoadError({path_, row.line, row.cells[width].column},
                        "expected " + std::to_string(width) + " cells, found " + std::to_string(row.cells.size()));
      std::vector<double> numbers;
      for (const CsvCell& cell : row.cells) numbers.push_back(csv_number(path_, row.line, cell));
      positions_.emplace_back(numbers.begin(), numbers.begin() + static_cast<long>(grid_.size()));
      for (std::size_t c = 0; c < columns_.size(); ++c) values_.push_back(numbers[grid_.size() + c] * factors_[c]);
      lines_.push_back(row.line);
    }
    if (positions_.size() < 2)
      throw LoadError({path_, rows_.front().line, 1}, "the table needs at least two rows of values");
  }

  std::string header_name(std::size_t column) const { return rows_.front().cells[column].text; }

  SourceLocation cell_at(std::size_t row, std::size_t column) const {
    return {path_, lines_[row], rows_[row + 1].cells[column].column};
  }

  // Works out the nodes of each variable from the rows (first variable slowest) and checks
  // that the rows form the full grid in that order.
  void read_grid_structure() {
    const std::size_t dims = grid_.size();
    std::vector<std::size_t> size(dims), stride(dims);
    std::size_t s = 1;
    for (std::size_t d = dims; d-- > 0;) {
      stride[d] = s;
      // Count the nodes of variable d: rows at multiples of its stride while the slower
      // variables keep their first value.
      std::size_t n = 0;
      for (std::size_t r = 0; r < positions_.size(); r += s) {
        bool same_slower = true;
        for (std::size_t e = 0; e < d; ++e) same_slower &= positions_[r][e] == positions_[0][e];
        if (!same_slower) break;
        ++n;
      }
      size[d] = n;
      for (std::size_t i = 0; i < n; ++i) grid_[d].nodes.push_back(positions_[i * s][d]);
      s *= n;
    }
    for (std::size_t d = 0; d < dims; ++d) check_monotonic(d, stride[d]);
    if (positions_.size() != s) {
      const std::size_t r = std::min(positions_.size(), s) - (positions_.size() > s ? 0 : 1);
      std::string shape;
      for (std::size_t d = 0; d < dims; ++d) shape += (d ? " x " : "") + std::to_string(size[d]);
      throw LoadError({path_, lines_[std::min(r, lines_.size() - 1)], 1},
                      "the rows do not form a full grid: a " + shape + " grid has " + std::to_string(s) +
                          " rows, the table has " + std::to_string(positions_.size()));
    }
    for (std::size_t r = 0; r < positions_.size(); ++r)
      for (std::size_t d = 0; d < dims; ++d) {
        const double expected = grid_[d].nodes[(r / stride[d]) % size[d]];
        if (positions_[r][d] != expected)
          throw LoadError(cell_at(r, d), "expected " + grid_[d].name() + " = " + significant_text(expected, 6) +
                                             " here: the rows must list the full grid, first "
                                             "column slowest");
      }
    stride_ = stride;
  }

  void check_monotonic(std::size_t d, std::size_t stride) const {
    const std::vector<double>& n = grid_[d].nodes;
    const std::string grid_hint =
        grid_.size() > 1 ? " (on a grid of several columns, the rows list every node, first column slowest)" : "";
    if (n.size() < 2) throw LoadError(grid_[d].where, "grid column needs at least two different positions");
    for (std::size_t i = 1; i < n.size(); ++i)
      if (n[i] == n[i - 1])
        throw LoadError(cell_at(i * stride, d), "position " + significant_text(n[i], 6) + " appears twice (lines " +
                                                    std::to_string(lines_[(i - 1) * stride]) + " and " +
                                                    std::to_string(lines_[i * stride]) + ")" + grid_hint);
    const bool increasing = n[1] > n[0];
    for (std::size_t i = 1; i < n.size(); ++i) {
      const bool ok = increasing ? n[i] > n[i - 1] : n[i] < n[i - 1];
      if (!ok)
        throw LoadError(cell_at(i * stride, d), "position " + significant_text(n[i], 6) + " does not continue the " +
                                                    (increasing ? "increasing" : "decreasing") + " order after " +
                                                    significant_text(n[i - 1], 6) +
                                                    ": grid positions must be strictly monotonic" + grid_hint);
    }
  }

  // A rotary grid spanning exactly 360 deg is periodic: its first and last values must agree.
  void check_periodic_ends() {
    for (std::size_t d = 0; d < grid_.size(); ++d) {
      GridVariable& g = grid_[d];
      if (!g.rotary || std::abs(std::abs(g.nodes.back() - g.nodes.front()) - 360.0) > 1e-9) continue;
      g.periodic = true;
      const std::size_t last = (g.nodes.size() - 1) * stride_[d];
      for (std::size_t r = 0; r < positions_.size(); ++r) {
        if ((r / stride_[d]) % g.nodes.size() != 0) continue;
        for (std::size_t c = 0; c < columns_.size(); ++c) {
          const double a = values_[r * columns_.size() + c];
          const double b = values_[(r + last) * columns_.size() + c];
          if (std::abs(a - b) > 1e-12 * std::max(1.0, std::abs(a)))
            throw LoadError(cell_at(r + last, grid_.size() + c),
                            "the grid spans 360 deg, so the table is periodic and this value must "
                            "equal the one on line " +
                                std::to_string(lines_[r]));
        }
      }
    }
  }

  void check_cubic() const {
    if (grid_.size() != 1)
      throw LoadError(grid_[1].where, "cubic interpolation is for 1-D tables; use linear on a cross-axis grid");
    if (grid_[0].periodic && grid_[0].nodes.size() < 5)
      throw LoadError(grid_[0].where, "a periodic cubic table needs at least 5 rows");
  }

  // Reorders every decreasing variable so that nodes increase, then checks the slopes of the
  // table as it will be interpolated.
  ErrorTable build() {
    const std::size_t ncol = columns_.size();
    std::vector<double> values(values_.size());
    std::vector<std::size_t> row_of_node(positions_.size());  // data row of each stored node
    for (std::size_t r = 0; r < positions_.size(); ++r) {
      std::size_t target = 0;
      for (std::size_t d = 0; d < grid_.size(); ++d) {
        const std::size_t n = grid_[d].nodes.size();
        std::size_t i = (r / stride_[d]) % n;
        if (grid_[d].nodes.front() > grid_[d].nodes.back()) i = n - 1 - i;
        target += i * stride_[d];
      }
      for (std::size_t c = 0; c < ncol; ++c) values[target * ncol + c] = values_[r * ncol + c];
      row_of_node[target] = r;
    }
    for (GridVariable& g : grid_)
      if (g.nodes.front() > g.nodes.back()) std::reverse(g.nodes.begin(), g.nodes.end());
    ErrorTable table(path_, grid_, columns_, std::move(values), options_.interpolation);
    check_slopes(table, row_of_node);
    return table;
  }

  // The slope limit holds anywhere on the grid (model.md): between neighbouring rows of a
  // linear table, inside every cell of a cubic spline (which overshoots its nodes). The
  // message names the two rows, in file order.
  void check_slopes(const ErrorTable& table, const std::vector<std::size_t>& row_of_node) const {
    const SteepestSlope s = steepest_slope(table, options_.limits);
    if (s.fraction <= 1.0) return;
    const std::size_t a = std::min(row_of_node[s.node], row_of_node[s.next]);
    const std::size_t b = std::max(row_of_node[s.node], row_of_node[s.next]);
    const bool length = columns_[s.column].symbol.quantity() == Quantity::Length;
    const double limit = length ? options_.limits.translation : options_.limits.rotation;
    const std::string slope = significant_text(s.fraction * limit, 6) + (length ? " mm/" : " rad/") +
                              (grid_[s.variable].rotary ? "deg" : "mm");
    const std::string lines = std::to_string(lines_[a]) + " and " + std::to_string(lines_[b]);
    const std::string why = ", above the limit " + significant_text(limit, 6) + " that keeps the correction invertible";
    throw LoadError(cell_at(b, grid_.size() + s.column), table.interpolation() == Interpolation::Cubic
                                                             ? "the cubic spline between lines " + lines +
                                                                   " reaches a slope of " + slope + why +
                                                                   " (use linear interpolation or smoother data)"
                                                             : "slope between lines " + lines + " is " + slope + why);
  }

  std::string path_;
  const TableOptions& options_;
  std::vector<CsvRow> rows_;
  std::vector<GridVariable> grid_;
  std::vector<Column> columns_;
  std::vector<double> factors_;
  std::vector<std::vector<double>> positions_;  // per data row: grid positions
  std::vector<double> values_;                  // per data row: error values, core units
  std::vector<int> lines_;                      // per data row: its line in the file
  std::vector<std::size_t> stride_;
};

}  // namespace

ErrorTable load_table(const std::string& path, const TableOptions& options) {
  return TableReader(path, options).read();
}

}  // namespace vc::tables
