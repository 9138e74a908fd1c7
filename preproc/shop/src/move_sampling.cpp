#include "move_sampling.hpp"

#include <algorithm>
#include <cmath>

namespace vc::shop {

namespace {

double arc_radius(const interpreter::Move& m) {
  const auto f = static_cast<std::size_t>(m.arc.first), g = static_cast<std::size_t>(m.arc.second);
  return std::max(std::hypot(m.start[f] - m.arc.center_first, m.start[g] - m.arc.center_second),
                  std::hypot(m.end[f] - m.arc.center_first, m.end[g] - m.arc.center_second));
}

}  // namespace

double path_length(const interpreter::Move& m) {
  if (m.kind != interpreter::MoveKind::Arc) {
    double length = 0;
    for (int i = 0; i < 3; ++i) length += (m.end[i] - m.start[i]) * (m.end[i] - m.start[i]);
    return std::sqrt(length);
  }
  const auto n = static_cast<std::size_t>(m.arc.normal);
  return std::hypot(std::abs(m.arc.sweep_rad) * arc_radius(m), m.end[n] - m.start[n]);
}

int piece_count(const interpreter::Move& m, double step_mm, double chord_tolerance_mm, double step_deg) {
  double n = path_length(m) / step_mm;
  if (m.kind == interpreter::MoveKind::Arc) {
    const double r = arc_radius(m);
    if (r > chord_tolerance_mm)
      n = std::max(n, std::abs(m.arc.sweep_rad) / (2 * std::acos(1 - chord_tolerance_mm / r)));
  }
  for (int i = 3; i < interpreter::kAxes; ++i) n = std::max(n, std::abs(m.end[i] - m.start[i]) / step_deg);
  return std::max(1, static_cast<int>(std::ceil(n)));
}

}  // namespace vc::shop
