#include "vc/identify/laser_runs.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

#include "instrument_csv.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::identify {
namespace {

std::optional<Direction> direction_of(const std::string& text) {
  const std::string t = lower(text);
  if (t == "+" || t == "up" || t == "forward" || t == "fwd" || t == "pos" || t == "positive") return Direction::Up;
  if (t == "-" || t == "down" || t == "backward" || t == "bwd" || t == "back" || t == "neg" || t == "negative")
    return Direction::Down;
  return std::nullopt;
}

}  // namespace

LaserRuns read_laser_runs(const std::string& path) {
  LaserRuns runs;
  runs.path = path;
  const std::vector<tables::CsvRow> rows = tables::read_csv_rows(path, "laser runs");
  if (rows.empty())
    throw LoadError({path}, "no header: target[mm],run,direction,deviation[um] (or target[mm],1+[um],1-[um],...)");
  runs.metadata = read_metadata(path);
  const tables::CsvRow& header = rows.front();
  const Header columns_read = read_header(path, header);
  const std::vector<HeaderCell>& cells = columns_read.cells;

  const auto find = [&](const std::string& name) { return columns_read.column(name); };
  const int target = find("target");
  if (target < 0) throw LoadError({path, header.line}, "missing column target[mm] (or target[deg] for a rotary axis)");
  const HeaderCell& t = cells[static_cast<std::size_t>(target)];
  if (!t.bracket)
    throw LoadError({path, header.line, header.cells[static_cast<std::size_t>(target)].column},
                    "the target needs its unit: target[mm] or target[deg]");
  runs.rotary = t.unit_name == "deg";
  if (t.unit_name != "deg" && t.unit_name != "mm")
    throw LoadError({path, header.line, header.cells[static_cast<std::size_t>(target)].column},
                    "targets are in mm (a linear axis) or deg (a rotary one)");

  // The deviation columns: one (long layout) or one per run and direction (wide layout).
  struct Column {
    int index;
    int run;                             // wide: its run; long: 0
    std::optional<Direction> direction;  // wide: its direction
    double to_core;
  };
  std::vector<Column> columns;
  int run_column = -1, direction_column = -1;
  std::optional<tables::Quantity> quantity;
  auto take_unit = [&](std::size_t i) {
    const HeaderCell& h = cells[i];
    if (!h.unit)
      throw LoadError({path, header.line, header.cells[i].column}, "a deviation needs its unit, e.g. deviation[um]");
    if (quantity && *quantity != h.unit->quantity)
      throw LoadError({path, header.line, header.cells[i].column}, "the deviations mix lengths and angles");
    quantity = h.unit->quantity;
    return h.unit->to_core;
  };
  if (const int d = find("deviation"); d >= 0) {
    run_column = find("run");
    direction_column = find("direction");
    if (run_column < 0 || direction_column < 0)
      throw LoadError({path, header.line},
                      "the long layout needs the columns run and direction (with target and deviation)");
    columns.push_back({d, 0, std::nullopt, take_unit(static_cast<std::size_t>(d))});
  } else {
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (static_cast<int>(i) == target) continue;
      std::string name = cells[i].name;
      if (name.rfind("run", 0) == 0) name = name.substr(3);
      const char sign = name.empty() ? ' ' : name.back();
      const std::string number = name.substr(0, name.empty() ? 0 : name.size() - 1);
      // At most 6 digits: a run's number is a count of runs, and std::stoi must not overflow.
      if ((sign != '+' && sign != '-') || number.empty() || number.size() > 6 ||
          !std::all_of(number.begin(), number.end(),
                       [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
        throw LoadError(
            {path, header.line, header.cells[i].column},
            "'" + header.cells[i].text + "' is neither a run column (1+[um], 1-[um], run2+[um], ...) nor target");
      columns.push_back(
          {static_cast<int>(i), std::stoi(number), sign == '+' ? Direction::Up : Direction::Down, take_unit(i)});
    }
    if (columns.empty())
      throw LoadError({path, header.line},
                      "no deviation columns: deviation[um] with run and direction, or 1+[um],1-[um],...");
  }
  runs.quantity = *quantity;

  for (std::size_t r = 1; r < rows.size(); ++r) {
    const tables::CsvRow& row = rows[r];
    if (row.cells.size() != header.cells.size())
      throw LoadError({path, row.line}, std::to_string(row.cells.size()) + " cells, the header has " +
                                            std::to_string(header.cells.size()));
    const double at = tables::csv_number(path, row.line, row.cells[static_cast<std::size_t>(target)]);
    for (const Column& c : columns) {
      const tables::CsvCell& cell = row.cells[static_cast<std::size_t>(c.index)];
      if (cell.text.empty() && !c.direction) throw LoadError({path, row.line, cell.column}, "no deviation");
      if (cell.text.empty()) continue;  // a wide layout's run that skipped this target
      Reading reading;
      reading.line = row.line;
      reading.target = at;
      reading.deviation = tables::csv_number(path, row.line, cell) * c.to_core;
      if (c.direction) {
        reading.run = c.run;
        reading.direction = *c.direction;
      } else {
        const tables::CsvCell& run = row.cells[static_cast<std::size_t>(run_column)];
        const double number = tables::csv_number(path, row.line, run);
        if (number != std::floor(number) || number < 0 || number > 1e6)
          throw LoadError({path, row.line, run.column}, "the run is a whole number");
        reading.run = static_cast<int>(number);
        const tables::CsvCell& way = row.cells[static_cast<std::size_t>(direction_column)];
        const auto d = direction_of(way.text);
        if (!d)
          throw LoadError({path, row.line, way.column},
                          "direction '" + way.text + "': +, -, up, down, forward or backward");
        reading.direction = *d;
      }
      runs.readings.push_back(reading);
    }
  }
  if (runs.readings.empty()) throw LoadError({path}, "no readings");
  return runs;
}

}  // namespace vc::identify
