// A LinuxCNC configuration that loads volkins, as the checks of its limits read it: the module's
// parameters, which LinuxCNC joint drives each axis of the machine file, and the INI's numbers.
#pragma once

#include <cmath>
#include <string>
#include <string_view>

#include "vc/init/linuxcnc_ini.hpp"
#include "vc/init/linuxcnc_units.hpp"
#include "vc/machine/kinematics.hpp"

namespace vc::init {

// What [KINS]KINEMATICS asks of volkins: coordinates= (LinuxCNC's axis letters, one per joint;
// empty: the machine's own order), world= (type 0's convention) and units= (LinuxCNC's length
// unit: the joints, the world and the tool length offset motion passes; the machine file is in mm).
struct VolkinsParameters {
  std::string machine;  // machine=: the machine file, made absolute against the configuration folder ("" if none)
  std::string coordinates;
  machine::WorldConvention world = machine::WorldConvention::Axes;
  LinearUnits units;  // from units=mm|inch (default mm), cited as the KINEMATICS line
};
// Throws vc::LoadError where KINEMATICS does not load volkins, or where its units= is not the
// INI's [TRAJ]LINEAR_UNITS (volkins would read every joint 25.4 times off).
VolkinsParameters read_volkins_parameters(const LinuxcncIni& ini);

// LinuxCNC's joint of the machine file's joint `j`: the first of its letter in coordinates=.
int linuxcnc_joint(const VolkinsParameters& volkins, const machine::Model& model, int j);

// The INI's number `key` in `section`, or `otherwise` where it is missing; `from` (optional)
// receives the citation. Throws vc::LoadError for a value that is not a number.
double ini_number(const LinuxcncIni& ini, std::string_view section, std::string_view key, double otherwise,
                  std::string* from = nullptr);

// Beyond a limit by less than this (mm or deg) is the kinematics solvers' noise (their tolerance
// is 1e-10 mm), not a finding of the limit checks.
inline constexpr double kLimitNoise = 1e-9;

// LinuxCNC's limits where the INI gives none are +-1e99: a limit this large is none (a
// continuous rotary axis).
inline constexpr double kNoLimit = 1e98;
inline bool no_limit(double limit) { return !(std::abs(limit) < kNoLimit); }

// A limit or HOME the checks suggest is a multiple of this, in the INI's units: 0.1 mm or deg,
// 0.01 inch.
inline double limit_step(const VolkinsParameters& volkins, bool rotary) {
  return rotary || !volkins.units.inch() ? 0.1 : 0.01;
}

// A small length or angle for messages: "5.24 um", "1.20 mdeg" (v in mm or deg).
std::string um_or_mdeg(double v, bool rotary);

}  // namespace vc::init
