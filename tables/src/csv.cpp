#include "vc/tables/csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>

#include "vc/tables/source_error.hpp"

namespace vc::tables {
namespace {

// `s` without leading and trailing blanks; `offset` grows by the blanks removed in front.
std::string trim(const std::string& s, int& offset) {
  const std::size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  const std::size_t e = s.find_last_not_of(" \t\r");
  offset += static_cast<int>(b);
  return s.substr(b, e - b + 1);
}

}  // namespace

std::vector<CsvCell> split_csv_line(const std::string& line) {
  std::vector<CsvCell> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string raw = line.substr(start, comma == std::string::npos ? comma : comma - start);
    int column = static_cast<int>(start) + 1;
    std::string text = trim(raw, column);
    cells.push_back({text, column});
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return cells;
}

std::vector<CsvRow> read_csv_rows(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw LoadError({path}, "cannot open the " + what);
  std::vector<CsvRow> rows;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 BOM (Excel)
    int offset = 0;
    const std::string content = trim(line, offset);
    if (content.empty() || content[0] == '#') continue;
    rows.push_back({split_csv_line(line), number});
  }
  return rows;
}

double csv_number(const std::string& path, int line, const CsvCell& cell) {
  double v = 0.0;
  const char* begin = cell.text.data();
  const char* end = begin + cell.text.size();
  // from_chars takes no '+'; skip one, but never before another sign ("+-1").
  if (cell.text.size() > 1 && *begin == '+' && begin[1] != '-' && begin[1] != '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, v);
  if (cell.text.empty()) throw LoadError({path, line, cell.column}, "empty cell: every cell needs a number");
  if (ec == std::errc::result_out_of_range && ptr == end)
    throw LoadError({path, line, cell.column}, "'" + cell.text + "' is out of the range of a number");
  if (ec != std::errc() || ptr != end)
    throw LoadError({path, line, cell.column}, "'" + cell.text + "' is not a number");
  if (!std::isfinite(v)) throw LoadError({path, line, cell.column}, "'" + cell.text + "' is not a finite number");
  return v;
}

}  // namespace vc::tables
