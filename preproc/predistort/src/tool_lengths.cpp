#include "vc/predistort/tool_lengths.hpp"

#include <algorithm>
#include <filesystem>

#include "vc/tables/number_text.hpp"
#include "vc/interpreter/program_reader.hpp"

namespace vc::predistort {
namespace {

using interpreter::ToolOffsetFrom;

constexpr std::size_t kStretchesShown = 4;  // per L; the rest are counted

std::string mm(double v) { return number_text(v) + " mm"; }

}  // namespace

void ToolLengthLog::add(const interpreter::Move& move, const std::string& file) {
  Source source{move.tool_offset_mm, move.tool_offset_from,
                move.tool_offset_from == ToolOffsetFrom::G43 ? move.tool_offset_tool : -1};
  if (source.from == ToolOffsetFrom::None) {
    source.offset_mm = 0.0;
    if (!first_without_offset_) first_without_offset_ = Where{file, move.line, move.tool};
  }
  const auto it = std::find(sources_.begin(), sources_.end(), source);
  const auto index = static_cast<std::size_t>(it - sources_.begin());
  if (it == sources_.end()) sources_.push_back(source);
  if (!stretches_.empty()) {
    Stretch& last = stretches_.back();
    if (last.source == index && last.file == file) {
      last.first = std::min(last.first, move.line);
      last.last = std::max(last.last, move.line);
      return;
    }
  }
  stretches_.push_back({index, file, move.line, move.line});
}

std::string ToolLengthLog::describe(const machine::Model& model, const std::string& program,
                                    const std::string& tool_table) const {
  if (sources_.empty()) return {};
  const std::string reference = "reference " + mm(model.tool_length_reference_mm);
  const std::string table =
      tool_table.empty() ? std::string("the tool table") : std::filesystem::path(tool_table).filename().string();
  std::string text = "tool lengths: ";
  for (std::size_t s = 0; s < sources_.size(); ++s) {
    const Source& source = sources_[s];
    text += (s ? "; " : "") + std::string("L = ") + mm(model.correction_length(source.offset_mm)) + " (";
    switch (source.from) {
      case ToolOffsetFrom::None:
        text += model.tool_length_reference_mm == 0.0
                    ? std::string("no G43: the spindle gauge point")
                    : "no G43: tool_length_reference_mm " + mm(model.tool_length_reference_mm) + " alone";
        break;
      case ToolOffsetFrom::G43:
        text += reference + " + G43 offset of tool " + std::to_string(source.tool) + " from " + table;
        if (source.tool == 0 && source.offset_mm == 0.0) text += " or the empty spindle's 0 mm";
        break;
      case ToolOffsetFrom::G43_1:
        text += reference + " + G43.1 offset " + mm(source.offset_mm) + " from the program";
        break;
    }
    text += ") for ";
    std::size_t count = 0;
    std::string lines;
    bool one_line = false;
    for (const Stretch& stretch : stretches_) {
      if (stretch.source != s) continue;
      one_line = ++count == 1 && stretch.first == stretch.last;
      if (count > kStretchesShown) continue;
      lines += (count > 1 ? ", " : "") + std::to_string(stretch.first);
      if (stretch.last != stretch.first) lines += "-" + std::to_string(stretch.last);
      if (stretch.file != program) lines += " of " + stretch.file;
    }
    text += (one_line ? "line " : "lines ") + lines;
    if (count > kStretchesShown) text += " and " + std::to_string(count - kStretchesShown) + " more stretches";
  }
  return text;
}

ToolLengthLog read_tool_lengths(std::istream& program, const interpreter::Setup& setup) {
  interpreter::Interpreter interpreter(setup);
  interpreter::ProgramReader reader(program, setup.file, interpreter, setup.subroutine_path);
  gcode::Block block;
  interpreter::Effect effect;
  interpreter::Origin origin;
  std::string raw;
  ToolLengthLog log;
  while (reader.next(raw, origin, block, effect))
    for (const interpreter::Move& m : effect.moves) log.add(m, reader.files()[static_cast<std::size_t>(origin.file)]);
  return log;
}

}  // namespace vc::predistort
