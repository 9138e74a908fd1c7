// LU with partial pivoting of the Newton solvers' small systems (3 to 6 unknowns), on plain
// arrays. Eigen's PartialPivLU of a dynamic-size matrix (SquareMatrix) dispatches to its
// blocked code for any size and took a third of the forward kinematics' time; this is the
// same algorithm (the largest pivot of each column) written out for n <= kMaxAxes.
// Real-time: no allocation.
#pragma once

#include <cmath>
#include <utility>

#include "vc/machine/correction_equations.hpp"

namespace vc::machine {

class SmallLu {
 public:
  // Factors `a` (n x n); false if a pivot is zero or not a number (a singular Jacobian).
  bool compute(const SquareMatrix& a) noexcept {
    n_ = static_cast<int>(a.rows());
    for (int r = 0; r < n_; ++r)
      for (int c = 0; c < n_; ++c) m_[r][c] = a(r, c);
    for (int c = 0; c < n_; ++c) {
      int pivot = c;
      for (int r = c + 1; r < n_; ++r)
        if (std::abs(m_[r][c]) > std::abs(m_[pivot][c])) pivot = r;
      row_[c] = pivot;
      if (pivot != c)
        for (int k = 0; k < n_; ++k) std::swap(m_[c][k], m_[pivot][k]);
      if (!(std::abs(m_[c][c]) > 0.0) || !std::isfinite(m_[c][c])) return ok_ = false;
      inverse_pivot_[c] = 1.0 / m_[c][c];
      for (int r = c + 1; r < n_; ++r) {
        const double f = m_[r][c] *= inverse_pivot_[c];  // L below the diagonal
        for (int k = c + 1; k < n_; ++k) m_[r][k] -= f * m_[c][k];
      }
    }
    return ok_ = true;
  }
  bool ok() const noexcept { return ok_; }

  // x with A x = b (after a successful compute()). In a local array: sums stay in registers
  // (written into the result vector, each step waited for the previous store).
  Joints solve(const Joints& b) const noexcept {
    double x[kMaxAxes];
    for (int i = 0; i < n_; ++i) x[i] = b[i];
    // P b first, all swaps in order: compute() swapped whole rows, L's multipliers included,
    // so L is that of the final row order (swapping while substituting would apply a later
    // swap to multipliers already used).
    for (int c = 0; c < n_; ++c)
      if (row_[c] != c) std::swap(x[c], x[row_[c]]);
    for (int c = 0; c < n_; ++c)
      for (int r = c + 1; r < n_; ++r) x[r] -= m_[r][c] * x[c];
    for (int r = n_ - 1; r >= 0; --r) {
      double sum = x[r];
      for (int k = r + 1; k < n_; ++k) sum -= m_[r][k] * x[k];
      x[r] = sum * inverse_pivot_[r];
    }
    Joints out(n_);
    for (int i = 0; i < n_; ++i) out[i] = x[i];
    return out;
  }

 private:
  double m_[kMaxAxes][kMaxAxes];    // U on and above the diagonal, L below (unit diagonal)
  double inverse_pivot_[kMaxAxes];  // 1 / U's diagonal
  int row_[kMaxAxes];               // the row swapped with row c at step c
  int n_ = 0;
  bool ok_ = false;
};

}  // namespace vc::machine
