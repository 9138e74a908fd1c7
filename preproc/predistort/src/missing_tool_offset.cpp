#include "vc/predistort/missing_tool_offset.hpp"

#include <filesystem>

#include "vc/tables/number_text.hpp"
#include "vc/machine/forward.hpp"

namespace vc::predistort {

std::optional<LikelyTool> likely_tool(const machine::Model& model, const interpreter::ToolTable* tools,
                                      int tool_in_spindle) {
  if (tools && tool_in_spindle > 0) {
    const auto it = tools->find(tool_in_spindle);
    if (it != tools->end()) return LikelyTool{model.correction_length(it->second.z_offset()), tool_in_spindle};
  }
  if (model.tool_length_mm > 0.0) return LikelyTool{model.tool_length_mm, -1};
  return std::nullopt;
}

void MissingOffsetCheck::at(const interpreter::Move& move, const machine::Joints& target,
                            const machine::Joints& corrected, MissingOffsetError& worst) const {
  const std::optional<LikelyTool> tool = likely_tool(model_, tools_, move.tool);
  if (!tool || tool->length_mm == model_.correction_length(0.0)) return;  // corrected for that tool
  const double error_mm =
      (machine::tool_pose(model_, conditions_, machine::Machine::Real, corrected, tool->length_mm).tip_mm -
       machine::tool_pose(model_, machine::Machine::Ideal, target, tool->length_mm).tip_mm)
          .norm();
  if (error_mm > worst.error_mm) worst = {error_mm, move.line, *tool};
}

std::string missing_offset_warning(const MissingOffsetError& error, const ToolLengthLog& log,
                                   const machine::Model& model, const std::string& program,
                                   const std::string& tool_table, double tolerance_mm) {
  const std::optional<ToolLengthLog::Where> first = log.first_without_offset();
  if (!first || !(error.error_mm > tolerance_mm)) return {};
  const double reference = model.tool_length_reference_mm;
  const std::string length = number_text(error.tool.length_mm) + " mm";
  std::string text =
      "warning: line " + std::to_string(first->line) + (first->file != program ? " of " + first->file : std::string()) +
      " moves without G43 (no tool length offset in force): corrected for L = " + number_text(reference) + " mm (" +
      (reference == 0.0 ? "the spindle gauge point" : "tool_length_reference_mm alone") + "); with ";
  if (error.tool.tool >= 0)
    text += "tool " + std::to_string(error.tool.tool) + " (" + length + ", " +
            std::filesystem::path(tool_table).filename().string() + ")";
  else
    text += "the machine file's tool (tool_length_mm " + length + ")";
  text += " in the spindle the angular errors would leave up to " + fixed_text(error.error_mm * 1e3, 1) +
          " um at the tip (at line " + std::to_string(error.line) + "), more than the tolerance " +
          number_text(tolerance_mm * 1e3) + " um. Add G43";
  if (error.tool.tool >= 0) text += " H" + std::to_string(error.tool.tool);
  text += error.tool.tool >= 0 ? " after the tool change" : " H.. after each tool change (with its tool table)";
  text += ", or set tool_length_reference_mm";
  if (error.tool.tool < 0) text += " = " + number_text(error.tool.length_mm) + " in [spindle]";
  return text + ".";
}

}  // namespace vc::predistort
