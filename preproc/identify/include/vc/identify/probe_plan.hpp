// The probing program for `identify sphere`: a LinuxCNC G-code program that probes a sphere on
// the table at a set of rotary positions with G38.2 (5 points each: the top, then +X -X +Y -Y
// on the equator) and logs every trip with (LOGOPEN)/(LOG) and LinuxCNC's probe results
// #5061-#5063, so that `identify sphere` reads the log (probe_log.hpp). It runs with the
// compensation off (volkins.enable 0, or trivkins), in G54 with the tool length offset off
// (G49): the log carries G54's offsets, so the joints of each trip are known whatever G54 is.
//
// Where the sphere is at each pose comes from where it is at B0 C0 (the DRO when the probe
// tip is jogged to its top, minus the radii: `centre`), carried through the ideal machine:
// the same point of the table, the rotary axes turned. Rapids go through a safe height in
// machine coordinates (G53) and over the sphere; each point is a search starting `clearance`
// off the surface (2 x clearance long, at the probe feed), a back-off and a slow measuring
// touch (2 x back-off long, at the touch feed), whose trip is logged: LinuxCNC takes the
// position of the servo cycle in which it sees the probe input, up to feed x period late.
#pragma once

#include <string>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::identify {

struct ProbePlanOptions {
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();  // joints X Y Z of the sphere's centre at rotary 0
  double sphere_diameter_mm = 25.0;
  double ball_diameter_mm = 2.0;  // the probe's stylus ball
  double probe_length_mm = 0.0;   // gauge point to ball centre (0: the machine file's tool length)
  double clearance_mm = 3.0;
  double safe_z_mm = 0.0;                             // machine Z of the rapids (default: the top of Z's travel)
  double probe_feed_mm_min = 100.0;                   // the search for the surface
  double back_off_mm = 0.3;                           // after the search, before the measuring touch
  double touch_feed_mm_min = 10.0;                    // the measuring touch (what is logged)
  double rapid_feed_mm_min = 2000.0;                  // the moves between the probe points
  std::vector<std::vector<double>> rotary_positions;  // per pose, the rotary axes in joint order (deg)
  std::string log_file = "volcomp_sphere_probe.txt";
};

// The program's text. Throws std::runtime_error for a pose whose moves leave the travel.
std::string probe_plan(const machine::Model& model, const ProbePlanOptions& options);

}  // namespace vc::identify
