// LinuxCNC's own files that decide how a program maps to the machine: the parameter file
// (.var: work offsets, G28/G30 homes) and the tool table (tool lengths). Read as LinuxCNC
// reads them; a line that cannot be read is refused with file:line:column.
#pragma once

#include <map>
#include <string>

#include "vc/gcode/parameters.hpp"

namespace vc::interpreter {

struct Tool {
  int number = 0;
  double z_offset = 0.0;   // tool length offset, machine units (mm here)
  double diameter = 0.0;   // D column, machine units; 0 if absent
  // The first of X Y A B C U V W that holds a non-zero offset (0: none). LinuxCNC's G43 applies
  // those too (a lathe tool's X); the pre-distorter takes Z only and refuses G43 with others.
  char other_offset = 0;
};
using ToolTable = std::map<int, Tool>;

// Lines "T<n> P<pocket> [X.. Y.. Z.. A.. B.. C.. U.. V.. W.. D.. I.. J.. Q..] [;comment]".
ToolTable read_tool_table(const std::string& path);

// Lines "<number> <value>" (LinuxCNC writes them sorted; anything else is refused). Sets
// those parameters and returns how many were read.
int read_var_file(const std::string& path, gcode::Parameters& parameters);

}  // namespace vc::interpreter
