// The path file: one sample per row, units in the header, full precision (number_text).
#include <ostream>

#include "vc/shop/tool_path.hpp"
#include "vc/tables/csv.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::shop {
namespace {

constexpr const char* kColumns[] = {"move",  "line",  "tool", "radius[mm]", "end", "cutting", "s",      "x[mm]",
                                    "y[mm]", "z[mm]", "i",    "j",          "k",   "ex[um]",  "ey[um]", "ez[um]"};
constexpr int kColumnCount = sizeof kColumns / sizeof kColumns[0];

}  // namespace

void write_path_header(std::ostream& out, const std::vector<std::string>& comments) {
  for (const std::string& c : comments) out << "# " << c << '\n';
  for (int i = 0; i < kColumnCount; ++i) out << (i ? "," : "") << kColumns[i];
  out << '\n';
}

void write_path_sample(std::ostream& out, const PathSample& p) {
  out << p.move << ',' << p.line << ',' << p.tool << ',';
  out << number_text(p.radius_mm);
  out << ',' << (p.end == ToolEnd::Ball ? "ball" : "flat") << ',' << (p.cutting ? 1 : 0) << ',';
  out << number_text(p.s);
  for (int i = 0; i < 3; ++i) out << ',' << number_text(p.tip[i]);
  for (int i = 0; i < 3; ++i) out << ',' << number_text(p.axis[i]);
  for (int i = 0; i < 3; ++i) out << ',' << number_text(p.error_mm[i] * 1e3);
  out << '\n';
}

ToolPath read_tool_path(const std::string& path) {
  const std::vector<tables::CsvRow> rows = tables::read_csv_rows(path, "tool path");
  if (rows.empty()) throw LoadError({path}, "the tool path is empty (no header)");
  const tables::CsvRow& header = rows.front();
  for (int i = 0; i < kColumnCount; ++i) {
    if (i >= static_cast<int>(header.cells.size()))
      throw LoadError({path, header.line},
                      std::string("missing column ") + kColumns[i] + " (volcomp simulate writes them)");
    if (header.cells[static_cast<std::size_t>(i)].text != kColumns[i])
      throw LoadError({path, header.line, header.cells[static_cast<std::size_t>(i)].column},
                      "column " + std::to_string(i + 1) + " must be " + kColumns[i] + ", not '" +
                          header.cells[static_cast<std::size_t>(i)].text + "'");
  }
  ToolPath samples;
  samples.reserve(rows.size() - 1);
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const tables::CsvRow& row = rows[r];
    if (static_cast<int>(row.cells.size()) != kColumnCount)
      throw LoadError({path, row.line},
                      std::to_string(row.cells.size()) + " cells, the header has " + std::to_string(kColumnCount));
    auto number = [&](int i) { return tables::csv_number(path, row.line, row.cells[static_cast<std::size_t>(i)]); };
    PathSample p;
    p.move = static_cast<int>(number(0));
    p.line = static_cast<int>(number(1));
    p.tool = static_cast<int>(number(2));
    p.radius_mm = number(3);
    const tables::CsvCell& end = row.cells[4];
    if (end.text != "flat" && end.text != "ball")
      throw LoadError({path, row.line, end.column}, "tool end must be flat or ball, not '" + end.text + "'");
    p.end = end.text == "ball" ? ToolEnd::Ball : ToolEnd::Flat;
    p.cutting = number(5) != 0;
    p.s = number(6);
    p.tip = {number(7), number(8), number(9)};
    p.axis = Eigen::Vector3d(number(10), number(11), number(12));
    if (std::abs(p.axis.norm() - 1) > 1e-6)
      throw LoadError({path, row.line, row.cells[10].column}, "the tool axis (i, j, k) is not a unit vector");
    p.error_mm = Eigen::Vector3d(number(13), number(14), number(15)) * 1e-3;
    samples.push_back(p);
  }
  return samples;
}

}  // namespace vc::shop
