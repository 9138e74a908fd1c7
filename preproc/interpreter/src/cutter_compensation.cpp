// LinuxCNC 2.9's cutter radius compensation, step for step (see cutter_compensation.hpp). The
// geometry is written in the plane's two coordinates (x, y: G17 X Y, G18 Z X) as LinuxCNC's
// own code is; names follow it so that the two can be read side by side.
#include "vc/interpreter/cutter_compensation.hpp"

#include <cmath>

#include "vc/interpreter/codes.hpp"

namespace vc::interpreter {
namespace {

constexpr double kPi = M_PI, kHalfPi = M_PI / 2;
constexpr double kSmall = 0.05;  // TOLERANCE_CONCAVE_CORNER, rad
constexpr double kToleranceEqual = 1e-6;
// CENTER_ARC_RADIUS_TOLERANCE (interp_internal.hh), in program units.
constexpr double kSpiralTolerance_inch = 2 * 0.001 * M_SQRT2, kSpiralTolerance_mm = 2 * 0.01 * M_SQRT2;

// LinuxCNC's find_turn: the angle swept from (x1, y1) to (x2, y2) about the centre, `turn`
// full or partial turns counter-clockwise (< 0: clockwise).
double find_turn(double x1, double y1, double cx, double cy, int turn, double x2, double y2) {
  if (turn == 0) return 0.0;
  double alpha = std::atan2(y1 - cy, x1 - cx), beta = std::atan2(y2 - cy, x2 - cx);
  if (turn > 0) {
    if (beta <= alpha) beta += 2 * kPi;
    return beta - alpha + (turn - 1) * 2 * kPi;
  }
  if (alpha <= beta) alpha += 2 * kPi;
  return beta - alpha + (turn + 1) * 2 * kPi;
}

}  // namespace

void CutterCompensation::start(Side side, double radius_mm, int plane, int orientation, bool inches) {
  if (radius_mm < 0) {  // a negative diameter: the other side
    radius_mm = -radius_mm;
    side = side == kLeft ? kRight : kLeft;
  }
  side_ = side;
  radius_ = radius_mm;
  orientation_ = orientation;
  xz_ = plane == G_18;
  if (xz_) {
    a_ = 2;
    b_ = 0;
    n_ = 1;
  } else {
    a_ = 0;
    b_ = 1;
    n_ = 2;
  }
  unit_ = inches ? 25.4 : 1.0;
}

void CutterCompensation::flush(std::vector<ReleasedMove>& out) {
  move_endpoint_and_flush(get1(current_), get2(current_), out);
  dequeue(out);
}

void CutterCompensation::stop(std::vector<ReleasedMove>& out) {
  if (offsets() && !first_) flush(out);
  side_ = kOff;
  first_ = true;
}

void CutterCompensation::lathe_origin(Position& p) const {
  // interp_queue.cc latheorigin_x/z: a lathe tool's controlled point is not its radius centre.
  if (!xz_) return;
  const int o = orientation_;
  const double r = radius_;
  if (o == 2 || o == 6 || o == 1) p[0] -= r;
  if (o == 3 || o == 8 || o == 4) p[0] += r;
  if (o == 2 || o == 7 || o == 3) p[2] -= r;
  if (o == 1 || o == 5 || o == 4) p[2] += r;
}

void CutterCompensation::enqueue_straight(const Move& line, long sequence, double d1, double d2, double x, double y,
                                          const Position& rest) {
  Queued q{sequence, line};
  q.move.end = rest;
  q.move.end[a_] = x;
  q.move.end[b_] = y;
  q.d1 = d1;
  q.d2 = d2;
  queue_.push_back(q);
}

void CutterCompensation::enqueue_arc(const Move& arc, long sequence, double original_turn, double x, double y,
                                     double cx, double cy, int turn, const Position& rest) {
  Queued q{sequence, arc};
  Move& m = q.move;
  m.kind = MoveKind::Arc;
  m.end = rest;
  m.end[a_] = x;
  m.end[b_] = y;
  m.arc.first = a_;
  m.arc.second = b_;
  m.arc.normal = n_;
  m.arc.center_first = cx;
  m.arc.center_second = cy;
  m.arc.turns = std::abs(turn);
  m.arc.clockwise = turn < 0;
  q.original_turn = original_turn;
  q.turn = turn;
  queue_.push_back(q);
}

void CutterCompensation::dequeue(std::vector<ReleasedMove>& out) {
  endpoint_valid_ = false;
  if (queue_.empty()) return;
  for (Queued& q : queue_) {
    Move m = q.move;
    m.start = tool_;
    lathe_origin(m.end);
    if (m.kind == MoveKind::Arc) {
      Position center{};
      center[a_] = m.arc.center_first;
      center[b_] = m.arc.center_second;
      lathe_origin(center);
      m.arc.center_first = center[a_];
      m.arc.center_second = center[b_];
      m.arc.sweep_rad = find_turn(get1(m.start), get2(m.start), m.arc.center_first, m.arc.center_second, q.turn,
                                  get1(m.end), get2(m.end));
    }
    tool_ = m.end;
    out.push_back({q.sequence, m});
  }
  stale_front_ = queue_.front();
  queue_.clear();
}

void CutterCompensation::move_endpoint_and_flush(double x, double y, std::vector<ReleasedMove>& out) {
  if (queue_.empty()) return;
  // Several moves may be held (into a concave corner, then up and down again): all end here.
  for (Queued& q : queue_) {
    Move& m = q.move;
    if (m.kind == MoveKind::Arc) {
      const double cx = m.arc.center_first, cy = m.arc.center_second;
      const double r1 = std::hypot(get1(m.end) - cx, get2(m.end) - cy);
      const double r2 = std::hypot(x - cx, y - cy);
      const double l2 = find_turn(endpoint_[0], endpoint_[1], cx, cy, q.turn, x, y);
      if (std::abs(r1 - r2) > 0.01 * unit_)
        throw CompensationError("cutter compensation has generated an invalid arc with mismatched radii");
      if (q.original_turn != 0.0 && endpoint_valid_ && std::abs(l2) > std::abs(q.original_turn) + 0.0254)
        throw CompensationError("arc move in concave corner cannot be reached by the tool without gouging");
    } else {
      const double dot = q.d1 * (x - endpoint_[0]) + q.d2 * (y - endpoint_[1]);
      if (endpoint_valid_ && dot < 0)  // backed up further than the move is long
        throw CompensationError(std::string(m.kind == MoveKind::Rapid ? "straight traverse" : "straight feed") +
                                " in concave corner cannot be reached by the tool without gouging");
    }
    m.end[a_] = x;
    m.end[b_] = y;
  }
  dequeue(out);
  set_endpoint(x, y);
}

void CutterCompensation::straight(const Move& move, const Position& from, const Position& tool_at, long sequence,
                                  std::vector<ReleasedMove>& out) {
  const double px = get1(move.end), py = get2(move.end);
  const double radius = radius_;
  if (first_) {  // convert_straight_comp1: the entry move
    tool_ = tool_at;
    current_ = from;
    const double cx = get1(current_), cy = get2(current_);
    if (std::hypot(px - cx, py - cy) <= radius)
      throw CompensationError("length of cutter compensation entry move is not greater than the tool radius");
    const double alpha = std::atan2(py - cy, px - cx) + (side_ == kLeft ? kHalfPi : -kHalfPi);
    const double end_x = px + radius * std::cos(alpha), end_y = py + radius * std::sin(alpha);
    set_endpoint(cx, cy);
    enqueue_straight(move, sequence, std::cos(alpha), std::sin(alpha), end_x, end_y, move.end);
    first_ = false;
    current_ = move.end;
    current_[a_] = end_x;
    current_[b_] = end_y;
    return;
  }
  // convert_straight_comp2
  const double cx = get1(current_), cy = get2(current_);
  const double opx = get1(from), opy = get2(from);
  double end_x = cx, end_y = cy;
  if (py == opy && px == opx) {  // no motion in the plane
    enqueue_straight(move, sequence, 0, 0, cx, cy, move.end);
  } else {
    double theta = std::atan2(cy - opy, cx - opx);
    double alpha = std::atan2(py - opy, px - opx);
    double beta, gamma;
    if (side_ == kLeft) {
      if (theta < alpha) theta += 2 * kPi;
      beta = theta - alpha - kHalfPi;
      gamma = kHalfPi;
    } else {
      if (alpha < theta) alpha += 2 * kPi;
      beta = alpha - theta - kHalfPi;
      gamma = -kHalfPi;
    }
    end_x = px + radius * std::cos(alpha + gamma);
    end_y = py + radius * std::sin(alpha + gamma);
    double mid_x = opx + radius * std::cos(alpha + gamma), mid_y = opy + radius * std::sin(alpha + gamma);
    const Queued* head = queue_.empty() ? nullptr : &queue_.front();
    bool concave;
    if (beta < -kSmall || beta > kPi + kSmall) {
      concave = true;
    } else if (beta > kPi - kSmall && head && head->move.kind == MoveKind::Arc &&
               ((side_ == kRight && head->turn > 0) || (side_ == kLeft && head->turn < 0))) {
      concave = true;  // an "h" shape: stay above and to the side rather than loop around
    } else {
      concave = false;
    }
    if (!concave && beta > kSmall) {  // convex corner: an arc about the programmed corner
      move_endpoint_and_flush(cx, cy, out);
      Position rest = move.end;
      rest[n_] = current_[n_];
      if (move.kind == MoveKind::Line) {
        enqueue_arc(move, sequence, 0.0, mid_x, mid_y, opx, opy, side_ == kLeft ? -1 : 1, rest);
      } else {  // no arc traverse: a straight one to the arc's end
        enqueue_straight(move, sequence, 0, 0, mid_x, mid_y, rest);
      }
      dequeue(out);
      set_endpoint(mid_x, mid_y);
    } else if (concave) {
      const Queued* prev = front();
      if (!prev || prev->move.kind != MoveKind::Arc) {  // line -> line
        const double halfcorner = (beta + kPi) / 2.0;
        if (halfcorner == 0.0) throw CompensationError("zero degree inside corner is invalid for cutter compensation");
        const double retreat = radius / std::tan(halfcorner);
        mid_x = cx + retreat * std::cos(theta + gamma);
        mid_y = cy + retreat * std::sin(theta + gamma);
        move_endpoint_and_flush(mid_x, mid_y, out);
      } else {  // arc -> line; the held arc is the compensated one
        const Move& arc = prev->move;
        const double pc1 = arc.arc.center_first, pc2 = arc.arc.center_second;
        const double oldrad = std::hypot(pc2 - get2(arc.end), pc1 - get1(arc.end));
        const double base_dir = std::atan2(py - opy, px - opx);
        const double th = prev->turn > 0 ? base_dir + kHalfPi : base_dir - kHalfPi;
        const double phi = std::atan2(pc2 - opy, pc1 - opx);
        const bool inside = tool_inside_arc(prev->turn);
        const double oldrad_uncomp = inside ? oldrad + radius : oldrad - radius;
        const double d = oldrad_uncomp * std::cos(th - phi);  // to the old centre, across the new line
        const double l = (inside ? d - radius : d + radius) / oldrad;
        if (l > 1.0 || l < -1.0)
          throw CompensationError(
              "arc to straight motion makes a corner the compensated tool can't fit in without gouging");
        const double angle = (inside == (prev->turn > 0) ? -std::acos(l) : std::acos(l)) + th + kPi;
        mid_x = pc1 + oldrad * std::cos(angle);
        mid_y = pc2 + oldrad * std::sin(angle);
        move_endpoint_and_flush(mid_x, mid_y, out);
      }
    } else {  // no corner (collinear, or a tangent arc -> line)
      dequeue(out);
      set_endpoint(cx, cy);
    }
    enqueue_straight(move, sequence, px - opx, py - opy, end_x, end_y, move.end);
  }
  current_ = move.end;
  current_[a_] = end_x;
  current_[b_] = end_y;
}

void CutterCompensation::arc(const Move& move, const Position& from, const Position& tool_at, long sequence,
                             std::vector<ReleasedMove>& out) {
  const double tool_radius = radius_;
  const double spiral_tolerance = unit_ == 1.0 ? kSpiralTolerance_mm : kSpiralTolerance_inch * unit_;
  const int turn = move.arc.clockwise ? -move.arc.turns : move.arc.turns;
  const double centerx = move.arc.center_first, centery = move.arc.center_second;
  double end_x = get1(move.end), end_y = get2(move.end);

  if (first_) {  // convert_arc_comp1: the entry move is an arc
    // arc_data_comp_ijk / _r: the tool must fit inside an arc it cuts on the inside.
    if (tool_inside_arc(turn) && std::hypot(centerx - get1(from), centery - get2(from)) <= tool_radius)
      throw CompensationError("tool radius not less than arc radius with cutter compensation");
    tool_ = tool_at;
    current_ = from;
    const double cx = get1(current_), cy = get2(current_);
    if (std::hypot(end_x - cx, end_y - cy) <= tool_radius)
      throw CompensationError("radius of cutter compensation entry arc is not greater than the tool radius");
    const double gamma = tool_inside_arc(turn) ? std::atan2(centery - end_y, centerx - end_x)
                                               : std::atan2(end_y - centery, end_x - centerx);
    first_ = false;
    end_x += tool_radius * std::cos(gamma);
    end_y += tool_radius * std::sin(gamma);
    // The compensated arc's centre: on the line from the new end towards the programmed centre,
    // as far from the end as from the start.
    const double b_len = std::hypot(cy - end_y, cx - end_x) / 2.0;
    const double ab_ang = std::atan2(centery - end_y, centerx - end_x);
    const double a_ang = std::atan2(cy - end_y, cx - end_x) - ab_ang;
    if (std::abs(std::cos(a_ang)) < kToleranceEqual)
      throw CompensationError("tool radius not less than arc radius with cutter compensation");
    const double c_len = b_len / std::cos(a_ang);
    const double ncx = end_x + c_len * std::cos(ab_ang), ncy = end_y + c_len * std::sin(ab_ang);
    if (std::abs(std::hypot(ncx - end_x, ncy - end_y) - std::hypot(ncx - cx, ncy - cy)) > spiral_tolerance)
      throw CompensationError("bug in tool radius compensation (LinuxCNC refuses this entry arc too)");
    if (orientation_ != 0 && orientation_ != 9) {  // a lathe tool: its origin moves first
      Move line = move;
      line.kind = MoveKind::Line;
      enqueue_straight(line, sequence, 0, 0, cx, cy, move.end);
      set_endpoint(cx, cy);
    }
    enqueue_arc(move, sequence, find_turn(cx, cy, ncx, ncy, turn, end_x, end_y), end_x, end_y, ncx, ncy, turn,
                move.end);
    current_ = move.end;
    current_[a_] = end_x;
    current_[b_] = end_y;
    return;
  }

  // convert_arc_comp2
  const double cx = get1(current_), cy = get2(current_), cz = current_[n_];
  const double opx = get1(from), opy = get2(from);
  const int side = side_;
  const double arc_radius = std::hypot(centerx - end_x, centery - end_y);
  double theta = std::atan2(cy - opy, cx - opx);
  theta = side == kLeft ? theta - kHalfPi : theta + kHalfPi;
  double delta = std::atan2(centery - opy, centerx - opx);
  const double alpha = turn > 0 ? delta - kHalfPi : delta + kHalfPi;
  double beta = side == kLeft ? theta - alpha : alpha - theta;
  beta = beta > 1.5 * kPi ? beta - 2 * kPi : beta < -kHalfPi ? beta + 2 * kPi : beta;  // -90 .. 270 deg
  double gamma;
  if (tool_inside_arc(turn)) {
    gamma = std::atan2(centery - end_y, centerx - end_x);
    if (arc_radius <= tool_radius)
      throw CompensationError("tool radius not less than arc radius with cutter compensation");
  } else {
    gamma = std::atan2(end_y - centery, end_x - centerx);
    delta += kPi;
  }
  const double new_end_x = end_x + tool_radius * std::cos(gamma), new_end_y = end_y + tool_radius * std::sin(gamma);
  const double sweep = find_turn(opx, opy, centerx, centery, turn, end_x, end_y);

  if (beta < -kSmall || beta > kPi + kSmall || (std::abs(beta - kPi) < kSmall && !tool_inside_arc(turn))) {
    // concave corner
    const Queued* prev = front();
    double midx, midy;
    if (!prev || prev->move.kind != MoveKind::Arc) {  // line -> arc
      const double across = arc_radius * std::sin(beta - kHalfPi);
      double angle_from_center;
      double dist_from_center;
      if (tool_inside_arc(turn)) {
        dist_from_center = arc_radius - tool_radius;
        const double l = (across + tool_radius) / dist_from_center;
        if (l > 1.0 || l < -1.0)
          throw CompensationError("arc move in concave corner cannot be reached by the tool without gouging");
        angle_from_center = turn > 0 ? theta + std::asin(l) : theta - std::asin(l);
      } else {
        dist_from_center = arc_radius + tool_radius;
        const double l = (across - tool_radius) / dist_from_center;
        if (l > 1.0 || l < -1.0)
          throw CompensationError("arc move in concave corner cannot be reached by the tool without gouging");
        angle_from_center = turn > 0 ? theta + kPi - std::asin(l) : theta + kPi + std::asin(l);
      }
      midx = centerx + dist_from_center * std::cos(angle_from_center);
      midy = centery + dist_from_center * std::sin(angle_from_center);
    } else {  // arc -> arc
      const Move& p = prev->move;
      const double pc1 = p.arc.center_first, pc2 = p.arc.center_second;
      const double oldrad = std::hypot(pc2 - get2(p.end), pc1 - get1(p.end));
      const double newrad = tool_inside_arc(turn) ? arc_radius - tool_radius : arc_radius + tool_radius;
      const double arc_cc = std::hypot(pc2 - centery, pc1 - centerx);
      if (oldrad == 0 || arc_cc == 0)
        throw CompensationError("arc to arc motion is invalid because the arcs have the same center");
      const double a = (oldrad * oldrad + arc_cc * arc_cc - newrad * newrad) / (2 * oldrad * arc_cc);
      if (a > 1.0 || a < -1.0)
        throw CompensationError("arc to arc motion makes a corner the compensated tool can't fit in without gouging");
      const double pullback = std::acos(a);
      const double cc_dir = std::atan2(centery - pc2, centerx - pc1);
      const double dir = tool_inside_arc(prev->turn) == (turn > 0) ? cc_dir + pullback : cc_dir - pullback;
      midx = pc1 + oldrad * std::cos(dir);
      midy = pc2 + oldrad * std::sin(dir);
    }
    move_endpoint_and_flush(midx, midy, out);
    enqueue_arc(move, sequence, sweep, new_end_x, new_end_y, centerx, centery, turn, move.end);
  } else if (beta > kSmall) {  // convex: an arc about the programmed corner, then the arc
    const double midx = opx + tool_radius * std::cos(delta), midy = opy + tool_radius * std::sin(delta);
    dequeue(out);
    Position rest = move.end;
    rest[n_] = cz;
    enqueue_arc(move, sequence, 0.0, midx, midy, opx, opy, side == kLeft ? -1 : 1, rest);
    dequeue(out);
    set_endpoint(midx, midy);
    enqueue_arc(move, sequence, sweep, new_end_x, new_end_y, centerx, centery, turn, move.end);
  } else {  // tangent
    dequeue(out);
    set_endpoint(cx, cy);
    enqueue_arc(move, sequence, sweep, new_end_x, new_end_y, centerx, centery, turn, move.end);
  }
  current_ = move.end;
  current_[a_] = new_end_x;
  current_[b_] = new_end_y;
}

}  // namespace vc::interpreter
