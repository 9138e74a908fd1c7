// The tip error after compensation, linearised in the table values x:
//     r(q, L; x) = e(q, L) + J(q, L) B(q) x
// with e = real tip - ideal tip at the nominal joints (mm, part frame), J the real machine's
// d tip / d q (PoseDerivatives: per mm or per deg) and B(q) x = c(q, x) the correction the
// tables apply (table_set.hpp). The correction is ~10 um (a rotary one ~0.01 deg) and the
// Jacobian changes by the error slopes (~1e-4, more at a measured table's kinks) over it, so
// the linear model is good to ~0.01 um (MC-300: 0.012 um at most, modified_method_test); every
// figure reported is still computed on the nonlinear model (evaluate.hpp), never from this.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "vc/fit_tables/poses.hpp"
#include "vc/fit_tables/table_set.hpp"

namespace vc::fit_tables {

// Sparse rows, three per pose: pose p's block is entries [start[p], start[p + 1]) of
// (unknown, coefficient): column `unknown` of J B, a 3-vector (mm per unit of x).
struct LinearSystem {
  int unknowns = 0;
  std::vector<Eigen::Vector3d> error_mm;  // e per pose
  std::vector<int> start;                 // poses + 1 entries
  std::vector<int> unknown;
  std::vector<Eigen::Vector3d> coefficient;

  int poses() const { return static_cast<int>(error_mm.size()); }
  // r for one pose.
  Eigen::Vector3d residual(int pose, const Eigen::VectorXd& x) const;
  // Adds the poses of `other` (the same table set).
  void append(const LinearSystem& other);
};

// `model` is the machine the tables are fitted to (its real and ideal tips).
LinearSystem linearise(const machine::Model& model, const TableSet& set, const std::vector<Pose>& poses);

}  // namespace vc::fit_tables
