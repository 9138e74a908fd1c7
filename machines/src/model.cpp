#include "vc/machine/model.hpp"

#include <cctype>
#include <cmath>

namespace vc::machine {

int Model::rotary_count() const {
  int n = 0;
  for (const Axis& a : axes) n += a.type == AxisType::Rotary;
  return n;
}

double AxisCompliance::at(double q) const {
  if (mm_per_N.empty()) return 0.0;
  if (position_mm.empty() || q <= position_mm.front()) return mm_per_N.front();
  if (q >= position_mm.back()) return mm_per_N.back();
  std::size_t i = 1;
  while (position_mm[i] < q) ++i;
  const double t = (q - position_mm[i - 1]) / (position_mm[i] - position_mm[i - 1]);
  return mm_per_N[i - 1] + t * (mm_per_N[i] - mm_per_N[i - 1]);
}

int Model::joint_of(char letter) const {
  for (int i = 0; i < joint_count(); ++i)
    if (axes[i].letter == letter) return i;
  return -1;
}

std::string Model::coordinates() const {
  std::string s;
  for (const Axis& a : axes) s += static_cast<char>(std::tolower(static_cast<unsigned char>(a.letter)));
  return s;
}

bool outside_tables(const Model& model, const Joints& q) noexcept {
  for (const BoundTable& bound : model.tables) {
    const auto& grid = bound.table.grid();
    for (std::size_t v = 0; v < grid.size(); ++v) {
      if (grid[v].periodic) continue;
      const double x = q[bound.joint[v]];
      if (x < grid[v].nodes.front() || x > grid[v].nodes.back()) return true;
    }
  }
  return false;
}

Eigen::Isometry3d line_placement(const Eigen::Vector3d& origin_mm, const Eigen::Vector3d& location_mm,
                                 const Eigen::Vector3d& location_rad) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = origin_mm + location_mm;
  t.linear() = rotation_xyz(location_rad);
  return t;
}

}  // namespace vc::machine
