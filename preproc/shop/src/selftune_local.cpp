#include "vc/shop/selftune_local.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "vc/shop/local_fit.hpp"
#include "move_sampling.hpp"
#include "program_blocks.hpp"
#include "program_points.hpp"

namespace vc::shop {
namespace {

using interpreter::Move;
using interpreter::MoveKind;
using interpreter::Position;

// The measured deviations at the cuts that shaped them, each in its cut's tool frame (the
// ideal machine's at the joints of the cut).
std::vector<Anchor> anchors_of(const machine::Model& model, const FirstPart& part) {
  std::vector<Anchor> anchors;
  for (std::size_t k = 0; k < part.points.size(); ++k) {
    const MatchedPoint& m = part.points[k];
    if (m.outlier) continue;
    for (const Contact& c : m.cuts) {
      const PathSample& a = part.path[static_cast<std::size_t>(c.sample)];
      const PathSample& b = part.path[static_cast<std::size_t>(c.sample) + 1];
      const PathSample& near = c.u < 0.5 ? a : b;
      const Eigen::Matrix3d frame =
          machine::part_T_tool(model, machine::Machine::Ideal, near.joints, near.tool_length_mm).linear();
      const Eigen::Vector3d tip = a.tip + c.u * (b.tip - a.tip);
      anchors.push_back({tip, frame.transpose() * m.point.normal, (m.point.nominal - tip).dot(frame.col(2)),
                         m.filtered_mm, frame, static_cast<int>(k)});
    }
  }
  return anchors;
}

// Whether a move turns a rotary axis (a 5-axis move). A 3+2 move holds them; pre-distorted,
// it turns them by thousandths of a degree (the correction), which does not count.
bool turns_rotary_axes(const Move& m, unsigned axes) {
  constexpr double kHeldDeg = 0.01;
  for (std::size_t i = 3; i < static_cast<std::size_t>(interpreter::kAxes); ++i)
    if ((axes >> i & 1u) && (m.known_start >> i & 1u) && std::abs(m.end[i] - m.start[i]) > kHeldDeg) return true;
  return false;
}

// What the path shift does at a point of a move.
struct PointChange {
  Position change{};                                      // program coordinates
  Eigen::Vector3d tip_on_part = Eigen::Vector3d::Zero();  // the programmed tool tip, part frame
  double tip_shift_mm = 0.0;                              // how far the change moves it on the part
  bool covered = false;
  enum class Tilt { NotAsked, Done, Unseen, BelowNoise, Singular } tilt = Tilt::NotAsked;
  double tilt_rad = 0.0;
};

class PathShift {
 public:
  PathShift(const machine::Model& model, const interpreter::Setup& setup, std::vector<Anchor> anchors, double noise_mm,
            const LocalOptions& options)
      : points_(model, options.world, setup.file),
        axes_(setup.machine_axes),
        anchors_(std::move(anchors)),
        noise_mm_(noise_mm),
        options_(options) {}

  // Rotary axes that can turn the tool (any of A B C).
  bool machine_tilts() const { return (axes_ >> 3) != 0; }

  Eigen::Vector3d tip_on_part(const Move& m, const Position& program) const {
    return points_.ideal_pose(m, program).translation();
  }

