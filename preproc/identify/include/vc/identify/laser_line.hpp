// What a laser on a line reads, through the model, and the error table that makes the model
// read what the laser read (preproc/identify/README.md, "What each instrument reads").
//
// A reading is the tool against the part: the tool-side optic (a point of the spindle frame)
// relative to the part-side optic (any point of the part frame: the part is rigid), real
// machine against ideal machine, in the part frame:
// - a translation (EXX positioning, EYX / EZX straightness) is the optic's displacement, read
//   along the measured axis's own motion for its positioning (readings grow with +X: the tool
//   moves +X against the part, ideal machine, at the run's pose) and along the part frame's
//   y or z for a straightness;
// - a rotation (EAX, EBX, ECX) is the tool's turn against the part about the part frame's x, y
//   or z (right-handed); a rotary axis's positioning (ECC against an angular reference) about
//   the axis's own ideal turn of the tool against the part (readings grow with +C).
// On an ISO 841 machine at its rotary axes' zero the part frame's x, y, z are the X, Y, Z
// motions, so both rules agree. The reading sees every error of the machine at the line:
// the other axes' errors where they stand, the Abbe terms of the optic's offset.
//
// Load time: allocates.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "vc/machine/model.hpp"
#include "vc/tables/symbols.hpp"

namespace vc::identify {

// Where a laser run was made.
struct LaserSetup {
  int joint = -1;                            // the axis that moved (the one whose error is measured)
  tables::ErrorSymbol error{0, 'X', false};  // what the optics measure
  machine::Joints at;                        // every joint where it stood; the moving joint's value is the target
  Eigen::Vector3d tool_point_mm = Eigen::Vector3d::Zero();  // the tool-side optic in the spindle frame, from
                                                            // the gauge point: (0, 0, -L) at a tool's tip
};

// "x=0, y=-160, z=-150, b=0, c=0" (commas or blanks between): every joint of `model` but the
// moving one must be given (its value, if given, is unused). Throws std::runtime_error naming
// what is missing or unreadable.
machine::Joints parse_axis_positions(const machine::Model& model, int moving_joint, const std::string& text);

// The reading (mm or rad) at `target` (mm or deg of the moving joint) on `model`.
double laser_reading(const machine::Model& model, const LaserSetup& setup, double target);

// How the runs are referenced (ISO 230-1): what of them the file takes as it is.
enum class Reference {
  None,          // the readings as they are (positioning, angular: the default)
  Datum,         // the laser zeroed at the first (lowest) target, the file's value there unknown
                 // to it: the file keeps its own value there (an origin shift of the runs)
  LeastSquares,  // straightness (the default): the table about its least-squares line (zero slope),
                 // the runs' slope a squareness, put into one location error of the file
  EndPoints,     // straightness: the same about the line through its first and last nodes
};
Reference default_reference(const tables::ErrorSymbol& error, bool rotary_axis);
const char* reference_name(Reference r);

// A straight line fitted to `values` at `targets`: value = offset + slope * (target - targets.front()).
struct ReferenceLine {
  double offset = 0.0, slope = 0.0;
  std::vector<double> at;  // at each target
};
ReferenceLine reference_line(const std::vector<double>& targets, const std::vector<double>& values, Reference r);

// What the solve may change: a column of a linear 1-D table over the moving joint whose nodes
// are the targets, ascending (a periodic one's last node is its first), and, for a referenced
// straightness, one location error (a rotation: the squareness) with the table's slope held 0.
struct LineUnknowns {
  int table = -1, column = 0;
  int squareness_joint = -1, squareness_component = -1;  // 3..5: EA0, EB0, EC0 of that joint
  Reference reference = Reference::None;                 // LeastSquares or EndPoints: the slope rule
};

// Sets the unknowns of `model` so that it reads `readings` at `targets` (least squares where a
// full turn reads 0 and 360 deg twice). Throws std::runtime_error when a reading does not depend
// on them (the line cannot see the error) or the solve does not converge.
struct LineSolution {
  std::vector<double> values;   // the column, node by node (mm or rad)
  double squareness_rad = 0.0;  // the location error, if one was solved for
  int iterations = 0;
  double largest_residual = 0.0;  // of the readings, mm or rad
};
LineSolution solve_line(machine::Model& model, const LineUnknowns& unknowns, const LaserSetup& setup,
                        const std::vector<double>& targets, const std::vector<double>& readings);

// Sets a rotation location error (component 3..5) of a joint's line in `model`.
void set_location_rotation(machine::Model& model, int joint, int component, double rad);

}  // namespace vc::identify
