// The modified method's fit (seeds/000 sec. 3.3.3.4): the table values x that make the tip
// error over the poses smallest, all tables together, on the linearised model
// (linear_system.hpp):
//   least squares:  min  sum_p w_p |r_p(x)|^2 + regularisation,  w_p = 1 / poses
//   minimax:        min  max_p |r_p(x)|  (criterion M), by Lawson's iteratively reweighted
//                   least squares: w_p <- w_p |r_p| / sum, the best iterate kept; each weighted
//                   solution's sqrt(sum w_p |r_p|^2) is a lower bound of the minimax, so the
//                   iteration stops when the best M is within `minimax_gap` of it.
// Each solve is one LDLT of the normal equations (unknowns ~ 100: small and dense).
//
// Regularisation towards a prior p (the usual practice's values): d = x - p, each term scaled
// per table by s_t, the RMS tip motion (mm) its unit value makes over the poses, so that the
// weights mean the same for mm, deg and ratio tables:
//   ridge       (ridge * s_t * d_k)^2 for every value: with one tool length the 14-table set
//               has an exact null direction (a constant B offset, a rotation made of X(z) and
//               Z(x) terms and X/Z offsets, the finding: unregularised, the fit drifts
//               along it, 1-3 mm off at other tool lengths); the ridge holds it near the usual
//               practice (B's offset corrected by B, as measured);
//   smoothness  (smoothness * s_t * second difference of d over the nodes)^2: a node no pose
//               lies next to (fewer grid levels than nodes, --rotary off the nodes) takes the
//               smooth continuation of its neighbours' departure from the prior.
// Both are small against the data (a 10 um RMS departure costs 1e-4 of a 10 um RMS error).
// Measured on the MC-300, 14 tables fitted at L = 100 mm alone (M at L = 100 / at L = 0 and
// 200): ridge 1e-3: 19.3 / 226 um (the XZ squareness drifts to 100 arcsec); 1e-2: 19.0 / 36.4
// um (11 arcsec); 3e-2: 19.1 / 34.9 um; pulling towards zero instead of the usual practice:
// 38.7 um at 1e-2. Fitted at L = 0, 100, 200 the ridge changes nothing measurable.
#pragma once

#include <Eigen/Core>

#include "vc/fit_tables/linear_system.hpp"

namespace vc::fit_tables {

enum class Criterion { LeastSquares, Minimax };

struct FitOptions {
  Criterion criterion = Criterion::Minimax;
  double ridge = 1e-2;
  double smoothness = 1e-2;
  int minimax_iterations = 400;  // Lawson steps at most
  double minimax_gap = 0.005;    // stop when M <= (1 + gap) * the lower bound
};

struct FitResult {
  Eigen::VectorXd x;
  // Of the linearised model, for the optimiser's own report only (the figures are computed on
  // the nonlinear model): the largest |r| at the solution and, for minimax, the lower bound.
  double linear_max_mm = 0.0;
  double lower_bound_mm = 0.0;
  int iterations = 0;  // solves
};

// `prior`: the values the regularisation pulls towards (set.unknowns of them).
FitResult fit(const LinearSystem& system, const TableSet& set, const FitOptions& options, const Eigen::VectorXd& prior);

}  // namespace vc::fit_tables
