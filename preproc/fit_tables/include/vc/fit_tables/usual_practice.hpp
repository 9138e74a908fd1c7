// The usual practice (the source's correction method 2): each table filled with its own
// measured deviation, negated: X's positioning table cancels EXX, the cross table X -> Y
// cancels EYX, the squareness Y -> X cancels the XY squareness (EC0X or EC0Y), C's positioning
// table cancels ECC; every other deviation is left alone.
//
// The sign and the projection are not written out per case but derived from the model: a
// table's value at a node is the correction of its output joint that cancels the tip error of
// the machine with ONLY its own deviations (vc::machine::keep_only), with the input joint at
// the node and the others at a reference pose (linear joints mid-travel, rotary ones at 0 or
// the travel end nearest to it, the machine file's tool length; for a rotary output, the linear
// joints at the 1/4, 1/2 or 3/4 point of their travels that put the tip farthest from its
// line): a 1-D Gauss-Newton on the
// nonlinear model, min_c |tip(q + c e_out) - ideal tip(q)|. A translation deviation (EXX, EYX)
// moves the tip the same everywhere, so the value cancels it everywhere; a rotary axis's
// positioning needs the tip off the axis line, as it is at the reference pose. A squareness
// value is the slope (least squares over the input's travel) of those corrections, as the
// source's single number is (the form has no intercept).
#pragma once

#include <Eigen/Core>

#include "vc/fit_tables/table_set.hpp"

namespace vc::fit_tables {

// Throws std::runtime_error if a table's output joint cannot move the tip at the reference
// pose (the tip on a rotary axis's line).
Eigen::VectorXd usual_practice(const machine::Model& model, const TableSet& set);

// The reference pose the usual practice is computed at, and the one for a table correcting
// joint `output`.
machine::Joints reference_pose(const machine::Model& model);
machine::Joints reference_pose(const machine::Model& model, int output);

}  // namespace vc::fit_tables
