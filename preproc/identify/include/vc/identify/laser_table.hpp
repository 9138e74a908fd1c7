// What an ISO 230-2 evaluation puts into an error table (volcomp identify laser): the value
// at each target (the mean bidirectional deviation, or one direction's mean), its standard
// uncertainty, and the table's rows, where a rotary axis measured over exactly one turn holds
// one value at 0 and 360 deg (one position: the loader requires it of a periodic table).
#pragma once

#include <vector>

#include "vc/identify/iso230_2.hpp"

namespace vc::identify {

enum class TableValue { Bidirectional, Up, Down };  // --direction both, up, down

// The value the table takes at a target (mm or rad).
double table_value(const TargetStatistics& t, TableValue which);

// Its standard uncertainty: of a mean of n runs, s / sqrt(n); the bidirectional mean, half
// the two directions' in quadrature.
double table_value_uncertainty(const TargetStatistics& t, const Iso230_2& e, TableValue which);

// True when a rotary axis's targets (more than two) span exactly 360 deg.
bool spans_one_turn(const Iso230_2& e, bool rotary);

struct TableRow {
  double target = 0.0;  // mm or deg
  double value = 0.0;   // mm or rad
  bool operator<(const TableRow& o) const { return target < o.target || (target == o.target && value < o.value); }
};

// One row per target, ascending; over one turn the first and last take the mean of the two.
std::vector<TableRow> laser_table_rows(const Iso230_2& e, bool rotary, TableValue which);

}  // namespace vc::identify
