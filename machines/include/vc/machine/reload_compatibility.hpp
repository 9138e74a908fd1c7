// Whether a new machine file may replace the running one under a homed machine (volkins'
// reload, issue 46): the nominal kinematics (joint -> world of the ideal machine) must not
// change, since LinuxCNC's positions, homes and queued moves are in them; the error tables and
// deviations may. Pure: no I/O, no exceptions.
#pragma once

#include <string>

#include "vc/machine/model.hpp"

namespace vc::machine {

// Nominal lengths (mm) and direction components agree within this.
inline constexpr double kReloadNominalTolerance = 1e-12;

// Empty if `candidate` may replace `running`; else what differs, for the message
// "<candidate's file>: <what differs>". Compared: the axes (count, letters in joint order,
// linear/rotary, tool/workpiece chain and the chains' order), the tool-axis coordinate, the
// temperature inputs' names in order (volkins' HAL pins), and the nominal geometry within
// kReloadNominalTolerance: each axis's direction and pole, the spindle's gauge point, the
// fixture, and tool_length_reference_mm (the nominal TCP kinematics' tool length).
std::string reload_incompatibility(const Model& running, const Model& candidate);

}  // namespace vc::machine
