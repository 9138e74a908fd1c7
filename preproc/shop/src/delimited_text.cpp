#include "delimited_text.hpp"

#include <stdexcept>

namespace vc::shop {

char delimiter_of(const std::string& line) {
  if (line.find('\t') != std::string::npos) return '\t';
  if (line.find(';') != std::string::npos) return ';';
  return ',';
}

std::vector<tables::CsvCell> split_delimited(const std::string& line, char delimiter) {
  std::vector<tables::CsvCell> cells;
  const auto blank = [&](char c) { return (c == ' ' || c == '\t' || c == '\r') && c != delimiter; };
  std::size_t at = 0;
  while (true) {
    while (at < line.size() && blank(line[at])) ++at;
    tables::CsvCell cell{"", static_cast<int>(at) + 1};
    if (at < line.size() && line[at] == '"') {
      const std::size_t open = at++;
      for (;; ++at) {
        if (at >= line.size()) throw std::invalid_argument(std::to_string(open + 1));
        if (line[at] != '"') {
          cell.text += line[at];
        } else if (at + 1 < line.size() && line[at + 1] == '"') {
          cell.text += '"', ++at;
        } else {
          ++at;
          break;
        }
      }
      cell.column = static_cast<int>(open) + 2;                // the first character inside the quotes
      while (at < line.size() && line[at] != delimiter) ++at;  // blanks after the closing quote
    } else {
      const std::size_t end = line.find(delimiter, at);
      std::string text = line.substr(at, end == std::string::npos ? std::string::npos : end - at);
      while (!text.empty() && blank(text.back())) text.pop_back();
      cell.text = text;
      at = end == std::string::npos ? line.size() : end;
    }
    cells.push_back(cell);
    if (at >= line.size()) break;
    ++at;  // the delimiter
  }
  return cells;
}

}  // namespace vc::shop
