// Writes a NominalMachine as a machine file (TOML, machines/README.md section 3): a header
// saying what it is and what to do next, every value with a comment naming where it came from,
// no [correction] (the defaults), no tables, no location errors.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "vc/init/nominal_machine.hpp"

namespace vc::init {

struct MachineFileOrigin {
  std::string ini;                    // the INI file it is generated from
  std::string date;                   // YYYY-MM-DD
  std::vector<std::string> not_read;  // files of the configuration init did not read, and why
};

void write_machine_file(const NominalMachine& machine, const MachineFileOrigin& origin, std::ostream& out);

}  // namespace vc::init
