// Where a volkins configuration stands after homing, against its axes' limits.
//
// LinuxCNC homes each joint to its [JOINT_n]HOME (default 0) and computes the world position
// from the joints with the kinematics module's forward. With volkins that is the joints less
// the correction there: a joint homed exactly at its axis's [AXIS_x]MIN_LIMIT or MAX_LIMIT puts
// the world coordinate up to the correction (a few um) beyond it. LinuxCNC then refuses every
// move that leaves the axis where it is ("Linear move ... would exceed X's positive limit")
// until one takes it inside, and notes "Motion enabled after reaching a coordinate soft limit"
// at each machine-on (its teleop check flags a position >= MAX_LIMIT: even trivkins' exact 0).
// A machine must home inside its soft limits by more than the correction.
//
// Checked in the kinematics type LinuxCNC starts and homes in (volkins' world=, type 0; in the
// TCP world the limits bound the tool tip in the part frame) at the tool length a homing has
// (no G43: offset 0, the machine file's reference length) and the reference temperatures.
#pragma once

#include <string>
#include <vector>

#include "vc/init/volkins_config.hpp"

namespace vc::init {

struct HomedAxis {
  char letter = 'X';  // upper case
  int joint = 0;      // LinuxCNC's joint (the first of its letter)
  // In mm or deg: the INI's lengths are LinuxCNC's units (volkins' units=), converted; the
  // HOME a problem suggests is given back in them.
  double home = 0.0;                           // [JOINT_n]HOME
  double world = 0.0;                          // the world coordinate after homing
  double min_limit = -1e99, max_limit = 1e99;  // [AXIS_x] (LinuxCNC's defaults where missing)
  std::string home_from;                       // "file:line `HOME = 0`" or "[JOINT_0] gives no HOME (0)"
};

struct HomeCheck {
  machine::WorldConvention convention = machine::WorldConvention::Axes;
  std::vector<HomedAxis> axes;        // in the machine file's joint order
  std::vector<std::string> problems;  // one per axis homed beyond a limit: what, where, the fix
};

// Throws vc::LoadError for a HOME or limit that is not a number.
HomeCheck check_home_position(const LinuxcncIni& ini, const machine::Model& model, const VolkinsParameters& volkins);

}  // namespace vc::init
