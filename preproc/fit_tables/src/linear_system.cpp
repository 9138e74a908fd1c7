#include "vc/fit_tables/linear_system.hpp"

#include "vc/machine/forward.hpp"

namespace vc::fit_tables {

Eigen::Vector3d LinearSystem::residual(int pose, const Eigen::VectorXd& x) const {
  Eigen::Vector3d r = error_mm[static_cast<std::size_t>(pose)];
  for (int k = start[static_cast<std::size_t>(pose)]; k < start[static_cast<std::size_t>(pose) + 1]; ++k)
    r += coefficient[static_cast<std::size_t>(k)] * x[unknown[static_cast<std::size_t>(k)]];
  return r;
}

void LinearSystem::append(const LinearSystem& other) {
  const int offset = start.empty() ? 0 : start.back();
  if (start.empty()) start.push_back(0);
  error_mm.insert(error_mm.end(), other.error_mm.begin(), other.error_mm.end());
  for (std::size_t p = 1; p < other.start.size(); ++p) start.push_back(other.start[p] + offset);
  unknown.insert(unknown.end(), other.unknown.begin(), other.unknown.end());
  coefficient.insert(coefficient.end(), other.coefficient.begin(), other.coefficient.end());
}

LinearSystem linearise(const machine::Model& model, const TableSet& set, const std::vector<Pose>& poses) {
  LinearSystem s;
  s.unknowns = set.unknowns;
  s.error_mm.reserve(poses.size());
  s.start.reserve(poses.size() + 1);
  s.start.push_back(0);
  std::vector<Contribution> c;
  machine::PoseDerivatives d;
  for (const Pose& p : poses) {
    const machine::ToolPose real = machine::tool_pose(model, machine::Machine::Real, p.q, p.tool_length_mm, d);
    const machine::ToolPose ideal = machine::tool_pose(model, machine::Machine::Ideal, p.q, p.tool_length_mm);
    s.error_mm.push_back(real.tip_mm - ideal.tip_mm);
    contributions(set, p.q, c);
    // Contributions of one unknown (a modulo table's shared node, or two tables on one
    // joint never share unknowns) are merged so that each unknown appears once per pose.
    const int first = static_cast<int>(s.unknown.size());
    for (const Contribution& k : c) {
      const Eigen::Vector3d column = d.tip.col(k.joint) * k.weight;
      bool merged = false;
      for (int e = first; e < static_cast<int>(s.unknown.size()); ++e)
        if (s.unknown[static_cast<std::size_t>(e)] == k.unknown) {
          s.coefficient[static_cast<std::size_t>(e)] += column;
          merged = true;
          break;
        }
      if (!merged) {
        s.unknown.push_back(k.unknown);
        s.coefficient.push_back(column);
      }
    }
    s.start.push_back(static_cast<int>(s.unknown.size()));
  }
  return s;
}

}  // namespace vc::fit_tables
