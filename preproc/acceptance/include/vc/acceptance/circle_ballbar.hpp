// A simulated ballbar on a planned circle of a true machine (`volcomp acceptance simulate`).
//
// The centre pivot is where the true machine puts the tool ball (the tool tip at the plan's L)
// with the circle's centre commanded (the set-up: the tool cup locked there), the tool ball where
// it puts it at each angle; the joints are the plan's points, or what volkins commands for them
// with compensation (diagonal_laser.hpp's LaserSimulation: truth, compensation, noise, seed). The
// reading is the distance between the two balls minus the radius, plus Gaussian noise, every
// degree of the full turn counterclockwise, then clockwise; `reversal_mm` adds a reversal spike
// of that height for 3 deg after each axis reversal (an axis's lost motion, as a real ballbar
// shows it: the first axis reverses at 90 and 270 deg, the second at 0 and 180).
#pragma once

#include <string>
#include <vector>

#include "vc/acceptance/diagonal_laser.hpp"
#include "vc/identify/iso230_4.hpp"

namespace vc::acceptance {

inline constexpr int kBallbarPointsPerTurn = 360;

// The run of both directions, as identify's reader returns one.
identify::CircularTest simulate_circle(const Plan& plan, const Circle& c, const LaserSimulation& sim, int circle_index);

// The ballbar software's export: `# key: value` lines (the comments, plane, radius, tool length,
// centre as the joints x=.., y=..) and angle[deg],direction,deviation[um].
std::string ballbar_csv(const Plan& plan, const Circle& c, const machine::Model& model, const identify::CircularTest& test,
                        const std::vector<std::string>& comments);

}  // namespace vc::acceptance
