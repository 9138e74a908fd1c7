// How finely a move is cut into samples or pieces (shared by the simulation and the
// self-tuning's path shift).
#pragma once

#include "vc/interpreter/move.hpp"

namespace vc::shop {

// Pieces of a move: at most step_mm long, chords of an arc straying less than
// chord_tolerance_mm from it, rotary axes turning at most step_deg per piece.
// Length of the tool-tip path of a move in program coordinates (mm): arcs along the arc.
double path_length(const interpreter::Move& m);

int piece_count(const interpreter::Move& m, double step_mm, double chord_tolerance_mm, double step_deg);

}  // namespace vc::shop
