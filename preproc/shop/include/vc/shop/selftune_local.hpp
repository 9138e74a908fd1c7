// Self-tuning, local strategy: P(i+1) = P(i) shifted against the measured deviations.
//
// The filtered deviations of the report (FirstPart) sit at the cuts that shaped them. At
// every point of the program's cutting moves, a displacement v of the tool tip is estimated
// from the points whose cuts lie within `radius_mm` (gaussian weights, sigma = radius / 2;
// least squares over their normals, n_k . v = deviation_k, so a corner with two faces gets
// both components) and the point is moved by -gain * v (through the ideal machine's
// kinematics, so a program in machine axes moves the tool tip by that much). Moves are cut
// into pieces of at most `step_mm` (arcs: chords within `tolerance_mm`) wherever a shift is
// applied; moves with no measured point near them are written as they are.
#pragma once

#include <istream>
#include <ostream>

#include "vc/predistort/writer.hpp"
#include "vc/shop/first_part.hpp"

namespace vc::shop {

struct LocalOptions {
  double gain = 1.0;
  double radius_mm = 40.0;
  double step_mm = 1.0;
  double tolerance_mm = 0.0005;
  machine::WorldConvention world = machine::WorldConvention::Axes;
};

struct LocalSummary {
  long lines = 0, moves_shifted = 0, pieces = 0;
  double cutting_length_mm = 0.0;
  double covered_fraction = 0.0;  // of the cutting path, within radius_mm of a measured cut
  double largest_shift_mm = 0.0;
};

LocalSummary shift_program(const machine::Model& model, const FirstPart& part, std::istream& program,
                           const interpreter::Setup& setup, const predistort::Provenance& provenance,
                           std::ostream& out, const LocalOptions& options);

}  // namespace vc::shop
