// Numbers in the plots' CSV files: 12 significant digits (far below any measurement's
// resolution, and a unit conversion's last-bit noise gone: 0.005 mm is 5 um, not
// 5.000000000000001), whatever the locale (a spreadsheet and gnuplot both read '.').
#pragma once

#include <string>
#include <vector>

#include "vc/tables/number_text.hpp"

namespace vc::plot {

inline std::string number(double v) { return without_negative_zero(significant_text(v, 12)); }

// `text` broken into lines of at most `width` characters at spaces (a longer word stays whole),
// the lines after the first indented by `indent` spaces: a note in a plot's side column.
inline std::vector<std::string> wrapped(const std::string& text, std::size_t width, std::size_t indent = 2) {
  std::vector<std::string> lines{""};
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = text.find(' ', at);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(at, end - at);
    if (!lines.back().empty() && lines.back().size() + 1 + word.size() > width)
      lines.push_back(std::string(indent, ' ') + word);
    else
      lines.back() += (lines.back().empty() ? "" : " ") + word;
    at = end + 1;
  }
  return lines;
}

}  // namespace vc::plot
