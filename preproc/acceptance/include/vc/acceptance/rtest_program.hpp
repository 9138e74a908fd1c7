// The R-test's program and setup sheet (LinuxCNC, axes world, mm), as the plan writes them:
// G43.1 with the nest's L, then for each pose of each sequence a rapid to its retract (the nest
// kRTestRetractMm back along the tool from the sphere), a G1 onto the sphere, a dwell for the
// reading, the G1 back. Between poses the nest moves at the retract, in joint space: this is the
// static R-test (discrete poses), not ISO 10791-6's dynamic one following the sphere (TCP).
#pragma once

#include <string>

#include "vc/acceptance/plan_file.hpp"
#include "vc/machine/model.hpp"

namespace vc::acceptance {

std::string rtest_program(const Plan& plan, const machine::Model& model);
std::string rtest_sheet(const Plan& plan, const machine::Model& model);

}  // namespace vc::acceptance
