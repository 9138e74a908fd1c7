#include "vc/predistort/path_corrector.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vc::predistort {
namespace {

using machine::Joints;
using machine::Machine;
using machine::Status;

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kCheckPoints[] = {0.25, 0.5, 0.75};
constexpr double kAcceptShare = 0.7;      // of the tolerance, at the check points
constexpr double kUncheckedShare = 0.25;  // of the tolerance, for the bounds

[[noreturn]] void fail(const Move& move, const std::string& what, Status status) {
  throw std::runtime_error("line " + std::to_string(move.line) + ": " + what + " (" + machine::describe(status) + ")");
}

// Angle from `from` to `to` turning the given way, in (0, 2 pi] (a full turn if equal).
double turn_between(double from, double to, bool counter_clockwise) {
  double sweep = counter_clockwise ? to - from : from - to;
  while (sweep <= 1e-12) sweep += kTwoPi;
  while (sweep > kTwoPi) sweep -= kTwoPi;
  return counter_clockwise ? sweep : -sweep;
}

// The circle LinuxCNC moves along for an arc piece from `start`: start angle, radius and
// signed sweep about the piece's centre (its ends are at equal radius).
struct PieceCircle {
  double start_angle, radius, sweep;
};
PieceCircle circle_of(const interpreter::Arc& arc, const Position& start, const Piece& piece) {
  const auto f = static_cast<std::size_t>(arc.first), g = static_cast<std::size_t>(arc.second);
  const double t0 = std::atan2(start[g] - piece.center_second, start[f] - piece.center_first);
  const double t1 = std::atan2(piece.end[g] - piece.center_second, piece.end[f] - piece.center_first);
  const double turns = (arc.clockwise ? -1 : 1) * kTwoPi * (piece.turns - 1);
  return {t0, std::hypot(start[f] - piece.center_first, start[g] - piece.center_second),
          turn_between(t0, t1, !arc.clockwise) + turns};
}

}  // namespace

PathCorrector::PathCorrector(const machine::Model& model, const machine::Conditions& conditions,
                             CorrectorOptions options, const Deflection* deflection, CorrectionBounds::Shared* shared)
    : model_(model),
      conditions_(conditions),
      options_(options),
      deflection_(deflection),
      checks_direction_(model.rotary_count() > 0 && options.tolerance_rad > 0),
      axes_(model),
      bounds_(model, conditions, shared),
      one_step_(model, conditions),
      missing_offset_(model, conditions, options.tools) {}

Joints PathCorrector::joints_of(const Position& world) const { return axes_.joints_of(world); }

Position PathCorrector::program_of(const Move& move, const Joints& world_joints, const Position& like) const {
  Position world = move.frame.world(like);
  axes_.set(world, world_joints);
  return move.frame.program(world);
}

Eigen::Vector3d PathCorrector::force_at(const Move& move, double s) {
  if (!deflection_ || move.kind == MoveKind::Rapid) return Eigen::Vector3d::Zero();
  // Feed direction and tool axis of the nominal path at s (ideal machine, part frame).
  const double h = 1e-4;
  const double s0 = std::max(0.0, s - h), s1 = std::min(1.0, s + h);
  Joints q0, q1;
  const double L = model_.correction_length(move.tool_offset_mm);  // the tool-length rule
  machine::nominal_inverse(model_, options_.world, joints_of(move.frame.world(interpreter::point_at(move, s0))), L, q0);
  machine::nominal_inverse(model_, options_.world, joints_of(move.frame.world(interpreter::point_at(move, s1))), L, q1);
  const machine::ToolPose p0 = machine::tool_pose(model_, Machine::Ideal, q0, L);
  const machine::ToolPose p1 = machine::tool_pose(model_, Machine::Ideal, q1, L);
  const Eigen::Vector3d step = p1.tip_mm - p0.tip_mm;
  if (step.norm() < 1e-12) return Eigen::Vector3d::Zero();
  // Path length of the whole move (for inverse-time feeds): this step scaled up.
  const double length = step.norm() / (s1 - s0);
  return deflection_->force(move, step.normalized(), p0.direction, length);
}

