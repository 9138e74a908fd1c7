// What the instrument files (laser runs, circular tests) share: "name[unit]" header cells and
// "# key: value" metadata lines at the top. Private to preproc/identify/src.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "vc/tables/csv.hpp"
#include "vc/tables/units.hpp"

namespace vc::identify {

std::string lower(std::string s);

struct HeaderCell {
  std::string name;       // lower case, without the unit
  std::string unit_name;  // as written ("" without brackets)
  std::optional<tables::Unit> unit;
  bool bracket = false;
};

// Throws LoadError at the cell for a malformed unit or one that is not a length or an angle.
HeaderCell header_cell(const std::string& path, int line, const tables::CsvCell& cell);

// A header line's cells read, and the column of a name (-1: none).
struct Header {
  std::vector<HeaderCell> cells;
  int column(const std::string& name) const;
};
Header read_header(const std::string& path, const tables::CsvRow& row);

// The "# key: value" lines before the first line that is not a comment.
// `lines`, if given, gets the line of each.
std::vector<std::pair<std::string, std::string>> read_metadata(const std::string& path,
                                                               std::vector<int>* lines = nullptr);

}  // namespace vc::identify