  // The change of a point of a move: the tip moved by -gain v and, on a 5-axis move where
  // the points tell it, the tool axis turned by -gain w (selftune_local.hpp).
  PointChange change_at(const Move& m, const Position& program) const {
    const Eigen::Isometry3d pose = points_.ideal_pose(m, program);
    const bool five_axis = options_.tilt && machine_tilts() && turns_rotary_axes(m, axes_);
    // The tilt, which changes slowly along a part (squareness, a tilted spindle or axis line)
    // and needs many points, from those within twice the radius and angle; the tip's shift,
    // which changes faster, from those within them, the tilt taken off.
    LocalFitOptions wide{2 * options_.radius_mm, 2 * options_.angle_deg * M_PI / 180, five_axis,
                         options_.tilt_spread_mm, noise_mm_};
    const LocalFit tilt =
        five_axis ? fit_tool_displacement(anchors_, pose.translation(), pose.linear(), wide) : LocalFit{};
    LocalFitOptions narrow{options_.radius_mm, options_.angle_deg * M_PI / 180, false, options_.tilt_spread_mm,
                           noise_mm_};
    if (tilt.tilt == TiltFit::Estimated) narrow.known_tilt_rad = tilt.tilt_rad;
    LocalFit fit = fit_tool_displacement(anchors_, pose.translation(), pose.linear(), narrow);
    // Where few measured points carry the shift (a corner that C turns through in a few
    // millimetres: the cuts within the angle touch few points), their noise is the shift:
    // the window widens.
    for (int widen = 0; widen < 3 && fit.covered && fit.support < options_.min_support; ++widen) {
      narrow.radius_mm *= 1.5;
      narrow.angle_rad *= 1.5;
      fit = fit_tool_displacement(anchors_, pose.translation(), pose.linear(), narrow);
    }
    PointChange c;
    c.tip_on_part = pose.translation();
    c.covered = fit.covered;
    if (!c.covered) return c;
    switch (tilt.tilt) {
      case TiltFit::NotAsked:
        break;
      case TiltFit::Unseen:
        c.tilt = PointChange::Tilt::Unseen;
        break;
      case TiltFit::BelowNoise:
        c.tilt = PointChange::Tilt::BelowNoise;
        break;
      case TiltFit::Estimated: {
        const Eigen::Vector3d turn = -options_.gain * (pose.linear() * tilt.tilt_rad);
        const Eigen::Vector3d tip_change = -options_.gain * (pose.linear() * fit.shift_mm);
        if (tilted(m, program, pose, tip_change, turn, c.change)) {
          c.tilt = PointChange::Tilt::Done;
          c.tilt_rad = turn.norm();
          c.tip_shift_mm = tip_change.norm();
          return c;
        }
        // The rotary axes cannot give the turn here: the tip's shift as without it.
        c.tilt = PointChange::Tilt::Singular;
        narrow.known_tilt_rad.setZero();
        fit = fit_tool_displacement(anchors_, pose.translation(), pose.linear(), narrow);
        break;
      }
    }
    const Eigen::Vector3d tip_change = -options_.gain * (pose.linear() * fit.shift_mm);
    c.tip_shift_mm = tip_change.norm();
    const Eigen::Vector3d dp = tip_jacobian(m, program).colPivHouseholderQr().solve(tip_change);
    for (int i = 0; i < 3; ++i) c.change[static_cast<std::size_t>(i)] = dp[i];
    return c;
  }

 private:
  // d tip / d program (x, y, z), by differences over 1 mm (the ideal machine is affine in
  // its linear axes).
  Eigen::Matrix3d tip_jacobian(const Move& m, const Position& program) const {
    Eigen::Matrix3d jacobian;
    const Eigen::Vector3d at = points_.ideal_tip(m, program);
    for (int i = 0; i < 3; ++i) {
      Position p = program;
      p[static_cast<std::size_t>(i)] += 1.0;
      jacobian.col(i) = points_.ideal_tip(m, p) - at;
    }
    return jacobian;
  }

  // The change of all program axes (the machine's) that moves the ideal tip by `tip_change`
  // and turns its tool axis by `turn` (rad, part frame): the linearised ideal kinematics
  // (differences: forward over 1 mm on linear axes, central over 0.001 deg on rotary ones),
  // least squares with the direction's rows weighted by 100 mm (a turn counts as the
  // displacement it makes 100 mm up the tool). False where the rotary axes cannot give the
  // turn (near a pole of the kinematics: the turn would be missed by more than 5 %, or need
  // more than 0.05 deg).
  bool tilted(const Move& m, const Position& program, const Eigen::Isometry3d& pose, const Eigen::Vector3d& tip_change,
              const Eigen::Vector3d& turn, Position& change) const {
    constexpr double kLever = 100.0, kStepDeg = 1e-3;
    std::vector<std::size_t> axes;
    for (std::size_t i = 0; i < static_cast<std::size_t>(interpreter::kAxes); ++i)
      if (i < 3 || (axes_ >> i & 1u)) axes.push_back(i);
    Eigen::Matrix<double, 6, Eigen::Dynamic> jacobian(6, static_cast<Eigen::Index>(axes.size()));
    for (std::size_t k = 0; k < axes.size(); ++k) {
      const bool linear = axes[k] < 3;
      const double step = linear ? 1.0 : kStepDeg;
      Position up = program, down = program;  // forward on linear axes, central on rotary ones
      up[axes[k]] += linear ? step : step / 2;
      if (!linear) down[axes[k]] -= step / 2;
      const Eigen::Isometry3d a = points_.ideal_pose(m, up), b = points_.ideal_pose(m, down);
      jacobian.col(static_cast<Eigen::Index>(k)) << (a.translation() - b.translation()) / step,
          kLever * (a.linear().col(2) - b.linear().col(2)) / step;
    }
    Eigen::Matrix<double, 6, 1> target;
    target << tip_change, kLever * turn.cross(pose.linear().col(2));
    const Eigen::VectorXd dp = jacobian.colPivHouseholderQr().solve(target);
    const Eigen::Matrix<double, 6, 1> got = jacobian * dp;
    if ((got - target).norm() > 0.05 * target.norm() + 1e-9) return false;
    Position result{};
    for (std::size_t k = 0; k < axes.size(); ++k) {
      if (axes[k] >= 3 && std::abs(dp[static_cast<Eigen::Index>(k)]) > 0.05) return false;
      result[axes[k]] = dp[static_cast<Eigen::Index>(k)];
    }
    change = result;
    return true;
  }

