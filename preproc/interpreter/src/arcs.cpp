// Arcs (G2/G3): the centre from I J K or R, with LinuxCNC 2.9's checks, and the points along
// a move's nominal path.
#include <algorithm>

#include "words.hpp"

namespace vc::interpreter {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

// LinuxCNC 2.9's arc checks (interp_internal.hh, interp_arc.cc), in program units: an R arc
// may fall short of the end point by RADIUS_TOLERANCE; an IJK arc's start and end radius
// (a spiral) may differ by CENTER_ARC_RADIUS_TOLERANCE if that is more than 0.1 % of the
// radius, and never by 100 times it; a radius below RADIUS_TOLERANCE is a zero-radius arc.
constexpr double kRadiusTolerance_inch = 0.00005;
constexpr double kCenterArcRadiusTolerance_inch = 2 * 0.001 * M_SQRT2;
constexpr double kCenterArcRadiusTolerance_mm = 2 * 0.01 * M_SQRT2;
constexpr double kSpiralRelativeTolerance = 0.001;

}  // namespace

void Interpreter::arc_geometry(const Words& w, const Position& end, int line, Move& m) const {
  Arc& arc = m.arc;
  arc.clockwise = motion_ == G_2;
  const int offset = w.find_g({G_2, G_3}) ? w.find_g({G_2, G_3})->offset : w[w.has('X') ? 'X' : 'Y'].offset;
  char first_letter, second_letter;  // center words of the plane
  if (plane_ == G_17) {
    arc.first = 0;
    arc.second = 1;
    arc.normal = 2;
    first_letter = 'I';
    second_letter = 'J';
  } else if (plane_ == G_18) {
    arc.first = 2;
    arc.second = 0;
    arc.normal = 1;
    first_letter = 'K';
    second_letter = 'I';
  } else {
    arc.first = 1;
    arc.second = 2;
    arc.normal = 0;
    first_letter = 'J';
    second_letter = 'K';
  }
  if (w.has('P')) {
    const double p = w.get('P');
    if (w.whole('P') < 1 || p > 1000) refuse(line, w['P'].offset, "P (turns) of an arc must be a whole number 1..1000");
    arc.turns = w.whole('P');
  }
  const double scale = inches_ ? kInch : 1.0;
  const double radius_tolerance = kRadiusTolerance_inch * kInch;  // the same length in G20 and G21
  const double spiral_tolerance = inches_ ? kCenterArcRadiusTolerance_inch * kInch : kCenterArcRadiusTolerance_mm;
  const double a0 = m.start[arc.first], b0 = m.start[arc.second];
  const double a1 = end[arc.first], b1 = end[arc.second];
  if (w.has('R')) {
    // Radius form: the center on the perpendicular bisector; R < 0 takes the long way.
    const double r = std::abs(w.get('R') * scale);
    if (a1 == a0 && b1 == b0) refuse(line, w['R'].offset, "an R-form arc cannot end where it starts");
    double half = std::hypot(a1 - a0, b1 - b0) / 2;
    if (half - r > radius_tolerance) refuse(line, w['R'].offset, "arc radius too small to reach the end point");
    if (half / r > 1 - 1e-12) half = r;  // LinuxCNC: a half circle within the tolerance
    const double h = std::sqrt(r * r - half * half);
    // Center to the left of start->end for (CCW, short way) and (CW, long way).
    const double sign = ((w.get('R') > 0) != arc.clockwise) ? 1.0 : -1.0;
    const double chord = std::hypot(a1 - a0, b1 - b0);
    const double ua = (a1 - a0) / chord, ub = (b1 - b0) / chord;
    arc.center_first = (a0 + a1) / 2 - sign * h * ub;
    arc.center_second = (b0 + b1) / 2 + sign * h * ua;
  } else {
    if (!w.has(first_letter) && !w.has(second_letter))
      refuse(line, offset,
             std::string("G2/G3 in this plane needs ") + first_letter + " or " + second_letter + " (center), or R");
    for (char c : {'I', 'J', 'K'})
      if (w.has(c) && c != first_letter && c != second_letter)
        refuse(line, w[c].offset, std::string(1, c) + " is not a center word in the active plane");
    const double di = w.get(first_letter) * scale, dj = w.get(second_letter) * scale;
    arc.center_first = arc_absolute_ ? di : a0 + di;
    arc.center_second = arc_absolute_ ? dj : b0 + dj;
    const double r0 = std::hypot(a0 - arc.center_first, b0 - arc.center_second);
    const double r1 = std::hypot(a1 - arc.center_first, b1 - arc.center_second);
    if (r0 < radius_tolerance || r1 < radius_tolerance) refuse(line, offset, "arc of zero radius");
    const double difference = std::abs(r1 - r0);
    if (difference > 100 * spiral_tolerance ||
        (difference / std::max(r0, r1) > kSpiralRelativeTolerance && difference > spiral_tolerance))
      refuse(line, offset,
             "radius to end of arc differs from radius to start by " + std::to_string(difference) +
                 " mm (LinuxCNC allows " + std::to_string(spiral_tolerance) + " mm or 0.1 %)");
  }
  const double t0 = std::atan2(b0 - arc.center_second, a0 - arc.center_first);
  const double t1 = std::atan2(b1 - arc.center_second, a1 - arc.center_first);
  arc.sweep_rad = arc_sweep(t0, t1, arc.clockwise, arc.turns);
}

