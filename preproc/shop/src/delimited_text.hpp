// Lines of a text table as CMM software and spreadsheets export them: cells separated by a
// comma, a semicolon or a tab, a cell optionally in double quotes ("a;b" is one cell, ""
// inside quotes is a quote). Cells remember their column for file:line:column messages.
#pragma once

#include <string>
#include <vector>

#include "vc/tables/csv.hpp"

namespace vc::shop {

// The separator of a header line: a tab if it has one, else a semicolon if it has one, else
// a comma (a semicolon file is usually written where the comma is the decimal separator).
char delimiter_of(const std::string& line);

// The cells of `line`, split at `delimiter` outside quotes, without surrounding blanks and
// quotes. Throws std::invalid_argument with the column of an opening quote never closed.
std::vector<tables::CsvCell> split_delimited(const std::string& line, char delimiter);

}  // namespace vc::shop
