// LinuxCNC's own files that decide how a program maps to the machine: the parameter file
// (.var: work offsets, G28/G30 homes) and the tool table (tool lengths). Read as LinuxCNC
// reads them; a line that cannot be read is refused with file:line:column. Both hold lengths
// in the machine's units (the INI's [TRAJ]LINEAR_UNITS).
#pragma once

#include <array>
#include <map>
#include <string>

#include "vc/gcode/parameters.hpp"

namespace vc::interpreter {

// One tool table entry, lengths in mm whatever the file's unit.
struct Tool {
  static constexpr const char* kOffsetLetters = "XYZABCUVW";
  int number = 0;
  std::array<double, 9> offset{};              // X Y Z A B C U V W: mm and deg; Z is the tool length offset
  double diameter = 0.0;                       // D column, mm; 0 if absent
  double front_angle = 0.0, back_angle = 0.0;  // I J (lathe tools), deg
  int orientation = 0;                         // Q (lathe tools)

  // Not an aggregate: a brace list {number, length, diameter} would fill X and Y silently.
  explicit Tool() = default;

  double z_offset() const { return offset[2]; }
  // The first of X Y A B C U V W that holds a non-zero offset (0: none). LinuxCNC's G43 applies
  // those too (a lathe tool's X); the pre-distorter takes Z only and refuses G43 with others.
  char other_offset() const;
};
using ToolTable = std::map<int, Tool>;

// A mill's entry: a length (Z) and a diameter, mm.
inline Tool mill_tool(int number, double length_mm, double diameter_mm) {
  Tool tool;
  tool.number = number;
  tool.offset[2] = length_mm;
  tool.diameter = diameter_mm;
  return tool;
}

// Lines "T<n> P<pocket> [X.. Y.. Z.. A.. B.. C.. U.. V.. W.. D.. I.. J.. Q..] [;comment]".
// machine_unit_mm: the length of the file's unit in mm (25.4 for a LinuxCNC set up in inches).
ToolTable read_tool_table(const std::string& path, double machine_unit_mm = 1.0);

// Lines "<number> <value>" (LinuxCNC writes them sorted; anything else is refused). Sets
// those parameters and returns how many were read.
int read_var_file(const std::string& path, gcode::Parameters& parameters);

}  // namespace vc::interpreter
