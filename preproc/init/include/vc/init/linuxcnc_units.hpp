// The length unit a LinuxCNC configuration runs in, [TRAJ]LINEAR_UNITS: the joints and their
// limits, the axes' limits, HOME, the tool table, the tool length offset (motion.tooloffset.z)
// and every position motion hands the kinematics are in it. The machine file and its tables
// are in mm, as they declare; this is where a configuration's lengths become mm (init, check
// --ini, trace, predistort's --start) and volkins' units= parameter says the same to the module.
#pragma once

#include <string>

#include "vc/init/linuxcnc_ini.hpp"

namespace vc::init {

struct LinearUnits {
  double mm_per_unit = 1.0;  // 25.4: inch
  std::string from;          // the LINEAR_UNITS line, cited ("" where the INI has none)

  bool inch() const { return mm_per_unit != 1.0; }
  // volkins' units= and volcomp's --machine-units: "mm" or "inch".
  const char* name() const { return inch() ? "inch" : "mm"; }
  double to_mm(double length) const { return length * mm_per_unit; }
};

// [TRAJ]LINEAR_UNITS as LinuxCNC 2.9 takes it (inifile.cc's linear units map: mm, metric, in,
// inch, imperial; or the number of units per mm, 1 or 1/25.4), case as LinuxCNC ignores it.
// Throws vc::LoadError where it is missing (LinuxCNC refuses to start without it) or names
// another unit.
LinearUnits read_linear_units(const LinuxcncIni& ini);

}  // namespace vc::init
