// Table slopes against the limits that keep the correction map invertible (model.md,
// Correction): |d delta/dq| <= 0.01 mm per mm or per deg, |d eps/dq| <= 1e-4 rad per mm or deg.
// Only along axis positions: a temperature grid variable has no slope limit.
#pragma once

#include "vc/tables/error_table.hpp"

namespace vc::tables {

struct SlopeLimits {
  double translation = 0.01;  // mm per mm, or mm per deg
  double rotation = 1e-4;     // rad per mm, or rad per deg
};

// The steepest slope of the table as it is interpolated, as a fraction of its limit (1 = at
// the limit): between neighbouring nodes for linear tables, the largest slope of the spline
// inside each cell for cubic ones (a spline overshoots the node-to-node slopes).
struct SteepestSlope {
  double fraction = 0.0;
  int column = -1;    // column of the table where it occurs
  int node = -1;      // the two nodes bounding the segment or cell where it occurs
  int next = -1;      //   (node indices of the table, in its increasing order)
  int variable = -1;  // grid variable along which it occurs
};
SteepestSlope steepest_slope(const ErrorTable& table, const SlopeLimits& limits = {});

}  // namespace vc::tables
