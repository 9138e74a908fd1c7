// Second derivatives of C2 cubic splines through (x, y), x strictly increasing.
// Load time only: allocates.
#pragma once

#include <vector>

namespace vc::tables {

// Natural ends (second derivative 0 at both ends).
std::vector<double> natural_spline_curvature(const std::vector<double>& x, const std::vector<double>& y);

// Periodic: y.front() == y.back() and the spline continues over the end with period
// x.back() - x.front(). Needs at least 4 points.
std::vector<double> periodic_spline_curvature(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace vc::tables
