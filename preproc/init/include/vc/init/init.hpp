// `volcomp init`: a user's LinuxCNC configuration -> a machine file with the nominal geometry
// of its kinematics (zero errors) and the patch that loads volkins in place of the stock
// module. Reads only; the caller writes the outputs. Everything is checked before anything
// is returned, so a refusal (vc::LoadError, file:line) leaves nothing half done.
#pragma once

#include <string>
#include <vector>

#include "vc/init/config_patch.hpp"
#include "vc/init/nominal_machine.hpp"
#include "vc/init/output_check.hpp"

namespace vc::init {

struct InitRequest {
  std::string ini;           // the configuration's INI file
  std::string machine_file;  // where the machine file will be written (as given: -o)
  std::string date;          // YYYY-MM-DD, for the machine file's header
  bool edit_shared = false;  // edit shared files in place (--edit-shared) instead of copying them
};

struct InitResult {
  std::string folder;  // the configuration folder
  NominalMachine machine;
  std::string machine_text;  // the machine file (TOML)
  std::string machine_path;  // the machine file as volkins' machine= names it
  ConfigPatch patch;
  std::vector<std::string> not_read;  // HAL files init could not read (Tcl), and where they are named
  std::vector<InputFile> inputs;      // every file init read or looked for: never an output
  std::vector<std::string> remarks;   // for the summary: the patch's copies of shared files, INIs not read
};

InitResult run_init(const InitRequest& request);

// How volkins' machine= names `machine_file` for a configuration in `folder`: relative to it
// when the file lies inside it (the configuration may be moved with it), else absolute.
std::string machine_parameter(const std::string& machine_file, const std::string& folder);

}  // namespace vc::init
