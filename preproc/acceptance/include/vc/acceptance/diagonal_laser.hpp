// A simulated laser along a planned diagonal on a true machine (`volcomp acceptance simulate`).
//
// At each target the joints are the nominal ones, q = the plan's point (compensation off), or
// what volkins commands for it (compensation on with FILE: the core's correction of FILE at q,
// vc/machine/correct.hpp, for the plan's L). The laser reads the true tool-side optic's
// displacement (the tool tip at L on the true machine, part frame) projected on the line's
// direction (the ideal machine's, part frame), relative to its reading at the start point
// (distance 0: where it was zeroed, with the same joints as target 1); the deviation is that
// reading minus the target's distance (error = actual - nominal), plus Gaussian noise of
// `noise_mm` per reading (std::mt19937_64 and Box-Muller: the same numbers on every platform).
// The model has no reversal (backlash): `reversal_mm` adds one as the drives' lost motion shows in
// a laser's runs, + readings by reversal / 2 and - readings by - reversal / 2 (simulate-laser-runs'
// rule), so that B reads it; 0: both directions read alike but for the noise.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vc/acceptance/plan_file.hpp"
#include "vc/identify/laser_runs.hpp"

namespace vc::acceptance {

struct LaserSimulation {
  const machine::Model* truth = nullptr;
  const machine::Model* compensation = nullptr;  // null: off
  double noise_mm = 0;
  double reversal_mm = 0;
  std::uint64_t seed = 1;
};

// The readings of every run and direction, in the order the program makes them.
std::vector<identify::Reading> simulate_diagonal(const Plan& plan, const Diagonal& d, const LaserSimulation& sim,
                                                 int diagonal_index);

// The laser software's export: the long layout of laser_runs.hpp with "# key: value" lines.
std::string laser_csv(const Diagonal& d, const std::vector<identify::Reading>& readings,
                      const std::vector<std::string>& comments);

}  // namespace vc::acceptance
