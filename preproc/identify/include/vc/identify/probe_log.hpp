// The log a probe_plan program writes: one line per probe trip,
//     POINT <pose> <rotary positions...> <#5061> <#5062> <#5063> <G54 X> <G54 Y> <G54 Z>
// after a header "# volcomp probe log: ..." with the sphere's and the ball's diameters and the
// probe length. The trips of one pose lie on a sphere of radius (sphere + ball) / 2 about the
// centre, in the part frame: the trips are carried there through the model's real machine
// (with its linear axes' errors, at the probe length), the sphere fitted by least squares
// (Gauss-Newton) and its centre carried back to the joints; its residual per point reported, a pose
// whose points do not lie on that sphere (another sphere, a wrong diameter, a bad trip: a
// residual over `tolerance`) refused with its line.
#pragma once

#include <string>
#include <vector>

#include "vc/identify/sphere_centres.hpp"
#include "vc/machine/model.hpp"

namespace vc::identify {

struct ProbeLog {
  double sphere_diameter_mm = 0.0, ball_diameter_mm = 0.0, probe_length_mm = 0.0;
  std::vector<SpherePose> centres;   // one per pose, joints at the fitted centre
  double largest_residual_um = 0.0;  // of a point from its fitted sphere
};

// Throws vc::LoadError (file:line) for what it cannot read or fit.
ProbeLog read_probe_log(const std::string& path, const machine::Model& model, double tolerance_mm = 0.005);

}  // namespace vc::identify
