// The machine file's typical tool (`[spindle] tool_length_mm`): the longest tool of the
// configuration's tool table ([EMCIO]TOOL_TABLE, LinuxCNC's .tbl, read by the interpreter's
// reader), or 0 without one.
#pragma once

#include <string>

#include "vc/init/linuxcnc_ini.hpp"
#include "vc/init/linuxcnc_units.hpp"

namespace vc::init {

struct TypicalTool {
  double length_mm = 0.0;
  std::string from;         // which tool, file:line and the entry, or why 0
  bool unreadable = false;  // the tool table could not be read (`from` says why)
};

// A tool table that cannot be read gives 0 and says why (in `from`). The table is in LinuxCNC's
// length unit; the length returned in mm.
TypicalTool longest_tool(const LinuxcncIni& ini, const LinearUnits& units);

}  // namespace vc::init
