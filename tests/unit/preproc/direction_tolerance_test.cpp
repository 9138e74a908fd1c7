// The tool direction between the written points (--tolerance-rad): along a 5-axis move through
// the pole fade band, the real machine's tool direction at the joints LinuxCNC interpolates
// between the corrected points stays within the direction tolerance of the exact correction's
// direction there, sampled densely and computed with the core's correction (not the path
// corrector's check points or bounds).
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "vc/machine/correct.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/path_corrector.hpp"

namespace vc::predistort {
namespace {

using machine::Joints;

Joints joints_of(const Position& p) {  // MC-300: X Y Z B C
  Joints q(5);
  q << p[0], p[1], p[2], p[4], p[5];
  return q;
}

// Largest direction deviation (rad) from the exact correction over a move through the fade band,
// and the number of pieces written.
std::pair<double, std::size_t> worst_direction(const machine::Model& model, double tolerance_rad,
                                               const Position& start = {-300, -160, -200, 0, -0.5, 0},
                                               const Position& end = {-290, -150, -195, 0, -14, 60}) {
  CorrectorOptions options;
  options.tolerance_rad = tolerance_rad;
  PathCorrector corrector(model, model.reference_conditions(), options, nullptr);
  const double L = model.correction_length(100.0);
  Move rapid;
  rapid.kind = MoveKind::Rapid;
  rapid.end = start;
  rapid.start = rapid.end;
  rapid.tool_offset_mm = 100.0;
  std::vector<Piece> pieces;
  corrector.correct(rapid, pieces);
  Position from = pieces.back().end;
  // Through the band (B from -0.5 to -14 deg: the fade runs from 2 to 10 deg off the C axis)
  // while C turns: the orientation correction fades in along the move.
  Move move = rapid;
  move.kind = MoveKind::Line;
  move.start = rapid.end;
  move.end = end;
  corrector.correct(move, pieces);
  double worst = 0.0, s0 = 0.0;
  for (const Piece& piece : pieces) {
    for (int k = 1; k < 40; ++k) {
      const double t = k / 40.0;
      const Joints commanded = joints_of(from) + t * (joints_of(piece.end) - joints_of(from));
      const Joints nominal = joints_of(interpreter::point_at(move, s0 + t * piece.fraction));
      const machine::Correction exact = machine::correct(model, nominal, L);
      EXPECT_EQ(exact.status, machine::Status::Ok);
      const Eigen::Vector3d d = machine::tool_pose(model, machine::Machine::Real, commanded, L).direction -
                                machine::tool_pose(model, machine::Machine::Real, exact.joints, L).direction;
      worst = std::max(worst, d.norm());
    }
    s0 += piece.fraction;
    from = piece.end;
  }
  EXPECT_NEAR(s0, 1.0, 1e-12);
  return {worst, pieces.size()};
}

TEST(DirectionTolerance, BoundsTheToolDirectionBetweenWrittenPoints) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const auto [by_default, pieces] = worst_direction(model, 2e-5);
  const auto [tight, pieces_tight] = worst_direction(model, 5e-6);
  const auto [unbounded, pieces_unbounded] = worst_direction(model, 0.0);  // the position tolerance only
  std::printf(
      "through the pole fade band: direction deviation %.3g rad in %zu pieces at 2e-5 rad, %.3g rad in %zu "
      "at 5e-6 rad, %.3g rad in %zu with the position tolerance only\n",
      by_default, pieces, tight, pieces_tight, unbounded, pieces_unbounded);
  EXPECT_LE(by_default, 2e-5);
  EXPECT_LE(tight, 5e-6);
  EXPECT_GT(unbounded, 5e-6);  // the position tolerance alone does not bound it
  EXPECT_GT(pieces_tight, pieces_unbounded);
}

// Issue 36's move: B -12 to -1 deg with C +40 deg in one G1, from outside the band (B -12,
// full correction) to inside its start (B -1: no orientation correction), sampled at 200
// points per piece against the core's exact (faded) correction at each point.
TEST(DirectionTolerance, AMoveAcrossTheWholeFadeBandStaysOnTheExactFade) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  for (const double tolerance : {2e-5, 5e-6}) {
    const auto [worst, pieces] =
        worst_direction(model, tolerance, {-300, -160, -200, 0, -12, 0}, {-300, -160, -200, 0, -1, 40});
    std::printf("B -12 -> -1, C +40: direction deviation from the exact fade %.3g rad in %zu pieces at %.0e rad\n",
                worst, pieces, tolerance);
    EXPECT_LE(worst, tolerance);
  }
}

}  // namespace
}  // namespace vc::predistort
