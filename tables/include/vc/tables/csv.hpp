// The CSV files of the project (error tables, pose lists): lines split into cells that
// remember their column, so every message can point at the character. Load time only.
#pragma once

#include <string>
#include <vector>

namespace vc::tables {

struct CsvCell {
  std::string text;  // without surrounding spaces, tabs or '\r'
  int column;        // 1-based character column of the cell's first character
};

struct CsvRow {
  std::vector<CsvCell> cells;
  int line;  // 1-based line in the file
};

// Cells of one line, separated by commas.
std::vector<CsvCell> split_csv_line(const std::string& line);

// The number in a cell (a leading '+' allowed); throws LoadError at the cell if it is empty,
// not a number, out of range or not finite.
double csv_number(const std::string& path, int line, const CsvCell& cell);

// The lines of a file that are neither blank nor comments ('#'), split into cells; a UTF-8
// byte-order mark (Excel's "CSV UTF-8") is skipped. Throws LoadError "cannot open the <what>".
std::vector<CsvRow> read_csv_rows(const std::string& path, const std::string& what);

}  // namespace vc::tables
