// Whether a volkins configuration's joint limits leave room for the correction.
//
// volkins sends the joints q_c = correct(q_n): at the ends of an axis's travel they lie up to
// the correction there (tens of um, more with a long tool) beyond the nominal joints q_n, which
// the world's [AXIS_x] limits bound. A joint whose [JOINT_n] MIN_LIMIT / MAX_LIMIT are the axis's
// own (as stock configurations have them, and `volcomp init` leaves them) makes LinuxCNC refuse
// a program's move to the end of the travel ("Linear move on line N would exceed joint 1's
// positive limit": LinuxCNC 2.9 checks a move's end through the inverse kinematics). The joint
// limits must lie beyond the axis limits by more than the correction.
//
// Sampled: every joint at 5 levels over its axis's limits, within its joint's (all combinations;
// where an axis has no limits, the machine file's travel), at the tool lengths 0 and the machine file's typical
// one (plus its reference length), at the reference temperatures.
//
// The fix it advises is the line that causes the problem: an axis whose [AXIS_x] limit lies
// within the correction of its joint's (or beyond it: LinuxCNC's xyzbc-trt sample gives B
// +-36000 over a joint of -100 .. 50) is narrowed to leave the joint that room. A rotary axis
// with stops never gets a widened joint limit; for a linear one, widening the joint limit is
// named as the alternative that is only right where the machine has that travel before its
// limit switch. A joint without limits (LinuxCNC's +-1e99: a continuous table) needs no room.
// The INI's numbers are in LinuxCNC's units (volkins' units=): converted to mm before they meet
// the model, and the advised values given back in the INI's units.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "vc/init/volkins_config.hpp"

namespace vc::init {

struct JointRoom {
  char letter = 'X';
  int joint = 0;                               // LinuxCNC's (every joint of the letter is checked)
  double min_limit = -1e99, max_limit = 1e99;  // [JOINT_n], mm or deg (the INI's units converted)
  double lowest = 0.0, highest = 0.0;          // the corrected joint over the samples
};

struct JointRoomCheck {
  std::vector<JointRoom> joints;            // one per LinuxCNC joint that drives an axis of the model
  int poses = 0;                            // corrections evaluated
  std::array<double, 2> tool_lengths_mm{};  // the L they were evaluated at
  std::vector<std::string> problems;        // one per joint limit the correction crosses: where, the fix
};

// Throws vc::LoadError for a limit that is not a number.
JointRoomCheck check_joint_room(const LinuxcncIni& ini, const machine::Model& model, const VolkinsParameters& volkins);

}  // namespace vc::init
