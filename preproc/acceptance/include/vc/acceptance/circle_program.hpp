// A circular test's G-code program and setup sheet (LinuxCNC, axes world, mm), as the plan writes
// them: the ballbar's start at 0 deg (the plane's first axis), a pause to fit the bar (M1), then
// counterclockwise a 10 deg feed-in, the full turn and a 10 deg feed-out, a dwell, and the same
// clockwise; G17 / G19 / G18 for XY / YZ / ZX (LinuxCNC's G2 and G3 turn right-handed about the
// plane's normal, +Z, +X, +Y: G3 is the increasing angle from the first axis to the second).
#pragma once

#include <string>

#include "vc/acceptance/circles.hpp"
#include "vc/acceptance/plan_file.hpp"
#include "vc/machine/model.hpp"

namespace vc::acceptance {

std::string circle_program(const Plan& plan, const Circle& c, const machine::Model& model);
std::string circle_sheet(const Plan& plan, const Circle& c, const machine::Model& model);

}  // namespace vc::acceptance
