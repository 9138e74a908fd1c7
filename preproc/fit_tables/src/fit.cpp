#include "vc/fit_tables/fit.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vc::fit_tables {
namespace {

// s_t per unknown: the RMS over the poses of the tip motion a unit value of its table makes.
Eigen::VectorXd table_scales(const LinearSystem& s, const TableSet& set) {
  Eigen::VectorXd column_sq = Eigen::VectorXd::Zero(s.unknowns);
  for (std::size_t e = 0; e < s.unknown.size(); ++e) column_sq[s.unknown[e]] += s.coefficient[e].squaredNorm();
  Eigen::VectorXd scale(s.unknowns);
  const double poses = std::max(1, s.poses());
  for (const Table& t : set.tables) {
    const double mean = column_sq.segment(t.first_unknown, t.unknowns()).sum() / (poses * t.unknowns());
    scale.segment(t.first_unknown, t.unknowns()).setConstant(mean > 0 ? std::sqrt(mean) : 1.0);
  }
  return scale;
}

// The regularisation's part of the normal equations.
Eigen::MatrixXd regularisation(const TableSet& set, const Eigen::VectorXd& scale, const FitOptions& o) {
  const int n = set.unknowns;
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) R(k, k) += o.ridge * o.ridge * scale[k] * scale[k];
  for (const Table& t : set.tables) {
    if (t.kind == TableKind::Squareness) continue;
    const int nodes = static_cast<int>(t.nodes.size());
    const double weight = o.smoothness * o.smoothness * scale[t.first_unknown] * scale[t.first_unknown];
    // Second differences x[k-1] - 2 x[k] + x[k+1] over the nodes (a modulo table wraps round).
    const int centres = t.modulo ? nodes - 1 : nodes - 2;
    for (int c = 0; c < centres; ++c) {
      const int k = t.modulo ? c : c + 1;
      const int u[3] = {t.unknown_of_node(t.modulo ? (k + nodes - 2) % (nodes - 1) : k - 1), t.unknown_of_node(k),
                        t.unknown_of_node(t.modulo ? (k + 1) % (nodes - 1) : k + 1)};
      const double d[3] = {1.0, -2.0, 1.0};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) R(u[a], u[b]) += weight * d[a] * d[b];
    }
  }
  return R;
}

// Solves the weighted least squares regularised towards `prior`: x = (A'WA + R)^-1 (R prior - A'We).
Eigen::VectorXd solve(const LinearSystem& s, const std::vector<double>& w, const Eigen::MatrixXd& R,
                      const Eigen::VectorXd& prior) {
  Eigen::MatrixXd H = R;
  Eigen::VectorXd g = -(R * prior);
  for (int p = 0; p < s.poses(); ++p) {
    const double wp = w[static_cast<std::size_t>(p)];
    if (wp == 0.0) continue;
    const int begin = s.start[static_cast<std::size_t>(p)], end = s.start[static_cast<std::size_t>(p) + 1];
    for (int a = begin; a < end; ++a) {
      const Eigen::Vector3d ca = wp * s.coefficient[static_cast<std::size_t>(a)];
      const int ua = s.unknown[static_cast<std::size_t>(a)];
      g[ua] += ca.dot(s.error_mm[static_cast<std::size_t>(p)]);
      for (int b = begin; b < end; ++b)
        H(ua, s.unknown[static_cast<std::size_t>(b)]) += ca.dot(s.coefficient[static_cast<std::size_t>(b)]);
    }
  }
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(H);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("the fit's normal equations could not be factorised");
  return -ldlt.solve(g);
}

std::vector<double> residual_norms(const LinearSystem& s, const Eigen::VectorXd& x) {
  std::vector<double> r(static_cast<std::size_t>(s.poses()));
  for (int p = 0; p < s.poses(); ++p) r[static_cast<std::size_t>(p)] = s.residual(p, x).norm();
  return r;
}

}  // namespace

FitResult fit(const LinearSystem& system, const TableSet& set, const FitOptions& options,
              const Eigen::VectorXd& prior) {
  if (system.poses() == 0) throw std::invalid_argument("no poses to fit the tables on");
  if (prior.size() != set.unknowns) throw std::invalid_argument("fit: the prior has the wrong size");
  FitResult result;
  if (set.unknowns == 0) {
    result.x = Eigen::VectorXd::Zero(0);
    return result;
  }
  const Eigen::MatrixXd R = regularisation(set, table_scales(system, set), options);
  std::vector<double> w(static_cast<std::size_t>(system.poses()), 1.0 / system.poses());

  result.x = solve(system, w, R, prior);
  result.iterations = 1;
  std::vector<double> r = residual_norms(system, result.x);
  result.linear_max_mm = *std::max_element(r.begin(), r.end());
  if (options.criterion == Criterion::LeastSquares) return result;

  // Lawson: the weights move onto the poses with the largest error.
  for (int it = 1; it < options.minimax_iterations; ++it) {
    double bound = 0.0, sum = 0.0;
    for (std::size_t p = 0; p < w.size(); ++p) bound += w[p] * r[p] * r[p];
    result.lower_bound_mm = std::max(result.lower_bound_mm, std::sqrt(bound));
    if (result.linear_max_mm <= (1.0 + options.minimax_gap) * result.lower_bound_mm) break;
    for (std::size_t p = 0; p < w.size(); ++p) sum += (w[p] *= r[p]);
    if (!(sum > 0)) break;  // every residual zero
    const double floor = 1e-14 / static_cast<double>(w.size());
    for (double& wp : w) wp = wp / sum < floor ? 0.0 : wp / sum;  // gone for good (Lawson's weights only shrink there)
    const Eigen::VectorXd x = solve(system, w, R, prior);
    ++result.iterations;
    r = residual_norms(system, x);
    const double worst = *std::max_element(r.begin(), r.end());
    if (worst < result.linear_max_mm) {
      result.linear_max_mm = worst;
      result.x = x;
    }
  }
  return result;
}

}  // namespace vc::fit_tables
