#include "vc/interpreter/line_text.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "vc/gcode/evaluate.hpp"
#include "vc/gcode/syntax_error.hpp"

namespace vc::interpreter {
namespace {

std::string lower_without_blanks(std::string_view text) {
  std::string out;
  for (char c : text)
    if (!std::isspace(static_cast<unsigned char>(c)))
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// After '#' at text[i]: a '<name>' (blanks skipped, lower-cased): its name and the index after
// the '>', or nothing.
std::optional<std::pair<std::string, std::size_t>> named_reference(std::string_view text, std::size_t i) {
  std::size_t j = i + 1;
  while (j < text.size() && std::isspace(static_cast<unsigned char>(text[j]))) ++j;
  if (j >= text.size() || text[j] != '<') return std::nullopt;
  const std::size_t close = text.find('>', j);
  if (close == std::string_view::npos) return std::nullopt;
  return std::make_pair(lower_without_blanks(text.substr(j + 1, close - j - 1)), close + 1);
}

// The message prefixes whose text LinuxCNC expands (convert_comment).
std::optional<std::size_t> expanded_message_start(std::string_view comment) {
  std::size_t start = 0;
  while (start < comment.size() && std::isspace(static_cast<unsigned char>(comment[start]))) ++start;
  for (const char* prefix : {"debug,", "print,", "log,"}) {
    const std::size_t n = std::strlen(prefix);
    if (comment.size() - start < n) continue;
    bool same = true;
    for (std::size_t k = 0; k < n && same; ++k)
      same = std::tolower(static_cast<unsigned char>(comment[start + k])) == prefix[k];
    if (same) return start + n;
  }
  return std::nullopt;
}

}  // namespace

std::string gcode_number_text(double value) {
  char buffer[400];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed);
  return std::string(buffer, result.ptr);
}

std::string expand_message(std::string_view text, const gcode::Parameters& parameters, int line) {
  std::string out;
  std::string format = "%f";
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '%') {
      ++i;
      if (i < text.size() && text[i] == 'd') {
        format = "%.0f";
        ++i;
      } else if (i < text.size() && text[i] == 'f') {
        format = "%.4f";
        ++i;
      } else if (i < text.size() && text[i] == '.') {
        ++i;
        if (i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) && text[i + 1] == 'f') {
          format = std::string("%.") + text[i] + "f";
          i += 2;
        } else {
          out += '.';
        }
      } else {
        out += '%';
      }
      continue;
    }
    if (c != '#') {
      out += c;
      ++i;
      continue;
    }
    ++i;
    std::optional<double> value;
    if (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
      long n = 0;
      for (; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i)
        n = std::min(n * 10 + (text[i] - '0'), 1000000L);
      if (n >= 1 && n < gcode::Parameters::kCount)
        value = parameters.get(static_cast<double>(n), 0);  // run-time ones: refused
    } else if (i < text.size() && text[i] == '<') {
      const std::size_t close = text.find('>', i);
      if (close == std::string_view::npos) throw gcode::SyntaxError(0, "named parameter not terminated in the message");
      const std::string name = lower_without_blanks(text.substr(i + 1, close - i - 1));
      i = close + 1;
      if (name == "_line")
        value = line;
      else if (parameters.exists(name))
        value = parameters.get(name, 0);
    } else {
      out += '#';
      continue;
    }
    if (value) {
      char buffer[64];
      const double shown = std::abs(*value) < 0.0001 ? 0.0 : *value;  // LinuxCNC: avoid -0.0
      const int n = std::snprintf(buffer, sizeof buffer, format.c_str(), shown);
      out += n > 0 && n < static_cast<int>(sizeof buffer) ? buffer : "######";
    } else {
      out += "######";
    }
  }
  return out;
}

