// The patch that puts volkins in place of the stock kinematics in a LinuxCNC configuration: a
// unified diff of the configuration's own files (paths relative to its folder, for
// `patch -p1 -d CONFIG_DIR`), which
// - makes [KINS]KINEMATICS `volkins machine=<file> coordinates=<joints>`, with world=tcp where
//   the stock module's type 0 is TCP (the trt modules, 5axiskins), or sparm=identityfirst where
//   the stock line had it;
// - deletes every `setp <module>.<pin> ...`, removes `<module>.<pin>` from every net (a net
//   left without pins is deleted, with the `sets` of a signal no net is left on; an arrow left
//   dangling goes too; 5axiskins' pivot-length leaves its sum2's out driving nothing), except
//   `<module>.tool-offset`, which becomes `volkins.tool-offset`; a `loadrt <module> ...`
//   with the INI's parameters becomes `loadrt [KINS]KINEMATICS`;
// - appends to the INI's [HAL] section, after a comment line, `HALCMD = addf volkins.update
//   servo-thread 1` and, unless a tool-offset pin became volkins.tool-offset, the net of
//   motion.tooloffset.z to volkins.tool-offset (on the signal motion.tooloffset.z is on, if
//   any).
// Every other line stays byte for byte. Lines that cannot be rewritten that way (another
// command naming a stock pin, a pin in a file outside the folder, a continued line) are
// refused with their file and line.
//
// A file other configurations use too is not changed unless PatchOptions::edit_shared says
// so: an #INCLUDEd file (LinuxCNC's qtplasmac samples include one file from six INIs) and a
// HAL file another INI of the folder uses. The patch creates a copy of it with the edits
// instead (`<name>.volkins<ext>` beside it, or in the configuration folder for an include
// outside it; a diff from /dev/null), and this configuration's line that names the file
// (#INCLUDE, HALFILE, source) names the copy; that line's file may be shared in turn.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "vc/init/hal_file.hpp"
#include "vc/init/kinematics_line.hpp"
#include "vc/init/nominal_machine.hpp"

namespace vc::init {

struct PatchOptions {
  bool edit_shared = false;  // edit shared files in place (volcomp init --edit-shared)
  // HAL files (absolute) other configurations of the folder use too, and which ones.
  std::map<std::string, std::string> shared_hal_files;
};

struct ConfigPatch {
  std::string diff;                  // "" if nothing changes
  std::string kinematics;            // the new [KINS]KINEMATICS value
  std::vector<std::string> changes;  // per file: what changes, for the summary
  std::vector<std::string> created;  // the files the patch creates (absolute): the copies
  std::vector<std::string> remarks;  // for the summary: the copies, and the option that edits in place
};

// machine_path: the machine file as volkins' machine= takes it (relative to the configuration
// folder, or absolute). Throws vc::LoadError (file:line) for what cannot be patched.
ConfigPatch patch_config(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& kinematics,
                         const NominalMachine& machine, const std::string& machine_path,
                         const PatchOptions& options = {});

}  // namespace vc::init
