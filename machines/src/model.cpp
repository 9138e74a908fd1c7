#include <stdexcept>
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
      if (grid[v].periodic || bound.joint[v] < 0) continue;  // (temperatures: their range is checked where set)
      const double x = q[bound.joint[v]];
      if (x < grid[v].first || x > grid[v].last) return true;  // (not the nodes: another cache line)
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

Conditions Model::reference_conditions() const noexcept {
  Conditions c;
  for (std::size_t i = 0; i < temperatures.size() && i < c.temperature_degC.size(); ++i)
    c.temperature_degC[i] = temperatures[i].reference_degC;
  c.fade = fade;
  return c;
}

void Model::set_temperature(Conditions& conditions, const std::string& name, double degC) const {
  const int i = temperature_of(name);
  if (i < 0) {
    std::string names;
    for (const TemperatureInput& t : temperatures) names += (names.empty() ? "" : ", ") + t.name;
    throw std::invalid_argument("no temperature input '" + name + "' in " + path +
                                (names.empty() ? " (it has no [temperatures])" : " (it has: " + names + ")"));
  }
  const TemperatureInput& t = temperatures[static_cast<std::size_t>(i)];
  if (!(degC >= t.min_degC && degC <= t.max_degC))
    throw std::invalid_argument("temperature " + name + " = " + std::to_string(degC) +
                                " degC is outside the range the model holds for (" + std::to_string(t.min_degC) +
                                " .. " + std::to_string(t.max_degC) + " degC)");
  conditions.temperature_degC[static_cast<std::size_t>(i)] = degC;
}

int Model::temperature_of(const std::string& name) const {
  for (std::size_t i = 0; i < temperatures.size(); ++i)
    if (temperatures[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace vc::machine