PathCorrector::Node PathCorrector::node_at(const Move& move, double s) {
  Node n;
  n.s = s;
  const Position p = interpreter::point_at(move, s);
  const double L = model_.correction_length(move.tool_offset_mm);  // the tool-length rule
  n.input = joints_of(move.frame.world(p));
  Status status = machine::nominal_inverse(model_, options_.world, n.input, L, n.nominal);
  if (status != Status::Ok) fail(move, "no nominal joints for a point of the move", status);
  n.target = n.nominal;
  if (deflection_) {
    const Eigen::Vector3d force = force_at(move, s);
    if (force.squaredNorm() > 0) {
      Joints shift;
      deflection_->at(n.nominal, L, force, shift, n.deflection_mm);
      n.target -= shift;
      stats_.max_deflection_mm = std::max(stats_.max_deflection_mm, n.deflection_mm.norm());
    }
  }
  const Joints seed = seed_for(n.target, L);
  ++stats_.corrections;
  if (!one_step_.correct(n.target, L, seed, n.corrected)) {
    const machine::Correction c = machine::correct(model_, conditions_, n.target, L, seed);
    if (c.status != Status::Ok) fail(move, "the correction failed", c.status);
    n.corrected = c.joints;
  }
  solved(n.target, n.corrected, L);
  stats_.grids.note(model_, n.corrected, move.line);
  if (move.tool_offset_from == interpreter::ToolOffsetFrom::None)
    missing_offset_.at(move, n.target, n.corrected, stats_.missing_offset);
  n.world = machine::nominal_forward(model_, options_.world, n.corrected, L);
  n.program = program_of(move, n.world, p);
  return n;
}

// Seed: this point plus the correction of a recent one (the correction changes little
// between neighbouring points, so Newton starts next to the answer), extrapolated along the
// path when the last two points lie on a line with this one: the change of the correction
// from one to the next is then mostly its slope times the step, which the seed takes along.
Joints PathCorrector::seed_for(const Joints& target, double tool_length_mm) const {
  if (recent_count_ == 0) return target;
  const Solved& last = recent_[1];
  if (last.tool_length_mm != tool_length_mm || last.target.size() != target.size() ||
      (last.target - target).cwiseAbs().maxCoeff() >= 1.0)
    return target;
  Joints seed = target + last.offset;
  const Solved& before = recent_[0];
  if (recent_count_ < 2 || before.tool_length_mm != tool_length_mm) return seed;
  const Joints step = last.target - before.target, ahead = target - last.target;
  const double step2 = step.squaredNorm();
  if (!(step2 > 0.0) || step2 >= 1.0) return seed;
  // How far ahead along the last step, and how far off its line.
  const double along = ahead.dot(step) / step2;
  const Joints off = ahead - along * step;
  if (along < -1.5 || along > 1.5 || off.squaredNorm() > 1e-4 * step2) return seed;
  return seed + along * (last.offset - before.offset);
}

void PathCorrector::solved(const Joints& target, const Joints& corrected, double tool_length_mm) {
  recent_[0] = std::move(recent_[1]);
  recent_[1] = {target, corrected - target, tool_length_mm};
  recent_count_ = std::min(recent_count_ + 1, 2);
}

Piece PathCorrector::piece_between(const Move& move, const Node& a, const Node& b) const {
  Piece piece;
  piece.kind = move.kind;
  piece.end = b.program;
  piece.fraction = b.s - a.s;
  if (move.kind != MoveKind::Arc) return piece;
  // A circle through both corrected ends, its center nearest to the nominal center moved by
  // the mean correction of the two ends (in the plane).
  const interpreter::Arc& arc = move.arc;
  const auto f = static_cast<std::size_t>(arc.first), g = static_cast<std::size_t>(arc.second);
  const Position na = interpreter::point_at(move, a.s), nb = interpreter::point_at(move, b.s);
  const double cf = arc.center_first + 0.5 * ((a.program[f] - na[f]) + (b.program[f] - nb[f]));
  const double cg = arc.center_second + 0.5 * ((a.program[g] - na[g]) + (b.program[g] - nb[g]));
  const double vf = b.program[f] - a.program[f], vg = b.program[g] - a.program[g];
  const double chord = std::hypot(vf, vg);
  if (chord < 1e-9) {
    piece.center_first = cf;
    piece.center_second = cg;
  } else {
    const double mf = 0.5 * (a.program[f] + b.program[f]), mg = 0.5 * (a.program[g] + b.program[g]);
    const double nf = -vg / chord, ng = vf / chord;  // unit normal of the chord
    const double along = (cf - mf) * nf + (cg - mg) * ng;
    piece.center_first = mf + along * nf;
    piece.center_second = mg + along * ng;
  }
  const double share = std::abs(piece.fraction * arc.sweep_rad);
  piece.turns = share > kTwoPi + 1e-9 ? static_cast<int>(std::ceil(share / kTwoPi - 1e-9)) : 1;
  // LinuxCNC decides the sweep from the center and the ends: if the corrected ends would
  // make it go the other way round (an arc of almost no or almost a full turn), write a line.
  if (std::abs(circle_of(arc, a.program, piece).sweep - piece.fraction * arc.sweep_rad) > M_PI / 2)
    piece.kind = MoveKind::Line;
  return piece;
}

