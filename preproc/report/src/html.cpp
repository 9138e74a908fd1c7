#include "vc/report/html.hpp"

#include <filesystem>

#include "vc/report/base64.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::report {

std::string escaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string html_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                       bool numeric) {
  std::string html = std::string("<table") + (numeric ? " class=\"numeric\"" : "") + ">\n";
  if (!header.empty()) {
    html += "<thead><tr>";
    for (const std::string& h : header) html += "<th>" + escaped(h) + "</th>";
    html += "</tr></thead>\n";
  }
  html += "<tbody>\n";
  for (const auto& row : rows) {
    html += "<tr>";
    for (const std::string& cell : row) html += "<td>" + escaped(cell) + "</td>";
    html += "</tr>\n";
  }
  return html + "</tbody></table>\n";
}

std::string html_png_figure(const std::string& png_bytes, const std::string& alt, const std::string& caption,
                            FigureSize size) {
  return std::string("<figure class=\"") + (size == FigureSize::Half ? "half" : "full") +
         "\">\n<img src=\"data:image/png;base64," + base64(png_bytes) + "\" alt=\"" + escaped(alt) +
         "\">\n<figcaption>" + escaped(caption) + "</figcaption>\n</figure>\n";
}

std::string shown_path(const std::string& path) { return std::filesystem::absolute(path).lexically_normal().string(); }

std::string fixed(double v, int decimals) {
  return fixed_text(v == 0.0 ? 0.0 : v, decimals);  // no "-0.0" for a zero (a small negative value keeps its sign)
}

}  // namespace vc::report
