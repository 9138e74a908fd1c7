#include "vc/shop/cmm_export.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "delimited_text.hpp"
#include "export_columns.hpp"
#include "vc/tables/csv.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::shop {
namespace {

using tables::CsvCell;

constexpr std::array<const char*, 3> kXyz{"X", "Y", "Z"}, kIjk{"I", "J", "K"};

struct Line {
  std::string text;
  int number;
};

std::vector<Line> read_lines(const std::string& path, bool report) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw LoadError({path}, report ? "cannot open the CMM report" : "cannot open the CMM plan");
  std::vector<Line> lines;
  std::string text;
  for (int number = 1; std::getline(in, text); ++number) {
    if (number == 1 && text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);  // UTF-8 BOM
    if (!text.empty() && text.back() == '\r') text.pop_back();
    lines.push_back({text, number});
  }
  return lines;
}

bool blank(const std::string& s) { return s.find_first_not_of(" \t\r") == std::string::npos; }

std::vector<CsvCell> split(const std::string& path, const Line& line, char delimiter) {
  try {
    return split_delimited(line.text, delimiter);
  } catch (const std::invalid_argument& open) {
    throw LoadError({path, line.number, std::stoi(open.what())}, "this quote is not closed on its line");
  }
}

// "Units: inch", "UNITS=MM", "Units;mm", "Length units, mm": the unit, else nothing.
std::optional<LengthUnit> unit_line(const std::string& text) {
  std::vector<std::string> words;
  std::string word;
  for (const char c : text + ' ') {
    if (std::isalnum(static_cast<unsigned char>(c)) || static_cast<unsigned char>(c) > 127) {
      word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (!word.empty()) {
      words.push_back(word), word.clear();
    }
  }
  if (!words.empty() && words[0] == "length") words.erase(words.begin());
  if (words.size() != 2 || (words[0] != "unit" && words[0] != "units")) return std::nullopt;
  return length_unit(words[1]);
}

bool has_nominal(const std::vector<ColumnName>& names, int axis) {
  return std::any_of(names.begin(), names.end(), [&](const ColumnName& n) {
    return n.axis == axis &&
           (n.role == ColumnRole::Coordinate || n.role == ColumnRole::Nominal || n.role == ColumnRole::NominalOrNormal);
  });
}

// The spacing of the last digit written in a number cell ("0.0040" -> 0.0001): the rounding
// a value read from it carries is half of it. An integer ("0", "5") is taken as exact: an
// export rounding to whole units would say nothing below them, and no CMM does.
double last_digit(std::string text) {
  int exponent = 0;
  const std::size_t e = text.find_first_of("eE");
  if (e != std::string::npos) {
    // Clamped: the cell was read as a finite number, but its exponent's digits may not fit an int.
    exponent = static_cast<int>(std::clamp(std::strtol(text.c_str() + e + 1, nullptr, 10), -400L, 400L));
    text.erase(e);
  }
  const std::size_t point = text.find_first_of(".,");
  if (point == std::string::npos && e == std::string::npos) return 0.0;
  const int decimals = point == std::string::npos ? 0 : static_cast<int>(text.size() - point - 1);
  return std::pow(10.0, exponent - decimals);
}

std::string um(double mm) { return with_sign(fixed_text(mm * 1e3, 3)) + " um"; }

class ExportReader {
 public:
  ExportReader(const std::string& path, bool report, const ReportFormat& format)
      : path_(path), report_(report), format_(format) {}

  std::vector<CmmPoint> read(std::string* layout) {
    const std::vector<Line> lines = read_lines(path_, report_);
    std::size_t at = find_header(lines);
    assign_columns();
    resolve_units();
    choose_deviation();
    if (layout) *layout = describe();
    std::vector<CmmPoint> points;
    for (++at; at < lines.size(); ++at)
      if (!blank(lines[at].text))
        if (auto p = point(lines[at])) points.push_back(*p);
    if (points.empty())
      throw LoadError({path_}, "no points below the header (line " + std::to_string(header_line_) + ")");
    return points;
  }

 private:
  struct Column {
    int index = -1;      // in the row's cells
    double to_mm = 1.0;  // lengths
    std::string unit;    // its name, for the layout
  };

  LoadError at_cell(int index, const std::string& message) const {
    return LoadError({path_, header_line_, cells_[static_cast<std::size_t>(index)].column}, message);
  }
  std::string quoted(int index) const { return "'" + cells_[static_cast<std::size_t>(index)].text + "'"; }

  // The first line naming the nominal X, Y and Z; the units line above it, if any.
  std::size_t find_header(const std::vector<Line>& lines) {
    int one_row_per_axis = 0;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (blank(lines[i].text)) continue;
      const char delimiter = delimiter_of(lines[i].text);
      std::vector<CsvCell> cells = split(path_, lines[i], delimiter);
      std::vector<ColumnName> names;
      for (const CsvCell& c : cells) names.push_back(column_name(c.text));
      if (has_nominal(names, 0) && has_nominal(names, 1) && has_nominal(names, 2)) {
        cells_ = std::move(cells), names_ = std::move(names), header_line_ = lines[i].number, delimiter_ = delimiter;
        if (format_.decimal_comma && delimiter == ',')
          throw LoadError({path_, header_line_}, "--decimal-comma, but the header is separated by commas");
        return i;
      }
      if (const auto u = unit_line(lines[i].text)) {
        if (unit_line_ && unit_line_->name != u->name)
          throw LoadError({path_, lines[i].number}, "this units line says " + u->name + ", the one on line " +
                                                        std::to_string(unit_line_number_) + " says " +
                                                        unit_line_->name);
        unit_line_ = u, unit_line_number_ = lines[i].number;
      } else if (std::any_of(names.begin(), names.end(),
                             [](const ColumnName& n) { return n.role == ColumnRole::LongLayout; })) {
        if (!one_row_per_axis) one_row_per_axis = lines[i].number;
      }
    }
    if (one_row_per_axis)
      throw LoadError({path_, one_row_per_axis},
                      "a table with one row per axis (columns such as Axis, Nominal, Measured) is not read: export "
                      "one row per point, with its nominal X, Y, Z, normal I, J, K and actual X, Y, Z or deviation "
                      "in columns");
    throw LoadError({path_},
                    "no header naming the nominal X, Y and Z (e.g. 'Nominal X', 'X Nom', 'NX' or 'X'; or "
                    "volcomp's id,x[mm],y[mm],z[mm],i,j,k,...)");
  }

  std::string not_understood() const {
    std::string list;
    for (std::size_t i = 0; i < names_.size(); ++i)
      if (names_[i].role == ColumnRole::Unknown) list += (list.empty() ? "" : ", ") + quoted(static_cast<int>(i));
    return list.empty() ? "" : " (columns not understood: " + list + ")";
  }

  void assign(int& slot, int index, const std::string& what) {
    if (slot >= 0)
      throw at_cell(index, quoted(index) + " is " + what + ", and so is " + quoted(slot) + " (column " +
                               std::to_string(cells_[static_cast<std::size_t>(slot)].column) + ")");
    slot = index;
  }

  void assign_columns() {
    const auto any = [&](ColumnRole r) {
      return std::any_of(names_.begin(), names_.end(), [&](const ColumnName& n) { return n.role == r; });
    };
    // "NX": nominal beside normals written otherwise, normal beside nominals written otherwise.
    const bool normals = any(ColumnRole::Normal), nominals = any(ColumnRole::Nominal) || any(ColumnRole::Coordinate);
    for (std::size_t i = 0; i < names_.size(); ++i) {
      if (names_[i].role != ColumnRole::NominalOrNormal) continue;
      if (normals == nominals)
        throw at_cell(static_cast<int>(i), quoted(static_cast<int>(i)) + " may be the nominal " + kXyz[names_[i].axis] +
                                               " or the normal's " + kIjk[names_[i].axis] +
                                               ", and the other columns do not tell: rename it 'Nominal " +
                                               kXyz[names_[i].axis] + "' or 'Normal " + kXyz[names_[i].axis] + "'");
      names_[i].role = normals ? ColumnRole::Nominal : ColumnRole::Normal;
    }
    // "X": the nominal, unless another column is marked as the nominal.
    const bool marked = any(ColumnRole::Nominal);
    std::array<int, 3> nominal{-1, -1, -1}, normal{-1, -1, -1}, actual{-1, -1, -1}, vector{-1, -1, -1};
    for (std::size_t i = 0; i < names_.size(); ++i) {
      const int index = static_cast<int>(i);
      const ColumnName& n = names_[i];
      const std::string xyz = n.axis >= 0 ? kXyz[n.axis] : "";
      switch (n.role) {
        case ColumnRole::Coordinate:
          if (marked)
            throw at_cell(index, quoted(index) +
                                     " is not marked nominal or actual, and another column is the "
                                     "nominal " +
                                     xyz + ": rename it (e.g. 'Actual " + xyz + "')");
          [[fallthrough]];
        case ColumnRole::Nominal:
          assign(nominal[n.axis], index, "the nominal " + xyz);
          break;
        case ColumnRole::Normal:
          assign(normal[n.axis], index, std::string("the normal's ") + kIjk[n.axis]);
          break;
        case ColumnRole::Actual:
          assign(actual[n.axis], index, "the actual " + xyz);
          break;
        case ColumnRole::DeviationComponent:
          assign(vector[n.axis], index, "the deviation's " + xyz);
          break;
        case ColumnRole::Deviation:
          assign(deviation_.index, index, "the deviation along the normal");
          break;
        case ColumnRole::Id:
          if (id_ < 0) id_ = index;
          break;
        default:
          break;
      }
    }
    for (int a = 0; a < 3; ++a) {
      if (nominal[a] < 0)
        throw LoadError({path_, header_line_}, std::string("no column for the nominal ") + kXyz[a] +
                                                   " (e.g. 'Nominal " + kXyz[a] + "')" + not_understood());
      if (normal[a] < 0)
        throw LoadError({path_, header_line_}, std::string("no column for the normal's ") + kIjk[a] +
                                                   " (the surface vector out of the "
                                                   "material: e.g. '" +
                                                   kIjk[a] + "' or 'Normal " + kXyz[a] + "')" + not_understood());
      nominal_[a].index = nominal[a], normal_[a].index = normal[a];
    }
    const auto all_or_none = [&](const std::array<int, 3>& c, const std::string& what) {
      const auto given = std::count_if(c.begin(), c.end(), [](int i) { return i >= 0; });
      if (given != 0 && given != 3)
        for (int a = 0; a < 3; ++a)
          if (c[a] < 0)
            throw LoadError({path_, header_line_}, "the " + what + " has no " + kXyz[a] + " column" + not_understood());
      return given == 3;
    };
    if (all_or_none(actual, "actual point"))
      for (int a = 0; a < 3; ++a) actual_[a].index = actual[a];
    if (all_or_none(vector, "deviation vector"))
      for (int a = 0; a < 3; ++a) vector_[a].index = vector[a];
  }

  // The unit of one length column: its header's, else the file's (units line or option).
  void resolve_unit(Column& c, bool coordinate) {
    if (c.index < 0) return;
    const ColumnName& n = names_[static_cast<std::size_t>(c.index)];
    if (!n.bad_unit.empty()) throw at_cell(c.index, "'" + n.bad_unit + "' is not a length unit (mm, um, inch)");
    std::optional<LengthUnit> file = unit_line_ ? unit_line_ : option_unit_;
    if (n.unit && coordinate && file && file->name != n.unit->name)
      throw at_cell(c.index, "the header says " + n.unit->name + ", " + file_unit_source() + " says " + file->name);
    const std::optional<LengthUnit> u = n.unit ? n.unit : file;
    if (!u)
      throw at_cell(c.index, "no unit for " + quoted(c.index) + ": write it in the header ('" +
                                 cells_[static_cast<std::size_t>(c.index)].text +
                                 " [mm]'), on a line above the "
                                 "header ('Units: mm'), or give --report-unit mm|inch");
    c.to_mm = u->to_mm, c.unit = u->name;
  }

  std::string file_unit_source() const {
    return unit_line_ ? "the units line (line " + std::to_string(unit_line_number_) + ")" : "--report-unit";
  }

  void resolve_units() {
    if (!format_.unit.empty()) {
      option_unit_ = length_unit(format_.unit);
      if (!option_unit_) throw std::runtime_error("--report-unit must be mm, um or inch, not " + format_.unit);
      if (unit_line_ && unit_line_->name != option_unit_->name)
        throw LoadError({path_, unit_line_number_, 1},
                        "this units line says " + unit_line_->name + ", --report-unit says " + option_unit_->name);
    }
    for (int a = 0; a < 3; ++a) {
      resolve_unit(nominal_[a], true);
      resolve_unit(actual_[a], true);
      resolve_unit(vector_[a], false);
    }
    resolve_unit(deviation_, false);
  }

  void choose_deviation() {
    if (!report_) return;
    if (actual_[0].index >= 0) return;  // n . (actual - nominal): no sign to state
    const int column = deviation_.index >= 0 ? deviation_.index : vector_[0].index;
    if (column < 0)
      throw LoadError({path_, header_line_},
                      "a report needs the actual X, Y, Z or the deviation along the normal "
                      "(a column such as 'Dev' or 'Deviation')" +
                          not_understood());
    if (format_.sign == DeviationSign::Unstated)
      throw at_cell(column, "the sign of " + quoted(column) +
                                " is not stated: give --deviation-sign actual-minus-nominal (the usual CMM "
                                "convention: + where the surface lies out along the normal, material left) or "
                                "nominal-minus-actual");
  }

  std::string describe() const {
    const auto columns = [&](const std::array<Column, 3>& c, bool unit) {
      std::string s;
      for (int a = 0; a < 3; ++a) s += (a ? "," : "") + quoted(c[a].index);
      return unit ? s + " [" + c[0].unit + (c[1].unit != c[0].unit || c[2].unit != c[0].unit ? ",..." : "") + "]" : s;
    };
    const char* separator = delimiter_ == '\t' ? "tab" : delimiter_ == ';' ? "semicolon" : "comma";
    std::string s = std::string("a CMM export, ") + separator + "-separated, header on line " +
                    std::to_string(header_line_) + ": nominal " + columns(nominal_, true) + ", normal " +
                    columns(normal_, false);
    if (report_ && actual_[0].index >= 0) {
      s += ", actual " + columns(actual_, true) + " (deviation = n . (actual - nominal)";
      if (deviation_.index >= 0)
        s += format_.sign == DeviationSign::Unstated
                 ? "; " + quoted(deviation_.index) + " not used, its sign not stated)"
                 : ", checked against " + quoted(deviation_.index) + ")";
      else
        s += ")";
    } else if (report_) {
      const std::string sign =
          format_.sign == DeviationSign::ActualMinusNominal ? "actual - nominal" : "nominal - actual";
      s += deviation_.index >= 0 ? ", deviation " + quoted(deviation_.index) + " [" + deviation_.unit + "] as " + sign
                                 : ", deviation vector " + columns(vector_, true) + " as " + sign;
    }
    if (id_ >= 0) s += ", names " + quoted(id_);
    return s;
  }

  double number(const Line& line, const std::vector<CsvCell>& row, int index) const {
    CsvCell c = row[static_cast<std::size_t>(index)];
    if (format_.decimal_comma) {
      if (c.text.find('.') != std::string::npos)
        throw LoadError({path_, line.number, c.column},
                        "'" + c.text + "' has a decimal point, but --decimal-comma says the file uses commas");
      std::replace(c.text.begin(), c.text.end(), ',', '.');
    } else if (c.text.find(',') != std::string::npos) {
      throw LoadError({path_, line.number, c.column},
                      "'" + c.text + "' has a comma: give --decimal-comma if it is the decimal separator");
    }
    return tables::csv_number(path_, line.number, c);
  }

  std::optional<CmmPoint> point(const Line& line) const {
    const std::vector<CsvCell> row = split(path_, line, delimiter_);
    if (std::all_of(row.begin(), row.end(), [](const CsvCell& c) { return c.text.empty(); })) return std::nullopt;
    int needed = id_;
    for (const auto* group : {&nominal_, &normal_, &actual_, &vector_})
      for (const Column& c : *group) needed = std::max(needed, c.index);
    needed = std::max(needed, deviation_.index) + 1;
    if (static_cast<int>(row.size()) < needed)
      throw LoadError({path_, line.number}, std::to_string(row.size()) + " cells, the header (line " +
                                                std::to_string(header_line_) + ") has " +
                                                std::to_string(cells_.size()));
    const auto length = [&](const Column& c) { return number(line, row, c.index) * c.to_mm; };
    const auto digit = [&](const Column& c) {
      return last_digit(row[static_cast<std::size_t>(c.index)].text) * c.to_mm;
    };
    CmmPoint p;
    p.line = line.number;
    p.id = id_ >= 0 ? row[static_cast<std::size_t>(id_)].text : "";
    if (p.id.empty()) p.id = "line" + std::to_string(line.number);
    Eigen::Vector3d n;
    for (int a = 0; a < 3; ++a) p.nominal[a] = length(nominal_[a]), n[a] = number(line, row, normal_[a].index);
    if (std::abs(n.norm() - 1) > 1e-3)
      throw LoadError({path_, line.number, row[static_cast<std::size_t>(normal_[0].index)].column},
                      "the normal (I, J, K) is not a unit vector (length " + std::to_string(n.norm()) + ")" +
                          (std::abs(n.norm() - 1) < 0.01 ? ": export it with 4 decimals or more" : ""));
    p.normal = n.normalized();
    if (!report_) return p;
    const double sign = format_.sign == DeviationSign::NominalMinusActual ? -1.0 : 1.0;
    std::optional<double> stated;
    if (deviation_.index >= 0) {
      stated = sign * length(deviation_);
    } else if (vector_[0].index >= 0) {
      const Eigen::Vector3d d(length(vector_[0]), length(vector_[1]), length(vector_[2]));
      stated = sign * p.normal.dot(d);
    }
    if (actual_[0].index < 0) {
      p.deviation_mm = stated;
      return p;
    }
    const Eigen::Vector3d actual(length(actual_[0]), length(actual_[1]), length(actual_[2]));
    p.deviation_mm = p.normal.dot(actual - p.nominal);
    if (stated && deviation_.index >= 0 && format_.sign != DeviationSign::Unstated) {
      // The stated deviation and the actual point agree to the digits written.
      double rounding = digit(deviation_);
      for (int a = 0; a < 3; ++a) rounding += std::abs(n[a]) * (digit(nominal_[a]) + digit(actual_[a]));
      rounding = rounding / 2 + 1e-9;
      if (std::abs(*stated - *p.deviation_mm) > rounding) {
        const bool opposite = std::abs(*stated + *p.deviation_mm) <= rounding;
        throw LoadError(
            {path_, line.number, row[static_cast<std::size_t>(deviation_.index)].column},
            "the deviation (" + um(*stated) + " as " + (sign > 0 ? "actual - nominal" : "nominal - actual") + ") " +
                (opposite ? "is the opposite of" : "disagrees with") +
                " the actual point's (n . (actual - nominal) = " + um(*p.deviation_mm) +
                "): " + (opposite ? "is --deviation-sign right?" : "is it the deviation along the normal?"));
      }
    }
    return p;
  }

  const std::string& path_;
  bool report_;
  const ReportFormat& format_;
  std::vector<CsvCell> cells_;
  std::vector<ColumnName> names_;
  int header_line_ = 0;
  char delimiter_ = ',';
  std::optional<LengthUnit> unit_line_, option_unit_;
  int unit_line_number_ = 0;
  std::array<Column, 3> nominal_, normal_, actual_, vector_;
  Column deviation_;
  int id_ = -1;
};

}  // namespace

std::vector<CmmPoint> read_cmm_export(const std::string& path, bool report, const ReportFormat& format,
                                      std::string* layout) {
  return ExportReader(path, report, format).read(layout);
}

}  // namespace vc::shop
