// One diagonal's laser runs (the laser software's export, laser_runs.hpp's long or wide
// layout: target[mm],run,direction,deviation[um]) read and checked against the plan before
// anything is evaluated: every reading at one of the plan's targets, every run reading every
// target once and both ways (the plan's runs are bidirectional), at least 2 runs in each
// direction (ISO 230-2 asks for 5). Each refusal is a
// LoadError at the file and line concerned.
#pragma once

#include <string>

#include "vc/acceptance/diagonals.hpp"
#include "vc/identify/laser_runs.hpp"

namespace vc::acceptance {

// The runs of `path` for `d`, their targets set to the plan's values (a reading within 0.5 um of
// a target is at it: the export rounds).
identify::LaserRuns read_diagonal_runs(const std::string& path, const Diagonal& d);

}  // namespace vc::acceptance
