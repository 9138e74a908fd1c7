#include "vc/interpreter/linuxcnc_files.hpp"

#include <cctype>
#include <cmath>
#include <charconv>
#include <fstream>
#include <limits>
#include <string_view>

#include "vc/tables/source_error.hpp"

namespace vc::interpreter {
namespace {

std::ifstream open(const std::string& path, const char* what) {
  std::ifstream in(path);
  if (!in) throw LoadError({path}, std::string("cannot open the ") + what);
  return in;
}

// Reads a number at s[pos...]; returns false if there is none. Advances pos past it.
bool read_number(std::string_view s, std::size_t& pos, double& value) {
  const char* first = s.data() + pos;
  const char* last = s.data() + s.size();
  if (first != last && *first == '+') ++first;  // from_chars does not take a leading '+'
  const auto [end, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || !std::isfinite(value)) return false;
  pos = static_cast<std::size_t>(end - s.data());
  return true;
}

void skip_spaces(std::string_view s, std::size_t& pos) {
  while (pos < s.size() && std::isspace(static_cast<unsigned char>(s[pos]))) ++pos;
}

}  // namespace

char Tool::other_offset() const {
  for (std::size_t i = 0; i < offset.size(); ++i)
    if (i != 2 && offset[i] != 0.0) return kOffsetLetters[i];
  return 0;
}

ToolTable read_tool_table(const std::string& path, double machine_unit_mm) {
  std::ifstream in = open(path, "tool table");
  ToolTable table;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    std::string_view s(text);
    if (const auto semicolon = s.find(';'); semicolon != std::string_view::npos) s = s.substr(0, semicolon);
    std::size_t pos = 0;
    skip_spaces(s, pos);
    if (pos == s.size()) continue;
    Tool tool;
    bool has_number = false;
    while (pos < s.size()) {
      const int column = static_cast<int>(pos) + 1;
      const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(s[pos++])));
      double value = 0.0;
      if (std::string_view("TPXYZABCUVWDIJQ").find(letter) == std::string_view::npos)
        throw LoadError({path, line, column}, std::string("unknown tool table column '") + letter + "'");
      if (!read_number(s, pos, value))
        throw LoadError({path, line, column + 1}, std::string("expected a number after '") + letter + "'");
      if (letter == 'T') {
        if (value != std::floor(value) || value < 0 || value > std::numeric_limits<int>::max())
          throw LoadError({path, line, column}, "tool number must be a whole number >= 0");
        tool.number = static_cast<int>(value);
        has_number = true;
      } else if (const auto axis = std::string_view(Tool::kOffsetLetters).find(letter);
                 axis != std::string_view::npos) {
        const bool angle = letter == 'A' || letter == 'B' || letter == 'C';
        tool.offset[axis] = angle ? value : value * machine_unit_mm;
      } else if (letter == 'D') {
        tool.diameter = value * machine_unit_mm;
      } else if (letter == 'I') {
        tool.front_angle = value;
      } else if (letter == 'J') {
        tool.back_angle = value;
      } else if (letter == 'Q') {
        if (value != std::floor(value) || value < 0 || value > 9)
          throw LoadError({path, line, column}, "tool orientation Q must be a whole number 0..9");
        tool.orientation = static_cast<int>(value);
      }
      skip_spaces(s, pos);
    }
    if (!has_number) throw LoadError({path, line, 1}, "tool entry without a T number");
    if (!table.emplace(tool.number, tool).second)
      throw LoadError({path, line, 1}, "tool " + std::to_string(tool.number) + " is listed twice");
  }
  return table;
}

int read_var_file(const std::string& path, gcode::Parameters& parameters) {
  std::ifstream in = open(path, "parameter file");
  std::string text;
  int count = 0;
  for (int line = 1; std::getline(in, text); ++line) {
    std::string_view s(text);
    std::size_t pos = 0;
    skip_spaces(s, pos);
    if (pos == s.size()) continue;
    double number = 0.0, value = 0.0;
    const int column = static_cast<int>(pos) + 1;
    if (!read_number(s, pos, number) || number != std::floor(number) || number < 1 ||
        number >= gcode::Parameters::kCount)
      throw LoadError({path, line, column}, "expected a parameter number 1..5601");
    skip_spaces(s, pos);
    const int value_column = static_cast<int>(pos) + 1;
    if (!read_number(s, pos, value)) throw LoadError({path, line, value_column}, "expected a value");
    skip_spaces(s, pos);
    if (pos != s.size()) throw LoadError({path, line, static_cast<int>(pos) + 1}, "unexpected text after the value");
    parameters[static_cast<int>(number)] = value;
    ++count;
  }
  return count;
}

}  // namespace vc::interpreter