Position PathCorrector::commanded_at(const Move& move, const Node& a, const Piece& piece, double t) const {
  Position p;
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = a.program[i] + t * (piece.end[i] - a.program[i]);
  if (piece.kind != MoveKind::Arc) return p;
  // LinuxCNC's arc through the piece's ends about its center (equal radii: a circle).
  const interpreter::Arc& arc = move.arc;
  const PieceCircle c = circle_of(arc, a.program, piece);
  p[static_cast<std::size_t>(arc.first)] = piece.center_first + c.radius * std::cos(c.start_angle + t * c.sweep);
  p[static_cast<std::size_t>(arc.second)] = piece.center_second + c.radius * std::sin(c.start_angle + t * c.sweep);
  return p;
}

PathCorrector::PieceError PathCorrector::error_between(const Move& move, const Node& a, const Node& b,
                                                       const Piece& piece, double t,
                                                       const DirectionErrors* exact_direction_errors) {
  ++stats_.checks;
  const double L = model_.correction_length(move.tool_offset_mm);  // the tool-length rule
  const double s = a.s + t * (b.s - a.s);
  Joints nominal, commanded;
  machine::nominal_inverse(model_, options_.world, joints_of(move.frame.world(interpreter::point_at(move, s))), L,
                           nominal);
  machine::nominal_inverse(model_, options_.world, joints_of(move.frame.world(commanded_at(move, a, piece, t))), L,
                           commanded);
  const Eigen::Vector3d deflection = a.deflection_mm + t * (b.deflection_mm - a.deflection_mm);
  const machine::ToolPose real = machine::tool_pose(model_, conditions_, Machine::Real, commanded, L);
  const machine::ToolPose ideal = machine::tool_pose(model_, Machine::Ideal, nominal, L);
  PieceError e;
  e.mm = (real.tip_mm + deflection - ideal.tip_mm).norm();
  if (exact_direction_errors) {
    // The exact correction's own direction error at the point: none where neither the ends nor
    // the point are in the pole fade band (full correction), else the exact correction's
    // there (one more exact inverse): the fade is not linear along a piece, so the ends'
    // values interpolated miss it by tens of urad across the band.
    const auto& [at_a, at_b] = *exact_direction_errors;
    Eigen::Vector3d exact = Eigen::Vector3d::Zero();
    if (at_a.squaredNorm() > 0 || at_b.squaredNorm() > 0 ||
        machine::pole_angle(model_, nominal, L) < conditions_.fade.full_rad)
      exact = direction_error(move, node_at(move, s));
    e.rad = (real.direction - ideal.direction - exact).norm();
  }
  return e;
}

Eigen::Vector3d PathCorrector::direction_error(const Move& move, const Node& n) const {
  const double L = model_.correction_length(move.tool_offset_mm);
  return machine::tool_pose(model_, conditions_, Machine::Real, n.corrected, L).direction -
         machine::tool_pose(model_, Machine::Ideal, n.nominal, L).direction;
}

bool PathCorrector::piece_within_tolerance(const Move& move, const Node& a, const Node& b, const Piece& piece) {
  PieceError worst;
  // The exact correction's own direction errors at the ends (the pole fade leaves them).
  DirectionErrors exact;
  if (checks_direction_) exact = {direction_error(move, a), direction_error(move, b)};
  for (double t : kCheckPoints) {
    const PieceError e = error_between(move, a, b, piece, t, checks_direction_ ? &exact : nullptr);
    worst.mm = std::max(worst.mm, e.mm);
    worst.rad = std::max(worst.rad, e.rad);
  }
  const bool within = worst.mm <= kAcceptShare * options_.tolerance_mm &&
                      (!checks_direction_ || worst.rad <= kAcceptShare * options_.tolerance_rad);
  if (within) {
    stats_.max_checked_error_mm = std::max(stats_.max_checked_error_mm, worst.mm);
    stats_.max_checked_error_rad = std::max(stats_.max_checked_error_rad, worst.rad);
  }
  return within;
}

// A straight piece that the bounds of the correction's slope or curvature keep well inside
// the tolerance (correction_bounds.hpp); the curvature bound needs the nominal joints to run
// straight between the ends (world = joints) and no cutting force.
bool PathCorrector::within_bounds(const Move& move, const Node& a, const Node& b) {
  if (move.kind != MoveKind::Line || deflection_) return false;
  const double share = kUncheckedShare * options_.tolerance_mm, L = model_.correction_length(move.tool_offset_mm);
  const double share_rad = checks_direction_ ? kUncheckedShare * options_.tolerance_rad : HUGE_VAL;
  const CorrectionBounds::Bound slope = bounds_.slope_bound(a.nominal, b.nominal, L);
  if (slope.mm <= share && slope.rad <= share_rad) return true;
  if (options_.world != machine::WorldConvention::Axes) return false;
  const CorrectionBounds::Bound curvature = bounds_.curvature_bound(a.nominal, b.nominal, a.corrected, b.corrected, L);
  return curvature.mm <= share && curvature.rad <= share_rad;
}