double arc_sweep(double t0, double t1, bool clockwise, int turns) {
  double sweep = t1 - t0;
  if (clockwise) {
    while (sweep >= -1e-12) sweep -= kTwoPi;  // (-2 pi, 0), a full turn if start == end
    if (sweep < -kTwoPi) sweep += kTwoPi;
  } else {
    while (sweep <= 1e-12) sweep += kTwoPi;
    if (sweep > kTwoPi) sweep -= kTwoPi;
  }
  return sweep + (clockwise ? -1.0 : 1.0) * kTwoPi * (turns - 1);
}

Position point_at(const Move& m, double s) {
  Position p;
  for (int i = 0; i < kAxes; ++i) p[i] = m.start[i] + s * (m.end[i] - m.start[i]);
  if (m.kind != MoveKind::Arc) return p;
  const Arc& a = m.arc;
  const double t0 = std::atan2(m.start[a.second] - a.center_second, m.start[a.first] - a.center_first);
  const double r0 = std::hypot(m.start[a.first] - a.center_first, m.start[a.second] - a.center_second);
  const double r1 = std::hypot(m.end[a.first] - a.center_first, m.end[a.second] - a.center_second);
  const double r = r0 + s * (r1 - r0), t = t0 + s * a.sweep_rad;
  p[a.first] = a.center_first + r * std::cos(t);
  p[a.second] = a.center_second + r * std::sin(t);
  return p;
}

double feed_length(const Move& m) {
  if (m.kind == MoveKind::Arc) {
    const Arc& a = m.arc;
    const double radius = std::hypot(m.start[a.first] - a.center_first, m.start[a.second] - a.center_second);
    const double along = radius * std::abs(a.sweep_rad), rise = m.end[a.normal] - m.start[a.normal];
    return rise == 0.0 ? along : std::hypot(along, rise);
  }
  const auto distance = [&](int from) {
    double sum = 0;
    for (int i = from; i < from + 3; ++i) sum += (m.end[i] - m.start[i]) * (m.end[i] - m.start[i]);
    return std::sqrt(sum);
  };
  const double linear = distance(0);
  return linear > 0.0 ? linear : distance(3);
}

double inverse_time_feed(const Move& m) { return m.compensated_rate_mm_per_min / std::max(feed_length(m), 1e-9); }

}  // namespace vc::interpreter
