#include "vc/shop/selftune_local.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "move_sampling.hpp"
#include "program_blocks.hpp"
#include "program_points.hpp"

namespace vc::shop {
namespace {

using interpreter::Move;
using interpreter::MoveKind;
using interpreter::Position;

// A measured deviation at the cut that shaped it.
struct Anchor {
  Eigen::Vector3d at;      // tool tip of the cut (part frame)
  Eigen::Vector3d normal;
  double deviation_mm;
};

std::vector<Anchor> anchors_of(const FirstPart& part) {
  std::vector<Anchor> anchors;
  for (const MatchedPoint& m : part.points) {
    if (m.outlier) continue;
    for (const Contact& c : m.cuts) {
      const PathSample& a = part.path[static_cast<std::size_t>(c.sample)];
      const PathSample& b = part.path[static_cast<std::size_t>(c.sample) + 1];
      anchors.push_back({a.tip + c.u * (b.tip - a.tip), m.point.normal, m.filtered_mm});
    }
  }
  return anchors;
}

class PathShift {
 public:
  PathShift(const machine::Model& model, const std::string& file, std::vector<Anchor> anchors,
            const LocalOptions& options)
      : points_(model, options.world, file), anchors_(std::move(anchors)), options_(options) {}

  // Program-coordinate shift at a point of a move; `covered` tells whether any measured cut
  // was within the radius.
  Position shift_at(const Move& m, const Position& program, bool& covered) const {
    const Eigen::Vector3d tip = points_.ideal_tip(m, program);
    const double sigma = options_.radius_mm / 2;
    Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
    Eigen::Vector3d right = Eigen::Vector3d::Zero();
    double weight = 0;
    for (const Anchor& a : anchors_) {
      const double d = (a.at - tip).norm();
      if (d > options_.radius_mm) continue;
      const double w = std::exp(-0.5 * (d / sigma) * (d / sigma));
      normal_matrix += w * a.normal * a.normal.transpose();
      right += w * a.deviation_mm * a.normal;
      weight += w;
    }
    Position shift{};
    covered = weight > 1e-6;
    if (!covered) return shift;
    // A small ridge keeps the directions no measured normal sees at zero.
    const Eigen::Vector3d v = (normal_matrix + 1e-6 * weight * Eigen::Matrix3d::Identity()).ldlt().solve(right);
    const Eigen::Vector3d dp = tip_jacobian(m, program).colPivHouseholderQr().solve(-options_.gain * v);
    for (int i = 0; i < 3; ++i) shift[static_cast<std::size_t>(i)] = dp[i];
    return shift;
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

  ProgramPoints points_;
  std::vector<Anchor> anchors_;
  const LocalOptions& options_;
};

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
  const double length = path_length(m);
  summary.cutting_length_mm += length;
  bool any = false;
  for (int i = 1; i <= n; ++i) {
    predistort::Piece piece;
    piece.kind = MoveKind::Line;
    piece.fraction = 1.0 / n;
    piece.end = interpreter::point_at(m, static_cast<double>(i) / n);
    bool covered = false;
    const Position d = shift.shift_at(m, piece.end, covered);
    for (std::size_t a = 0; a < 3; ++a) piece.end[a] += d[a];
    const double size = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    summary.largest_shift_mm = std::max(summary.largest_shift_mm, size);
    any = any || size > 0;
    if (covered) covered_length += length / n;
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
                           const interpreter::Setup& setup, const predistort::Provenance& provenance,
                           std::ostream& out, const LocalOptions& options) {
  const PathShift shift(model, setup.file, anchors_of(part), options);
  interpreter::Interpreter interpreter(setup);
  predistort::Writer writer(out, setup.machine_axes, options.tolerance_mm);
  LocalSummary summary;
  double covered_length = 0;
  std::vector<std::vector<predistort::Piece>> pieces;
  bool header_written = false;
  for_each_block(program, interpreter, setup, [&](const std::string& raw, const gcode::Block& block,
                                           const interpreter::Effect& effect, int) {
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
