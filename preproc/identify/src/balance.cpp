#include "vc/identify/balance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vc/machine/deviations.hpp"
#include "vc/machine/forward.hpp"

namespace vc::identify {
namespace {

// The grid of poses: every joint at `levels` positions over its travel (a full turn at
// 360 / levels steps: 0 and 360 deg are one pose).
std::vector<machine::Joints> pose_grid(const machine::Model& model, int levels) {
  const int n = model.joint_count();
  std::vector<std::vector<double>> positions(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
    const bool full_turn = a.type == machine::AxisType::Rotary && std::abs(a.travel_max - a.travel_min - 360.0) < 1e-9;
    for (int k = 0; k < levels; ++k)
      positions[static_cast<std::size_t>(j)].push_back(full_turn ? a.travel_min + 360.0 * k / levels
                                                                 : a.travel_min + (a.travel_max - a.travel_min) * k /
                                                                                      (levels - 1));
  }
  std::vector<machine::Joints> poses;
  std::vector<int> index(static_cast<std::size_t>(n), 0);
  while (true) {
    machine::Joints q(n);
    for (int j = 0; j < n; ++j)
      q[j] = positions[static_cast<std::size_t>(j)][static_cast<std::size_t>(index[static_cast<std::size_t>(j)])];
    poses.push_back(q);
    int j = 0;
    while (j < n && ++index[static_cast<std::size_t>(j)] == levels) index[static_cast<std::size_t>(j++)] = 0;
    if (j == n) break;
  }
  return poses;
}

DeviationEffect effect_of(const std::string& symbol, const machine::Model& with,
                          const std::vector<machine::Joints>& poses, const std::vector<machine::ToolPose>& ideal,
                          double tool_length_mm) {
  DeviationEffect e;
  e.symbol = symbol;
  double least = INFINITY, sum = 0.0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const machine::ToolPose real = machine::tool_pose(with, machine::Machine::Real, poses[k], tool_length_mm);
    const double error = (real.tip_mm - ideal[k].tip_mm).norm() * 1e3;
    e.max_um = std::max(e.max_um, error);
    least = std::min(least, error);
    sum += error * error;
    const double turn =
        std::atan2(real.direction.cross(ideal[k].direction).norm(), real.direction.dot(ideal[k].direction));
    e.max_urad = std::max(e.max_urad, turn * 1e6);
  }
  e.delta_um = e.max_um - least;
  e.rms_um = std::sqrt(sum / static_cast<double>(poses.size()));
  return e;
}

}  // namespace

Balance accuracy_balance(const machine::Model& model, const BalanceOptions& options) {
  if (options.levels < 2 || options.levels > 21) throw std::invalid_argument("--levels must be in 2..21");
  Balance b;
  b.tool_length_mm = options.tool_length_mm.value_or(model.tool_length_mm);
  const std::vector<machine::Joints> poses = pose_grid(model, options.levels);
  b.poses = static_cast<int>(poses.size());
  std::vector<machine::ToolPose> ideal;
  ideal.reserve(poses.size());
  for (const machine::Joints& q : poses)
    ideal.push_back(machine::tool_pose(model, machine::Machine::Ideal, q, b.tool_length_mm));

  b.total = effect_of("all", model, poses, ideal, b.tool_length_mm);
  double sum = 0.0;
  std::vector<std::string> symbols = machine::deviation_symbols(model);  // (a symbol in two tables: once)
  for (std::size_t k = 0; k < symbols.size(); ++k)
    if (std::find(symbols.begin(), symbols.begin() + static_cast<long>(k), symbols[k]) !=
        symbols.begin() + static_cast<long>(k))
      symbols.erase(symbols.begin() + static_cast<long>(k--));
  for (const std::string& symbol : symbols) {
    b.effects.push_back(effect_of(symbol, machine::keep_only(model, {symbol}), poses, ideal, b.tool_length_mm));
    sum += b.effects.back().rms_um * b.effects.back().rms_um;
  }
  for (DeviationEffect& e : b.effects) e.share = sum > 0 ? e.rms_um * e.rms_um / sum : 0.0;
  std::stable_sort(b.effects.begin(), b.effects.end(),
                   [](const DeviationEffect& l, const DeviationEffect& r) { return l.max_um > r.max_um; });
  return b;
}

}  // namespace vc::identify