void PathCorrector::refine(const Move& move, const Node& a, const Node& b, int depth, std::vector<Piece>& pieces) {
  const Piece piece = piece_between(move, a, b);
  bool accept = within_bounds(move, a, b);
  if (!accept) accept = piece_within_tolerance(move, a, b, piece);
  if (!accept && depth >= options_.max_depth) {
    ++stats_.tolerance_misses;
    accept = true;
  }
  if (accept) {
    pieces.push_back(piece);
    return;
  }
  const Node mid = node_at(move, 0.5 * (a.s + b.s));
  refine(move, a, mid, depth + 1, pieces);
  refine(move, mid, b, depth + 1, pieces);
}

void PathCorrector::correct(const Move& move, std::vector<Piece>& pieces) {
  pieces.clear();
  ++stats_.moves;
  // The start is where the previous move ended: its correction is known, unless the tool
  // length or the cutting force changed.
  Node a;
  const bool continues = have_last_ && !last_loaded_ && last_tool_length_ == move.tool_offset_mm &&
                         (!deflection_ || move.kind == MoveKind::Rapid) &&
                         last_.input == joints_of(move.frame.world(move.start));
  if (continues) {
    a = last_;
    a.s = 0.0;
    a.program = program_of(move, a.world, move.start);
  } else {
    a = node_at(move, 0.0);
  }
  // A short piece to the corrected start if the machine is not there (the previous move was
  // written uncorrected, or the tool length changed and with it the correction).
  if (move.kind != MoveKind::Rapid && (!have_last_ || (last_.world - a.world).cwiseAbs().maxCoeff() > 1e-9)) {
    Piece lead;
    lead.kind = MoveKind::Line;
    lead.end = a.program;
    // In G93 a piece takes fraction / F minutes: the lead its length's share of the move's
    // (chord) length, not the whole move's time.
    const Position from = have_last_ ? program_of(move, last_.world, move.start) : move.start;
    double lead_length = 0, move_length = 0;
    for (int i = 0; i < 3; ++i) {
      lead_length += (a.program[i] - from[i]) * (a.program[i] - from[i]);
      move_length += (move.end[i] - move.start[i]) * (move.end[i] - move.start[i]);
    }
    lead.fraction = move_length > 0 ? std::clamp(std::sqrt(lead_length / move_length), 1e-6, 1.0) : 1.0;
    pieces.push_back(lead);
  }
  const Node b = node_at(move, 1.0);
  if (move.kind == MoveKind::Rapid) {
    pieces.push_back(piece_between(move, a, b));
  } else if (move.kind == MoveKind::Arc && std::abs(move.arc.sweep_rad) > M_PI) {
    // Long arcs: whole if the tolerance allows, else in pieces of at most half a turn.
    const Piece whole = piece_between(move, a, b);
    if (piece_within_tolerance(move, a, b, whole)) {
      pieces.push_back(whole);
    } else {
      const int n = static_cast<int>(std::ceil(std::abs(move.arc.sweep_rad) / M_PI));
      Node from = a;
      for (int i = 1; i <= n; ++i) {
        const Node to = i == n ? b : node_at(move, static_cast<double>(i) / n);
        refine(move, from, to, 1, pieces);
        from = to;
      }
    }
  } else {
    refine(move, a, b, 0, pieces);
  }
  stats_.pieces += static_cast<long>(pieces.size());
  ended(move, b);
}

void PathCorrector::ended(const Move& move, const Node& end) {
  last_ = end;
  have_last_ = true;
  last_tool_length_ = move.tool_offset_mm;
  last_loaded_ = end.deflection_mm.squaredNorm() > 0;
}

void PathCorrector::resume_after(const Move& move) { ended(move, node_at(move, 1.0)); }

void CorrectorStats::add(const CorrectorStats& other) {
  moves += other.moves;
  pieces += other.pieces;
  corrections += other.corrections;
  checks += other.checks;
  tolerance_misses += other.tolerance_misses;
  grids.add(other.grids);
  missing_offset.add(other.missing_offset);
  max_checked_error_mm = std::max(max_checked_error_mm, other.max_checked_error_mm);
  max_checked_error_rad = std::max(max_checked_error_rad, other.max_checked_error_rad);
  max_deflection_mm = std::max(max_deflection_mm, other.max_deflection_mm);
}

}  // namespace vc::predistort
