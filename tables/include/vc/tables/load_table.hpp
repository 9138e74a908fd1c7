// Reads and validates an error-table CSV file. Load time only (allocates, throws).
//
// Format (one header line, then one row per grid node; '#' starts a comment line):
//     x[mm],EXX[um],EYX[um],EZX[um],EAX[urad],EBX[urad],ECX[urad]
//     0,0,0,0,0,0,0
//     -10,0.4,...
// The first columns are grid variables: lower-case axis letters with their unit (mm for a
// linear axis, deg for a rotary one) or temperature inputs by name in degC ("x_screw[degC]",
// bound to the machine file's [temperatures] by the machine loader), up to three of them. The other
// columns are ISO 230-1 component errors (EXX, EYX, ...) with a length or angle unit
// (units.hpp). On a grid of several variables the rows list every node, first variable
// slowest. Each variable's positions are strictly increasing or strictly decreasing, any step.
#pragma once

#include <map>
#include <string>

#include "vc/tables/error_table.hpp"
#include "vc/tables/slope.hpp"

namespace vc::tables {

struct TableOptions {
  Interpolation interpolation = Interpolation::Linear;
  std::map<std::string, double> scale;  // symbol -> factor applied to that column
  SlopeLimits limits;
};

// Throws LoadError naming file, line and column of the first problem found.
ErrorTable load_table(const std::string& path, const TableOptions& options = {});

}  // namespace vc::tables
