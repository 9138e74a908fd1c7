// The circular test (ISO 230-4; a ballbar such as the QC-10): the radius deviations dR(phi)
// of a circle of radius R run clockwise and counterclockwise in one plane, evaluated as
// ISO 230-4 does and fitted, first order (seed 000, section 3.2, circular test),
// with actual x' = x (1 + ex) + theta y, y' = y (1 + ey) and the circle's centre off by (cx, cy):
//     dR(phi) = -cx cos phi - cy sin phi + R (ex cos^2 phi + ey sin^2 phi) + R theta sin phi cos phi
// (x, y: the plane's first and second axes: X Y in XY, Y Z in YZ, Z X in ZX).
//
// The file, a CSV a spreadsheet opens, in either layout:
//     # plane: XY          # radius_mm: 150     (metadata lines, as in laser runs)
//     angle[deg],direction,deviation[um]        direction ccw / cw (or +, -)
//     angle[deg],ccw[um],cw[um]
// Angles measured from the plane's first axis towards its second; deviation = measured
// radius - nominal radius (+: the ball bar longer).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::identify {

struct CircleRun {
  bool ccw = true;
  std::vector<std::pair<double, double>> points;  // angle (rad), radius deviation (mm), by angle
};

struct CircularTest {
  std::string path;
  std::string plane = "XY";  // XY, YZ or ZX
  double radius_mm = 0.0;
  std::vector<CircleRun> runs;  // one per direction present
  std::vector<std::pair<std::string, std::string>> metadata;
};

// Throws vc::LoadError with file:line:column.
CircularTest read_circular_test(const std::string& path);

struct CircleFit {
  bool ccw = true;
  double centre_first_mm = 0.0, centre_second_mm = 0.0;  // cx, cy
  double mean_scale = 0.0;                               // (ex + ey) / 2
  double scale_mismatch = 0.0;                           // ex - ey
  double squareness_rad = 0.0;                           // theta: x' = x + theta y
  double circular_deviation_mm = 0.0;                    // G: max - min of dR about the least-squares centre
  double radial_deviation_mm = 0.0;                      // F: max |dR| about the nominal centre
  double residual_rms_mm = 0.0;                          // after the fit (what the first-order model leaves)
  // Reversal spikes: where an axis reverses (the plane's first axis at 90 and 270 deg, its
  // second at 0 and 180 deg), the residual's peak within 6 deg above the residual around it.
  std::vector<std::pair<double, double>> spikes;  // angle (deg), height (mm)
};

struct CircularEvaluation {
  std::vector<CircleFit> fits;         // per direction
  double circular_deviation_mm = 0.0;  // G(b): both directions together about one centre
  double hysteresis_mm = 0.0;          // H: max |dR_cw - dR_ccw| at the same angle
  double squareness_rad = 0.0;         // the directions' mean (the reversal cancels)
  double scale_mismatch = 0.0;
};

// Throws std::runtime_error when the runs cannot support the fit (fewer than 12 points, or
// not spread over the full circle: the squareness needs the whole turn).
CircularEvaluation evaluate_circular_test(const CircularTest& test);

// The squareness fitted from dR, in a machine file's own terms: for each location error that
// tilts the plane's axes against each other (XY: EC0X, EC0Y; YZ: EA0Y, EA0Z; ZX: EB0X, EB0Z),
// the value that makes the file, with every other error as it is, show the measured
// squareness: the file's own squareness (its lines and its tables' slopes: a straightness
// table with a slope is a squareness too) is found by simulating the circle on the model (about
// the setup's centre, at its tool length), and the term takes the difference,
// by what one radian of it alone makes there. One squareness in the file, however many
// instruments measured it; the file's convention and chain decide the sign, not this code.
// Where the circle ran, for simulating it on the model: the joints at its centre (rotary axes
// where they stood) and the tool-side ball's offset from the spindle's gauge point along the
// tool, declared as the active tool length while it ran. ISO/TR 16907 requires the offset
// declared wherever L-ANG, R-ANG, L-VOL or R-VOL is on (L548, L919): an angular error moves the
// ball by its Abbe arm, so a pitch that grows along an axis shows as a squareness that grows with
// the offset, and the file's share of the measured squareness is only known at the ball's offset.
struct CircleSetup {
  machine::Joints centre;
  double tool_length_mm = 0.0;
};
// The middle of the travel, rotary axes at 0, the machine file's tool length.
CircleSetup default_circle_setup(const machine::Model& model);

struct SquarenessTerm {
  std::string symbol;          // e.g. EC0Y
  double value_rad;            // its value for the measured squareness, the file's other errors as they are
  double in_file_rad;          // its value in the machine file now
  double file_squareness_rad;  // the squareness the file shows now (all its errors)
};
std::vector<SquarenessTerm> squareness_terms(const machine::Model& model, const std::string& plane, double radius_mm,
                                             double squareness_rad, const CircleSetup& setup);

}  // namespace vc::identify
