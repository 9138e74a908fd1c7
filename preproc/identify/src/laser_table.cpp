#include "vc/identify/laser_table.hpp"

#include <algorithm>
#include <cmath>

namespace vc::identify {

double table_value(const TargetStatistics& t, TableValue which) {
  return which == TableValue::Up ? t.mean_up : which == TableValue::Down ? t.mean_down : t.mean;
}

double table_value_uncertainty(const TargetStatistics& t, const Iso230_2& e, TableValue which) {
  const double up = t.s_up / std::sqrt(static_cast<double>(e.runs_up));
  const double down = t.s_down / std::sqrt(static_cast<double>(e.runs_down));
  return which == TableValue::Up ? up : which == TableValue::Down ? down : std::hypot(up, down) / 2;
}

bool spans_one_turn(const Iso230_2& e, bool rotary) {
  return rotary && e.targets.size() > 2 && std::abs(e.targets.back().target - e.targets.front().target - 360.0) < 1e-9;
}

std::vector<TableRow> laser_table_rows(const Iso230_2& e, bool rotary, TableValue which) {
  std::vector<TableRow> rows;
  for (const TargetStatistics& t : e.targets) rows.push_back({t.target, table_value(t, which)});
  if (spans_one_turn(e, rotary)) rows.front().value = rows.back().value = (rows.front().value + rows.back().value) / 2;
  std::sort(rows.begin(), rows.end());
  return rows;
}

}  // namespace vc::identify
