#include "vc/init/typical_tool.hpp"

#include <cctype>
#include <filesystem>
#include <sstream>

#include "vc/init/number.hpp"
#include "vc/interpreter/linuxcnc_files.hpp"

namespace vc::init {
namespace {

// The line of tool `number` in the table (its "T<number>" word), 0 if not found.
int line_of_tool(const TextFile& table, int number) {
  for (int n = 1; n <= static_cast<int>(table.lines.size()); ++n) {
    std::istringstream words(table.line(n).text.substr(0, table.line(n).text.find(';')));
    double t = 0.0;
    for (std::string w; words >> w;)
      if (w.size() > 1 && std::toupper(static_cast<unsigned char>(w[0])) == 'T' && parse_number(w.substr(1), t) &&
          t == number)
        return n;
  }
  return 0;
}

}  // namespace

TypicalTool longest_tool(const LinuxcncIni& ini, const LinearUnits& units) {
  const IniEntry* entry = ini.find("EMCIO", "TOOL_TABLE");
  if (!entry) return {0.0, "no [EMCIO]TOOL_TABLE: no typical tool (L = the G43 offset alone)"};
  const std::filesystem::path file = std::filesystem::path(ini.folder()) / entry->value;
  if (!std::filesystem::is_regular_file(file))
    return {0.0, "the tool table of " + ini.cite(*entry) + " does not exist (yet): no typical tool"};
  const std::string path = absolute_path(file.string());
  interpreter::ToolTable tools;
  try {
    tools = interpreter::read_tool_table(path, units.mm_per_unit);  // the lengths in mm
  } catch (const LoadError& e) {                                    // the typical tool is not worth a refusal
    return {0.0, "no typical tool: the tool table cannot be read: " + std::string(e.what()), true};
  }
  const interpreter::Tool* longest = nullptr;
  for (const auto& [number, tool] : tools)
    if (tool.z_offset() > 0.0 && (!longest || tool.z_offset() > longest->z_offset())) longest = &tool;
  if (!longest) return {0.0, "no tool of " + ini.cite(*entry) + " has a length (Z > 0)"};
  const TextFile table = read_text_file(path, "tool table");
  const int line = line_of_tool(table, longest->number);
  const std::string text = line ? trim(table.line(line).text) : "";
  return {longest->z_offset(), "the longest tool of the tool table, T" + std::to_string(longest->number) +
                                   (units.inch() ? " (inch, x 25.4)" : "") + ": " +
                                   cite(path, line, text, ini.folder())};
}

}  // namespace vc::init
