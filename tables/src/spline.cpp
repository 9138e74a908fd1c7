#include "spline.hpp"

#include <cstddef>

namespace vc::tables {
namespace {

// Solves a tridiagonal system: sub[i] x[i-1] + diag[i] x[i] + super[i] x[i+1] = rhs[i]
// (Thomas algorithm; the systems here are diagonally dominant).
std::vector<double> solve_tridiagonal(const std::vector<double>& sub, const std::vector<double>& diag,
                                      const std::vector<double>& super, std::vector<double> rhs) {
  const std::size_t n = diag.size();
  std::vector<double> c(n, 0.0);
  double d = diag[0];
  c[0] = super[0] / d;
  rhs[0] /= d;
  for (std::size_t i = 1; i < n; ++i) {
    d = diag[i] - sub[i] * c[i - 1];
    c[i] = super[i] / d;
    rhs[i] = (rhs[i] - sub[i] * rhs[i - 1]) / d;
  }
  for (std::size_t i = n - 1; i-- > 0;) rhs[i] -= c[i] * rhs[i + 1];
  return rhs;
}

double slope(const std::vector<double>& x, const std::vector<double>& y, std::size_t i) {
  return (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
}

}  // namespace

std::vector<double> natural_spline_curvature(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  std::vector<double> m(n, 0.0);
  if (n < 3) return m;
  const std::size_t k = n - 2;  // interior nodes 1..n-2
  std::vector<double> sub(k), diag(k), super(k), rhs(k);
  for (std::size_t j = 0; j < k; ++j) {
    const std::size_t i = j + 1;
    const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
    sub[j] = h0;
    diag[j] = 2.0 * (h0 + h1);
    super[j] = h1;
    rhs[j] = 6.0 * (slope(x, y, i) - slope(x, y, i - 1));
  }
  sub[0] = 0.0;
  super[k - 1] = 0.0;
  const std::vector<double> inner = solve_tridiagonal(sub, diag, super, rhs);
  for (std::size_t j = 0; j < k; ++j) m[j + 1] = inner[j];
  return m;
}

std::vector<double> periodic_spline_curvature(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size() - 1;  // distinct nodes; node n repeats node 0
  std::vector<double> sub(n), diag(n), super(n), rhs(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t prev = (i + n - 1) % n;  // cell before node i, wrapping
    const double h0 = x[prev + 1] - x[prev], h1 = x[i + 1] - x[i];
    sub[i] = h0;
    diag[i] = 2.0 * (h0 + h1);
    super[i] = h1;
    rhs[i] = 6.0 * (slope(x, y, i) - slope(x, y, prev));
  }
  // Cyclic tridiagonal by Sherman-Morrison: corners sub[0] (row 0, column n-1) and
  // super[n-1] (row n-1, column 0).
  const double top_right = sub[0], bottom_left = super[n - 1];
  const double gamma = -diag[0];
  std::vector<double> d = diag;
  d[0] -= gamma;
  d[n - 1] -= bottom_left * top_right / gamma;
  sub[0] = 0.0;
  super[n - 1] = 0.0;
  const std::vector<double> xs = solve_tridiagonal(sub, d, super, rhs);
  std::vector<double> u(n, 0.0);
  u[0] = gamma;
  u[n - 1] = bottom_left;
  const std::vector<double> z = solve_tridiagonal(sub, d, super, u);
  const double factor = (xs[0] + top_right * xs[n - 1] / gamma) / (1.0 + z[0] + top_right * z[n - 1] / gamma);
  std::vector<double> m(n + 1);
  for (std::size_t i = 0; i < n; ++i) m[i] = xs[i] - factor * z[i];
  m[n] = m[0];
  return m;
}

}  // namespace vc::tables
