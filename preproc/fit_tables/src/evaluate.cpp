#include "vc/fit_tables/evaluate.hpp"

#include <algorithm>

#include "vc/machine/correct.hpp"
#include "vc/machine/forward.hpp"

namespace vc::fit_tables {

double tip_error_um(const machine::Model& truth, const machine::Joints& commanded, const Pose& p) {
  const Eigen::Vector3d real = machine::tool_pose(truth, machine::Machine::Real, commanded, p.tool_length_mm).tip_mm;
  const Eigen::Vector3d ideal = machine::tool_pose(truth, machine::Machine::Ideal, p.q, p.tool_length_mm).tip_mm;
  return (real - ideal).norm() * 1e3;
}

Figures figures(const std::vector<double>& errors_um) {
  Figures f;
  f.poses = static_cast<int>(errors_um.size());
  if (errors_um.empty()) return f;
  const auto [least, most] = std::minmax_element(errors_um.begin(), errors_um.end());
  f.max_um = *most;
  f.delta_um = *most - *least;
  return f;
}

std::vector<double> uncompensated_errors(const machine::Model& truth, const std::vector<Pose>& poses) {
  std::vector<double> out;
  out.reserve(poses.size());
  for (const Pose& p : poses) out.push_back(tip_error_um(truth, p.q, p));
  return out;
}

std::vector<double> table_errors(const machine::Model& truth, const TableSet& set, const Eigen::VectorXd& x,
                                 const std::vector<Pose>& poses) {
  std::vector<double> out;
  out.reserve(poses.size());
  for (const Pose& p : poses) out.push_back(tip_error_um(truth, compensated(set, x, p.q), p));
  return out;
}

std::vector<double> full_correction_errors(const machine::Model& model, const machine::Model& truth,
                                           const std::vector<Pose>& poses) {
  std::vector<double> out;
  out.reserve(poses.size());
  for (const Pose& p : poses)
    out.push_back(tip_error_um(truth, machine::correct(model, p.q, p.tool_length_mm).joints, p));
  return out;
}

}  // namespace vc::fit_tables
