// Self-tuning, local strategy: P(i+1) = P(i) shifted against the measured deviations.
//
// The filtered deviations of the report (FirstPart) sit at the cuts that shaped them. At
// every point of the program's cutting moves, a displacement v of the tool tip is estimated
// from the points whose cuts lie within `radius_mm` and whose tool frames are turned less
// than `angle_deg` from the point's (gaussian weights, sigma = half of each; least squares
// over their normals in the tool frame, n_k . v = deviation_k, so a corner with two faces
// gets both components: local_fit.hpp) and the point is moved by -gain * v (through the
// ideal machine's kinematics, so a program in machine axes moves the tool tip by that much).
// On 5-axis moves (the rotary axes turn) a rotation w of the tool axis about the tip is
// estimated too, from the points within twice the radius and angle, where their heights
// along the tool tell it from v (a swarf wall) and it stands above the noise; the tool axis
// is then turned by -gain * w as well (all program axes through the ideal kinematics, the
// rotary ones included) and v estimated with w taken off. 3-axis machines and moves that
// hold the rotary axes (3+2) keep their tool axis. Moves are cut into pieces of at most
// `step_mm` (arcs: chords within `tolerance_mm`, rotary axes 0.05 deg) wherever a shift is
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
  double angle_deg = 20.0;      // cuts at tool frames turned further are not used (local_fit.hpp)
  bool tilt = true;             // turn the tool axis on 5-axis moves where the points tell it
  double tilt_spread_mm = 1.0;  // heights along the tool that tell a tilt from a shift (local_fit.hpp)
  // > 0: where fewer measured points than this (effective number, LocalFit::support) carry a
  // shift, its window widens (radius and angle x 1.5, at most three times) until they do.
  // 6: on bc_head's swarf part the worst of four noise draws went from 3.95 to 2.43 um PV
  // (preproc/shop/README.md); 3 and 12 did less.
  double min_support = 6.0;
};

// What the tool axis got, counted over the pieces with measured points near (their ends).
struct TiltSummary {
  bool asked = true;           // LocalOptions::tilt
  bool machine_tilts = false;  // the machine has a rotary axis
  long tilted = 0;             // 5-axis pieces whose tool axis was turned
  long unseen = 0;             // 5-axis pieces whose points lie at one height along the tool
  long below_noise = 0;        // ... whose tilt does not stand above the noise
  long singular = 0;           // 5-axis pieces where the rotary axes cannot give the turn (a pole)
  long rotary_held = 0;        // pieces of moves holding the rotary axes (3+2): tip only
  double largest_rad = 0.0;
};

struct LocalSummary {
  long lines = 0, moves_shifted = 0, pieces = 0;
  double cutting_length_mm = 0.0;      // of the tool tip on the part (part frame), feed moves with the spindle on
  double covered_fraction = 0.0;       // of that length, within radius_mm of a measured cut
  double largest_tip_shift_mm = 0.0;   // of the tool tip on the part: what the measured deviations ask for
  double largest_axis_shift_mm = 0.0;  // of the linear axes' words: the tip's shift plus the tilts' lever arms
  TiltSummary tilt;
};

LocalSummary shift_program(const machine::Model& model, const FirstPart& part, std::istream& program,
                           const interpreter::Setup& setup, const predistort::Provenance& provenance, std::ostream& out,
                           const LocalOptions& options);

}  // namespace vc::shop
