// The ISO 230-4 circular tests of a machine with linear X, Y, Z axes: a ballbar's circle in each
// of the XY, YZ and ZX planes, about the work volume's centre, run counterclockwise and clockwise
// (each a full turn from the plane's first axis), with the tool-side ball's offset declared as the
// active tool length (ISO/TR 16907 11.3 a, L548, L919; identify circle's CircleSetup).
//
// Angles, directions and readings as `volcomp identify circle` reads them: from the plane's first
// axis towards its second (XY: X to Y, YZ: Y to Z, ZX: Z to X), ccw the increasing angle; the
// reading the ballbar's length minus its nominal length (+: longer).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "vc/acceptance/work_volume.hpp"
#include "vc/machine/model.hpp"

namespace vc::acceptance {

// The standard ballbar lengths (mm) a radius is chosen from when none is given.
inline constexpr double kBallbarLengthsMm[] = {50, 100, 150, 300};

struct Circle {
  std::string name;       // circle-XY, circle-YZ, circle-ZX
  std::string plane;      // XY, YZ, ZX
  Eigen::Vector3d centre_mm;  // X, Y, Z joints
  double radius_mm = 0;
  // The plane's first and second axes as X, Y, Z indices (XY: 0, 1; YZ: 1, 2; ZX: 2, 0).
  int first() const;
  int second() const;
  // The point at `angle_rad` from the first axis towards the second, in X, Y, Z joints.
  Eigen::Vector3d at(double angle_rad) const;
};

// The circles of `planes` ("XY,YZ,ZX", any subset in any order, or "none": no circle) about the
// volume's centre. radius_mm 0: the longest standard ballbar that fits in the volume in both of
// the plane's axes. Throws std::runtime_error for an unknown plane or a radius that leaves the
// volume.
std::vector<Circle> plan_circles(const WorkVolume& volume, const std::string& planes, double radius_mm);

}  // namespace vc::acceptance
