// A program that moves without G43 is corrected for L = tool_length_reference_mm alone (the
// tool-length rule): with the default 0, for the spindle gauge point. The tool in the spindle
// is longer, and at its tip the angular errors times its length stay uncorrected (issue 23:
// 18.5 um with a 100 mm tool on the MC-300). This finds the tool that is likely there and the
// tool-tip error the correction leaves with it, for a warning when that exceeds the tolerance.
#pragma once

#include <optional>
#include <string>

#include "vc/interpreter/linuxcnc_files.hpp"
#include "vc/interpreter/move.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/predistort/tool_lengths.hpp"

namespace vc::predistort {

// The tool likely in the spindle during a move, and its physical length.
struct LikelyTool {
  double length_mm = 0.0;  // L
  int tool = -1;           // the tool loaded (T.. M6) whose tool table entry gives L; -1: the
                           // machine file's tool_length_mm (no tool table, or the tool not in it)
};

// The tool loaded for `move` if the tool table has it (L = correction_length(its Z offset), as
// G43 would make it), else the machine file's typical tool (tool_length_mm) if it has one.
std::optional<LikelyTool> likely_tool(const machine::Model& model, const interpreter::ToolTable* tools,
                                      int tool_in_spindle);

// The largest tool-tip error left at the likely tool's length by corrections for L without an
// offset (a corrector's statistics: one per lane, then combined).
struct MissingOffsetError {
  double error_mm = 0.0;
  int line = 0;  // of the move where it is largest
  LikelyTool tool;
  void add(const MissingOffsetError& other) {
    if (other.error_mm > error_mm) *this = other;
  }
};

class MissingOffsetCheck {
 public:
  MissingOffsetCheck(const machine::Model& model, const machine::Conditions& conditions,
                     const interpreter::ToolTable* tools)
      : model_(model), conditions_(conditions), tools_(tools) {}
  // At a point of `move` (no tool length offset in force): `target` the nominal joints (less
  // the deflection), `corrected` their correction for L = correction_length(0). The error left
  // is the real machine's tip at `corrected` with the likely tool minus the ideal machine's at
  // `target` with it; `worst` keeps the largest.
  void at(const interpreter::Move& move, const machine::Joints& target, const machine::Joints& corrected,
          MissingOffsetError& worst) const;

 private:
  const machine::Model& model_;
  machine::Conditions conditions_;
  const interpreter::ToolTable* tools_;
};

// "warning: line 12 moves without G43 ...: corrected for L = 0 mm (the spindle gauge point);
// with tool 1 (100 mm, mc300.tbl) in the spindle the angular errors would leave up to 23.4 um at
// the tip (at line 37), more than the tolerance 0.5 um. Add G43 H1, or set
// tool_length_reference_mm." Empty when the error is within `tolerance_mm` or no move lacked G43.
std::string missing_offset_warning(const MissingOffsetError& error, const ToolLengthLog& log,
                                   const machine::Model& model, const std::string& program,
                                   const std::string& tool_table, double tolerance_mm);

}  // namespace vc::predistort
