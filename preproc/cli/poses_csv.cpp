#include "poses_csv.hpp"

#include "vc/tables/csv.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

namespace vc::cli {

Poses read_poses(const std::string& path, const machine::Model& model) {
  Poses poses;
  bool header_read = false;
  const int n = model.joint_count();
  for (const tables::CsvRow& row : tables::read_csv_rows(path, "poses file")) {
    const std::vector<tables::CsvCell>& cells = row.cells;
    const int number = row.line;
    if (!header_read) {
      for (const tables::CsvCell& c : cells) {
        const int j = c.text.size() == 1
                          ? model.joint_of(static_cast<char>(std::toupper(static_cast<unsigned char>(c.text[0]))))
                          : -1;
        if (j < 0)
          throw LoadError({path, number, c.column}, "column '" + c.text + "' is not an axis of " + model.info.name +
                                                        " (" + model.coordinates() + ")");
        for (int k : poses.joint_of_column)
          if (k == j) throw LoadError({path, number, c.column}, "column '" + c.text + "' appears twice");
        poses.header.push_back(c.text);
        poses.joint_of_column.push_back(j);
      }
      if (static_cast<int>(cells.size()) != n)
        throw LoadError({path, number, 1},
                        "the header must name every axis of " + model.info.name + ": " + model.coordinates());
      header_read = true;
      continue;
    }
    if (cells.size() != poses.header.size())
      throw LoadError({path, number, cells.back().column}, "expected " + std::to_string(poses.header.size()) +
                                                               " values, found " + std::to_string(cells.size()));
    machine::Joints q(n);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const std::string& t = cells[c].text;
      double v = 0.0;
      const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
      if (t.empty() || ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v))
        throw LoadError({path, number, cells[c].column}, "'" + t + "' is not a finite number");
      q[poses.joint_of_column[c]] = v;
    }
    poses.joints.push_back(q);
    poses.lines.push_back(number);
  }
  if (!header_read)
    throw LoadError({path}, "the poses file is empty: it needs a header such as " + model.coordinates());
  return poses;
}

}  // namespace vc::cli