  ProgramPoints points_;
  unsigned axes_;
  std::vector<Anchor> anchors_;
  double noise_mm_;  // of a measured point, for the tilt's noise test
  const LocalOptions& options_;
};

// What happened to the tool axis at a piece's end (counted only where measured points were near).
void count_tilt(const PointChange& c, bool machine_tilts, LocalSummary& summary) {
  if (!c.covered || !machine_tilts) return;
  switch (c.tilt) {
    case PointChange::Tilt::NotAsked:
      ++summary.tilt.rotary_held;
      break;
    case PointChange::Tilt::Unseen:
      ++summary.tilt.unseen;
      break;
    case PointChange::Tilt::BelowNoise:
      ++summary.tilt.below_noise;
      break;
    case PointChange::Tilt::Singular:
      ++summary.tilt.singular;
      break;
    case PointChange::Tilt::Done:
      ++summary.tilt.tilted;
      summary.tilt.largest_rad = std::max(summary.tilt.largest_rad, c.tilt_rad);
      break;
  }
}

// The pieces of one move: cutting moves cut into pieces whose ends are shifted; moves that
// do not cut, or that no measured point is near, as they are.
void shifted_pieces(const Move& m, const PathShift& shift, const LocalOptions& options, LocalSummary& summary,
                    double& covered_length, std::vector<predistort::Piece>& pieces) {
  predistort::Piece whole;
  whole.kind = m.kind;
  whole.end = m.end;
  whole.center_first = m.arc.center_first;
  whole.center_second = m.arc.center_second;
  whole.turns = m.arc.turns;
  if (m.kind == MoveKind::Rapid || !m.spindle_on) {
    pieces.push_back(whole);
    return;
  }
  const int n = piece_count(m, options.step_mm, options.tolerance_mm, 0.05);
  // Lengths on the part (the tool tip in the part frame, piece by piece): where a rotary axis
  // turns the part, the linear axes' travel is not the length of the contour cut.
  Eigen::Vector3d tip = shift.tip_on_part(m, m.start);
  bool any = false;
  for (int i = 1; i <= n; ++i) {
    predistort::Piece piece;
    piece.kind = MoveKind::Line;
    piece.fraction = 1.0 / n;
    piece.end = interpreter::point_at(m, static_cast<double>(i) / n);
    const PointChange c = shift.change_at(m, piece.end);
    const double length = (c.tip_on_part - tip).norm();
    tip = c.tip_on_part;
    summary.cutting_length_mm += length;
    const Position& d = c.change;
    for (std::size_t a = 0; a < static_cast<std::size_t>(interpreter::kAxes); ++a) piece.end[a] += d[a];
    const double size = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    summary.largest_axis_shift_mm = std::max(summary.largest_axis_shift_mm, size);
    summary.largest_tip_shift_mm = std::max(summary.largest_tip_shift_mm, c.tip_shift_mm);
    any = any || size > 0 || c.tilt_rad > 0;
    if (c.covered) covered_length += length;
    count_tilt(c, shift.machine_tilts(), summary);
    pieces.push_back(piece);
  }
  if (!any) {
    pieces.assign(1, whole);
    return;
  }
  ++summary.moves_shifted;
  summary.pieces += n;
}

}  // namespace

LocalSummary shift_program(const machine::Model& model, const FirstPart& part, std::istream& program,
                           const interpreter::Setup& setup, const predistort::Provenance& provenance, std::ostream& out,
                           const LocalOptions& options) {
  const PathShift shift(model, setup, anchors_of(model, part), part.robust_sigma_mm, options);
  interpreter::Interpreter interpreter(setup);
  predistort::Writer writer(out, setup.machine_axes, options.tolerance_mm);
  LocalSummary summary;
  summary.tilt.asked = options.tilt;
  summary.tilt.machine_tilts = shift.machine_tilts();
  double covered_length = 0;
  std::vector<std::vector<predistort::Piece>> pieces;
  bool header_written = false;
  for_each_block(program, interpreter, setup,
                 [&](const std::string& raw, const gcode::Block& block, const interpreter::Effect& effect, int) {
                   if (!header_written && !block.percent) {
                     writer.header(provenance);
                     header_written = true;
                   }
                   ++summary.lines;
                   if (!effect.translate) {
                     writer.verbatim(raw, block, effect, interpreter.position(), interpreter.frame());
                     return;
                   }
                   pieces.assign(effect.moves.size(), {});
                   for (std::size_t k = 0; k < effect.moves.size(); ++k)
                     shifted_pieces(effect.moves[k], shift, options, summary, covered_length, pieces[k]);
                   writer.translated(raw, block, effect, pieces);
                 });
  if (!header_written) writer.header(provenance);
  writer.flush();
  summary.covered_fraction = summary.cutting_length_mm > 0 ? covered_length / summary.cutting_length_mm : 0.0;
  return summary;
}

}  // namespace vc::shop
