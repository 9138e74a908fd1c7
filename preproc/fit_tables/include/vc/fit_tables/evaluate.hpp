// Tip errors on the nonlinear model, and the source's two criteria over a set of poses
// (seed 000, section 3.3.3, volumetric analysis): M = max |tip error|, Delta = max - min.
//
// The tip error of a compensation at pose (q, L) is the real tip where the machine goes minus
// the ideal tip at q, in the part frame: the real tip of `truth` at the joints the
// compensation commands. `truth` is the machine itself, or a different "true" machine when
// the compensation was made from a model of it (the hidden-truth check).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "vc/fit_tables/poses.hpp"
#include "vc/fit_tables/table_set.hpp"

namespace vc::fit_tables {

struct Figures {
  double max_um = 0.0;    // M
  double delta_um = 0.0;  // Delta = max - min
  int poses = 0;
};

Figures figures(const std::vector<double>& errors_um);

// |tip error| (um) of `truth` at the joints a compensation commands for pose p.
double tip_error_um(const machine::Model& truth, const machine::Joints& commanded, const Pose& p);

// |tip error| (um) per pose: no compensation.
std::vector<double> uncompensated_errors(const machine::Model& truth, const std::vector<Pose>& poses);
// ... with the tables holding x (the controller's interpolation, joints q + c(q, x)).
std::vector<double> table_errors(const machine::Model& truth, const TableSet& set, const Eigen::VectorXd& x,
                                 const std::vector<Pose>& poses);
// ... with the full correction computed from `model` (what volkins does: vc::machine::correct,
// position exact, tool direction faded near a pole): the bound no table set can beat when
// truth is the model.
std::vector<double> full_correction_errors(const machine::Model& model, const machine::Model& truth,
                                           const std::vector<Pose>& poses);

}  // namespace vc::fit_tables
