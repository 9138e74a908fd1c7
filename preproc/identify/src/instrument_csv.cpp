#include "instrument_csv.hpp"

#include <cctype>
#include <fstream>

#include "vc/tables/source_error.hpp"

namespace vc::identify {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

HeaderCell header_cell(const std::string& path, int line, const tables::CsvCell& cell) {
  HeaderCell h;
  const auto open = cell.text.find('[');
  if (open == std::string::npos) {
    h.name = lower(cell.text);
    return h;
  }
  if (cell.text.back() != ']')
    throw LoadError({path, line, cell.column}, "a unit is written name[unit], e.g. target[mm]");
  h.bracket = true;
  h.name = lower(cell.text.substr(0, open));
  h.unit_name = cell.text.substr(open + 1, cell.text.size() - open - 2);
  h.unit = tables::find_unit(h.unit_name);
  if (!h.unit)
    throw LoadError({path, line, cell.column + static_cast<int>(open) + 1},
                    "unknown unit '" + h.unit_name +
                        "' (lengths: " + std::string(tables::unit_names(tables::Quantity::Length)) +
                        "; angles: " + std::string(tables::unit_names(tables::Quantity::Angle)) + ")");
  return h;
}

int Header::column(const std::string& name) const {
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (cells[i].name == name) return static_cast<int>(i);
  return -1;
}

Header read_header(const std::string& path, const tables::CsvRow& row) {
  Header h;
  for (const tables::CsvCell& c : row.cells) h.cells.push_back(header_cell(path, row.line, c));
  return h;
}

std::vector<std::pair<std::string, std::string>> read_metadata(const std::string& path, std::vector<int>* lines) {
  std::vector<std::pair<std::string, std::string>> out;
  std::ifstream in(path);
  auto trim = [](const std::string& s) {
    const auto b = s.find_first_not_of(" \t#"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line[0] != '#') break;
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    out.emplace_back(trim(line.substr(0, colon)), trim(line.substr(colon + 1)));
    if (lines) lines->push_back(number);
  }
  return out;
}

}  // namespace vc::identify
