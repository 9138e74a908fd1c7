// Table slopes against the limits that keep the correction map invertible (model.md,
// Correction): |d delta/dq| <= 0.01 mm per mm or per deg, |d eps/dq| <= 1e-4 rad per mm or deg.
#pragma once

#include "vc/tables/error_table.hpp"

namespace vc::tables {

struct SlopeLimits {
  double translation = 0.01;  // mm per mm, or mm per deg
  double rotation = 1e-4;     // rad per mm, or rad per deg
};

// The steepest slope between neighbouring nodes, as a fraction of its limit (1 = at the limit).
struct SteepestSlope {
  double fraction = 0.0;
  int column = -1;  // column of the table where it occurs
};
SteepestSlope steepest_slope(const ErrorTable& table, const SlopeLimits& limits = {});

}  // namespace vc::tables
