#include "vc/fit_tables/poses.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "vc/fit_tables/interpolation.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::fit_tables {
namespace {}  // namespace

std::vector<Pose> grid_poses(const machine::Model& model, const GridSpec& spec) {
  if (spec.levels < 2) throw std::invalid_argument("--levels must be at least 2");
  if (spec.tool_lengths_mm.empty()) throw std::invalid_argument("no tool length to fit at");
  for (const auto& [letter, positions] : spec.rotary) {
    const int j = model.joint_of(letter);
    if (j < 0 || model.axes[static_cast<std::size_t>(j)].type != machine::AxisType::Rotary)
      throw std::invalid_argument(std::string("--rotary ") + letter + ": " + model.info.name + " has no rotary axis " +
                                  letter);
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
    if (positions.empty()) throw std::invalid_argument(std::string("--rotary ") + letter + ": no positions");
    for (double p : positions)
      if (!std::isfinite(p) || p < a.travel_min - 1e-9 || p > a.travel_max + 1e-9)
        throw std::invalid_argument(std::string("--rotary ") + letter + "=" + number_text(p) + ": outside the travel " +
                                    number_text(a.travel_min) + " .. " + number_text(a.travel_max) + " deg");
  }
  const int n = model.joint_count();
  std::vector<std::vector<double>> levels(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
    auto& at = levels[static_cast<std::size_t>(j)];
    const auto given = spec.rotary.find(a.letter);
    if (given != spec.rotary.end()) {
      at = given->second;
      continue;
    }
    at = equally_spaced(a.travel_min, a.travel_max, spec.levels);
    const bool full_turn = a.type == machine::AxisType::Rotary && std::abs(a.travel_max - a.travel_min - 360.0) < 1e-9;
    if (full_turn && spec.full_turn_once) at.pop_back();
  }
  std::vector<Pose> poses;
  for (double length : spec.tool_lengths_mm) {
    std::vector<std::size_t> index(static_cast<std::size_t>(n), 0);
    while (true) {
      machine::Joints q(n);
      for (int j = 0; j < n; ++j) q[j] = levels[static_cast<std::size_t>(j)][index[static_cast<std::size_t>(j)]];
      poses.push_back({q, length});
      int j = 0;
      while (j < n && ++index[static_cast<std::size_t>(j)] == levels[static_cast<std::size_t>(j)].size())
        index[static_cast<std::size_t>(j++)] = 0;
      if (j == n) break;
    }
  }
  return poses;
}

std::vector<Pose> FreshPoses::next(int count, const std::vector<double>& tool_lengths_mm) {
  std::vector<Pose> poses;
  std::vector<machine::Joints> joints;
  for (int k = 0; k < count; ++k) joints.push_back(samples_.next());
  for (double length : tool_lengths_mm)
    for (const machine::Joints& q : joints) poses.push_back({q, length});
  return poses;
}

}  // namespace vc::fit_tables
