// A diagonal's G-code program and its setup sheet.
//
// The program (LinuxCNC, axes world: program coordinates are the nominal joints, minus the tool
// length offset on Z): G21 G90, the tool-side optic's length declared by G43.1 Z (L -
// tool_length_reference_mm, so volkins corrects for the optic: machines/README.md, the
// tool-length rule), the rotary axes to 0, then `runs` bidirectional runs of the ISO 230-2 cycle
// along the line: from the overrun before the start, G1 at the feed to each target with a G4
// dwell for the reading, on to the overrun past the last target, back over the targets the other
// way with the same dwells, and to the overrun before the start again, so every target is
// approached from the same side in each direction.
#pragma once

#include <string>

#include "vc/acceptance/plan_file.hpp"

namespace vc::acceptance {

std::string diagonal_program(const Plan& plan, const Diagonal& d, const machine::Model& model);

// The setup sheet (Markdown): where the laser and the tool-side optic go, the tool length to
// declare, feed, dwell, targets, runs, what to export.
std::string diagonal_sheet(const Plan& plan, const Diagonal& d, const machine::Model& model);

// The plan's index page (Markdown): the tests, their files, what the programs assume.
std::string plan_index(const Plan& plan, const machine::Model& model);

}  // namespace vc::acceptance