bool pin_line_number(std::string& raw, int line, const gcode::Parameters& parameters) {
  if (raw.find('#') == std::string::npos) return false;
  std::string out;
  bool pinned = false;
  for (std::size_t i = 0; i < raw.size();) {
    if (raw[i] == ';') {  // the rest is a comment LinuxCNC does not expand
      out += raw.substr(i);
      break;
    }
    if (raw[i] == '(') {
      const std::size_t close = raw.find(')', i);
      if (close == std::string::npos) break;  // the parser says what is wrong
      const std::string_view comment = std::string_view(raw).substr(i + 1, close - i - 1);
      const auto start = expanded_message_start(comment);
      if (start && lower_without_blanks(comment).find("#<_line>") != std::string::npos) {
        const std::string expanded = expand_message(comment.substr(*start), parameters, line);
        if (expanded.find_first_of("#%()") != std::string::npos)
          throw gcode::SyntaxError(static_cast<int>(i),
                                   "this message reads #<_line> and also prints '#', '%' or '(': it cannot be "
                                   "rewritten for the pre-distorted program's line numbers");
        out += '(';
        out += comment.substr(0, *start);
        out += expanded;
        out += ')';
        pinned = true;
      } else {
        out += raw.substr(i, close + 1 - i);
      }
      i = close + 1;
      continue;
    }
    if (raw[i] == '#') {
      if (const auto named = named_reference(raw, i); named && named->first == "_line") {
        out += std::to_string(line);
        i = named->second;
        pinned = true;
        continue;
      }
    }
    out += raw[i++];
  }
  if (!pinned) return false;
  raw = std::move(out);
  return true;
}

std::string evaluated_line(std::string_view raw, const gcode::Block& block, const gcode::Parameters& parameters,
                           int line, bool numbered_shared, bool in_main_program) {
  struct Edit {
    int begin, end;
    std::string text;
  };
  std::vector<Edit> edits;
  for (const gcode::Word& w : block.words) {
    if (boost::get<double>(&w.value)) continue;  // a number as written
    const double value = gcode::evaluate(w.value, parameters, w.begin);
    if (!std::isfinite(value)) throw gcode::SyntaxError(w.begin, "the value is not a finite number");
    edits.push_back({w.begin, w.end, std::string(1, w.letter) + gcode_number_text(value)});
  }
  for (const gcode::Assignment& a : block.assignments) {
    const double value = gcode::evaluate(a.value, parameters, a.begin);
    std::string text;
    if (const auto* named = boost::get<gcode::ast::NamedParameter>(&a.target)) {
      if (gcode::Parameters::is_global(named->name) || in_main_program)
        text = "#<" + named->name + ">=" + gcode_number_text(value);
    } else {
      const auto& numbered = boost::get<boost::spirit::x3::forward_ast<gcode::ast::NumberedParameter>>(a.target).get();
      const double n = std::round(gcode::evaluate(numbered.index, parameters, a.begin));
      if (n > gcode::Parameters::kLocals || numbered_shared)
        text = "#" + gcode_number_text(n) + "=" + gcode_number_text(value);
    }
    edits.push_back({a.begin, a.end, text});
  }
  for (const gcode::Comment& c : block.comments) {
    if (raw[static_cast<std::size_t>(c.begin)] != '(') continue;  // ';' comments are not expanded
    const auto start = expanded_message_start(c.text);
    if (!start || c.text.find_first_of("#%", *start) == std::string::npos) continue;
    const std::string expanded = expand_message(std::string_view(c.text).substr(*start), parameters, line);
    if (expanded.find_first_of("#%()") != std::string::npos)
      throw gcode::SyntaxError(c.begin,
                               "this message, expanded, prints '#', '%' or '(': it cannot be written into "
                               "the flat program");
    edits.push_back({c.begin, c.end, "(" + c.text.substr(0, *start) + expanded + ")"});
  }
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.begin < b.begin; });
  std::string out;
  std::size_t from = 0;
  for (const Edit& e : edits) {
    out.append(raw.substr(from, static_cast<std::size_t>(e.begin) - from));
    out += e.text;
    from = static_cast<std::size_t>(e.end);
  }
  out.append(raw.substr(std::min(from, raw.size())));
  return out;
}

}  // namespace vc::interpreter
