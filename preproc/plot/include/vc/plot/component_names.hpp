// What an ISO 230-1 error symbol means, in the words a machine-tool engineer reads on a plot:
// EXX "positioning", EYX "straightness in Y", EAX "roll", EBX "pitch", ECX "yaw", ECC
// "angular positioning", EX0C "position of the C line along x", EC0Y "squareness: Y's line
// turned about z".
#pragma once

#include <string>

#include "vc/tables/symbols.hpp"

namespace vc::plot {

// A component error of a linear axis (X, Y, Z, U, V, W) or a rotary one (A, B, C). Pitch and
// yaw follow the usual horizontal-axis naming (pitch about the other horizontal axis, yaw about
// Z); a vertical axis's two tilts are named by the axis they turn about.
std::string component_meaning(const tables::ErrorSymbol& symbol);

// A location error of an axis line or of the spindle line (axis 'S').
std::string location_meaning(const tables::ErrorSymbol& symbol, bool rotary_axis);

}  // namespace vc::plot
