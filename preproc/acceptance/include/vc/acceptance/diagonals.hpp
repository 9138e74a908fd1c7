// The ISO 230-6 diagonal displacement tests of a machine with linear X, Y, Z axes: the four body
// diagonals of the work volume (corner to opposite corner) and two diagonals of each of the XY,
// YZ and ZX faces through the volume's centre, each measured by a laser along the line as ISO
// 230-2 measures an axis: targets along the line, 5 bidirectional runs, an overrun before each
// reversal, a dwell at each target for the reading.
//
// Names: a body diagonal by its start and end corners, N (the low end) or P (the high end) of
// X, Y, Z in that order ("body-NNN-PPP": from x0,y0,z0 to x1,y1,z1); a face diagonal by its face
// and the corners of the face's two axes in the face's order ("face-YZ-NP-PN": Y from low to
// high, Z from high to low, X at the centre). Every diagonal starts at the low end of X (body,
// XY) or of its face's first axis, so its distances grow with that axis.
//
// Targets (ISO 230-2 practice, off the compensation tables' nodes, ISO/TR 16907 11.3 L915):
// the first at the start (distance 0, where the laser is zeroed), the last at the end (its
// length rounded to 1 um), the
// others at the even spacing p plus a pseudo-random offset in [-p/4, p/4] (a fixed generator
// and seed: the same plan every time), rounded to 1 um.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "vc/acceptance/work_volume.hpp"
#include "vc/machine/model.hpp"

namespace vc::acceptance {

struct DiagonalSettings {
  WorkVolume volume;
  double tool_length_mm = 100;  // L of the tool-side optic below the spindle gauge point
  double feed_mm_per_min = 1000;
  double dwell_s = 2;
  double overrun_mm = 5;  // past the first and last targets before each reversal
  int runs = 5;           // bidirectional
  int targets = 11;       // per diagonal, ends included
  unsigned seed = 1;      // of the targets' offsets
  std::string which = "all";  // "all", "body" (the four body diagonals), "face" (the six face ones) or "none"
};

struct Diagonal {
  std::string name;  // body-NNN-PPP, face-XY-NN-PP, ...
  std::string kind;  // "body" or "face XY" / "face YZ" / "face ZX"
  Eigen::Vector3d start_mm, end_mm;  // X, Y, Z joints
  std::vector<double> targets_mm;    // distance from the start along the line, ascending

  double length_mm() const { return (end_mm - start_mm).norm(); }
  Eigen::Vector3d direction() const { return (end_mm - start_mm).normalized(); }  // in X, Y, Z joints
  Eigen::Vector3d at(double distance_mm) const { return start_mm + distance_mm * direction(); }
  bool axis_run() const { return kind.rfind("axis ", 0) == 0; }  // an ISO 230-2 run along an axis
};

// The 10 diagonals, or the body or face ones (settings.which: each with the targets it has among
// all 10); throws std::runtime_error for settings that cannot make them (fewer than 5 targets or
// 2 runs, overruns leaving the travel, a feed or dwell not > 0, an unknown `which`).
std::vector<Diagonal> plan_diagonals(const machine::Model& model, const DiagonalSettings& settings);

// ISO 230-2's linear positioning runs, laser lines of the same kind as the diagonals: one per axis
// of `axes` ("X,Y,Z", any subset, or "none"), along it from the volume's low end to its high end
// through the volume's centre; named "axis-X", kind "axis X", targets as the diagonals' (their
// generators after the diagonals'). Throws std::runtime_error as plan_diagonals, or for an
// unknown axis.
std::vector<Diagonal> plan_axis_runs(const machine::Model& model, const DiagonalSettings& settings,
                                     const std::string& axes);

// The joints at a point of a diagonal: `rest` (every joint; the rotary ones at 0) with X, Y, Z
// set to `xyz_mm`.
machine::Joints joints_at(const machine::Model& model, const machine::Joints& rest, const Eigen::Vector3d& xyz_mm);

// Every joint at 0 but X, Y, Z at the volume's centre; a rotary axis whose travel excludes 0 is
// refused (std::runtime_error).
machine::Joints rest_joints(const machine::Model& model, const WorkVolume& volume);

}  // namespace vc::acceptance
