// Which files of a configuration the other configurations of its folder (the other .ini files
// there) use too: their #INCLUDEs, their HAL files (HALFILE, POSTTASK_HALFILE,
// POSTGUI_HALFILE, found as LinuxCNC finds them) and the files those and their HALCMDs run by
// `source`. The patch copies such a file rather than change it, since changing it would switch
// the other configuration to volkins too (config_patch.hpp).
//
// Read leniently, as a guard: a name that cannot be resolved (an INI reference in a source
// line, a missing file) is passed over; an INI that cannot be read is named in a remark.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "vc/init/linuxcnc_ini.hpp"

namespace vc::init {

struct SharedFiles {
  std::map<std::string, std::string> files;  // absolute path -> "x.ini uses it too"
  std::vector<std::string> inis;             // the other INI files read (absolute)
  std::vector<std::string> remarks;          // the INIs that could not be read
};

SharedFiles files_shared_in_folder(const LinuxcncIni& ini);

}  // namespace vc::init
