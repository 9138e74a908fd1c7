#include "vc/init/linuxcnc_units.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "vc/init/number.hpp"

namespace vc::init {

LinearUnits read_linear_units(const LinuxcncIni& ini) {
  const IniEntry* linear = ini.find("TRAJ", "LINEAR_UNITS");
  if (!linear)
    throw LoadError(ini.where_missing("TRAJ"),
                    "no [TRAJ]LINEAR_UNITS (LinuxCNC needs it): LINEAR_UNITS = mm or LINEAR_UNITS = inch");
  std::string u = linear->value;
  std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  double per_mm = 0.0;
  const bool number = parse_number(u, per_mm);
  LinearUnits units;
  units.from = ini.cite(*linear);
  if (u == "in" || u == "inch" || u == "imperial" || (number && std::abs(per_mm * 25.4 - 1.0) < 1e-6))
    units.mm_per_unit = 25.4;
  else if (!(u == "mm" || u == "metric" || (number && per_mm == 1.0)))
    throw LoadError(linear->where(), "LINEAR_UNITS = " + linear->value +
                                         " is neither mm nor inch (LinuxCNC's mm, metric, in, inch, imperial, or "
                                         "the units per mm: 1 or 0.03937007874)");
  return units;
}

}  // namespace vc::init
