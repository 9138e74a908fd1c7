// LinuxCNC's COMP_FILEs replayed on a session recorded without any correction (stock
// kinematics, or volkins with its gain 0 throughout; axes world: the joints are the commanded
// axes): the tool-tip error each checked sample would have had with the tables loaded, as
// LinuxCNC applies them period by period (LinuxcncCompJoint: direction from the commanded
// velocity, held while a joint stands, 0 until it first moves (the homing's move to HOME
// included), through LinuxCNC's ramp).
// Session tests show the replay equals a real stock session with the tables to 0 um at every
// sample (tests/session/stock_tables_session_test.cpp), so the main job can show the tables'
// effect without a session of its own per table set.
#pragma once

#include <vector>

#include "vc/fit_tables/comp_file.hpp"
#include "vc/machine/model.hpp"
#include "vc/trace/session_trace.hpp"

namespace vc::fit_tables {

// What the replay takes from a joint's [JOINT_n]: the limits LinuxCNC's ramp of the correction
// uses, and the homing's final move. With HOME_SEARCH_VEL = 0 LinuxCNC takes the joint's
// position to be HOME_OFFSET and then moves it to HOME: a COMP_FILE's correction is active from
// that move on (the reverse value at HOME if HOME is below HOME_OFFSET), before the session's
// first sample.
struct JointLimits {
  double max_velocity = 0.0, max_acceleration = 0.0;  // units/s, units/s^2
  int homing_move = 0;                                // the move to HOME: +1 up, -1 down, 0 none (HOME = HOME_OFFSET)
};

struct CompReplay {
  std::vector<double> tip_error_um;  // per checked sample of `summary`, |e|
  std::vector<bool> settled;         // per checked sample: every joint carries its table's value
};

// `comps`, `limits`: per joint (an empty LinuxcncComp: no table on that joint). Throws
// std::invalid_argument if their sizes are not the model's joint count, or the trace has a
// correction active (volkins' gain not 0) somewhere.
CompReplay replay_comp_files(const machine::Model& model, const trace::SessionTrace& session,
                             const trace::TraceSummary& summary, const std::vector<LinuxcncComp>& comps,
                             const std::vector<JointLimits>& limits, double servo_period_s);

}  // namespace vc::fit_tables
