#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <random>

#include "vc/shop/cmm.hpp"
#include "vc/shop/cmm_export.hpp"
#include "vc/tables/csv.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/tables/source_error.hpp"
#include "vc/tables/units.hpp"

namespace vc::shop {
namespace {

// "x[mm]" -> ("x", factor to mm); a name without unit -> factor 1 (i, j, k).
struct HeaderCell {
  std::string name;
  double to_mm = 1.0;
  bool has_unit = false;
};

HeaderCell header_cell(const std::string& path, int line, const tables::CsvCell& cell) {
  HeaderCell h;
  const auto open = cell.text.find('[');
  if (open == std::string::npos) {
    h.name = cell.text;
    return h;
  }
  if (cell.text.back() != ']') throw LoadError({path, line, cell.column}, "a unit is written name[unit], e.g. x[mm]");
  h.name = cell.text.substr(0, open);
  const std::string unit = cell.text.substr(open + 1, cell.text.size() - open - 2);
  const auto u = tables::find_unit(unit);
  if (!u || u->quantity != tables::Quantity::Length)
    throw LoadError(
        {path, line, cell.column + static_cast<int>(open) + 1},
        "'" + unit + "' is not a length unit (" + std::string(tables::unit_names(tables::Quantity::Length)) + ")");
  h.to_mm = u->to_core;
  h.has_unit = true;
  return h;
}

// Our CSV: the first line that is neither blank nor a comment starts with the cell "id".
bool is_volcomp_csv(const std::string& path) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    return tables::split_csv_line(line).front().text == "id";
  }
  return false;
}

std::vector<CmmPoint> read_volcomp_csv(const std::string& path, bool report) {
  const std::vector<tables::CsvRow> rows = tables::read_csv_rows(path, report ? "CMM report" : "CMM plan");
  if (rows.empty())
    throw LoadError({path}, "no header: id,x[mm],y[mm],z[mm],i,j,k" + std::string(report ? ",deviation[um]" : ""));
  const tables::CsvRow& header = rows.front();
  std::map<std::string, std::pair<int, HeaderCell>> columns;  // name -> index, cell
  for (std::size_t i = 0; i < header.cells.size(); ++i) {
    HeaderCell h = header_cell(path, header.line, header.cells[i]);
    if (columns.count(h.name))
      throw LoadError({path, header.line, header.cells[i].column}, "column " + h.name + " appears twice");
    columns[h.name] = {static_cast<int>(i), h};
  }
  auto need = [&](const std::string& name, bool length) {
    const auto it = columns.find(name);
    if (it == columns.end())
      throw LoadError({path, header.line}, "missing column " + name + (length ? "[mm] (a length with its unit)" : ""));
    if (length != it->second.second.has_unit)
      throw LoadError({path, header.line, header.cells[static_cast<std::size_t>(it->second.first)].column},
                      length ? "column " + name + " needs its unit, e.g. " + name + "[mm]"
                             : "column " + name + " is a direction cosine: no unit");
    return it->second;
  };
  const auto id = columns.find("id");
  if (id == columns.end()) throw LoadError({path, header.line}, "missing column id");
  const auto x = need("x", true), y = need("y", true), z = need("z", true);
  const auto i = need("i", false), j = need("j", false), k = need("k", false);
  const bool by_deviation = columns.count("deviation") != 0;
  const bool by_point = columns.count("mx") || columns.count("my") || columns.count("mz");
  if (report && !by_deviation && !by_point)
    throw LoadError({path, header.line}, "a report needs deviation[um] (along the normal) or mx[mm],my[mm],mz[mm]");
  if (by_deviation && by_point) throw LoadError({path, header.line}, "give either deviation or mx,my,mz, not both");
  using Column = std::pair<int, HeaderCell>;
  std::optional<Column> deviation;
  std::optional<std::array<Column, 3>> measured;
  if (by_deviation) deviation = need("deviation", true);
  if (by_point) measured = std::array<Column, 3>{need("mx", true), need("my", true), need("mz", true)};

  std::vector<CmmPoint> points;
  std::map<std::string, int> seen;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const tables::CsvRow& row = rows[r];
    if (row.cells.size() != header.cells.size())
      throw LoadError({path, row.line}, std::to_string(row.cells.size()) + " cells, the header has " +
                                            std::to_string(header.cells.size()));
    auto value = [&](const std::pair<int, HeaderCell>& c) {
      return tables::csv_number(path, row.line, row.cells[static_cast<std::size_t>(c.first)]) * c.second.to_mm;
    };
    CmmPoint p;
    p.line = row.line;
    p.id = row.cells[static_cast<std::size_t>(id->second.first)].text;
    if (p.id.empty())
      throw LoadError({path, row.line, row.cells[static_cast<std::size_t>(id->second.first)].column}, "empty id");
    if (const auto [it, fresh] = seen.emplace(p.id, row.line); !fresh)
      throw LoadError({path, row.line, row.cells[static_cast<std::size_t>(id->second.first)].column},
                      "id " + p.id + " already on line " + std::to_string(it->second));
    p.nominal = {value(x), value(y), value(z)};
    const Eigen::Vector3d n(value(i), value(j), value(k));
    if (std::abs(n.norm() - 1) > 1e-3)
      throw LoadError({path, row.line, row.cells[static_cast<std::size_t>(i.first)].column},
                      "the normal (i, j, k) is not a unit vector (length " + std::to_string(n.norm()) + ")");
    p.normal = n.normalized();
    if (deviation) {
      p.deviation_mm = value(*deviation);
    } else if (measured) {
      const Eigen::Vector3d m(value((*measured)[0]), value((*measured)[1]), value((*measured)[2]));
      p.deviation_mm = p.normal.dot(m - p.nominal);
    }
    points.push_back(p);
  }
  if (points.empty()) throw LoadError({path}, "no points");
  return points;
}

}  // namespace

std::vector<CmmPoint> read_cmm_points(const std::string& path, bool report, const ReportFormat& format,
                                      std::string* layout) {
  if (!is_volcomp_csv(path)) return read_cmm_export(path, report, format, layout);
  if (!format.unit.empty() || format.decimal_comma || format.sign == DeviationSign::NominalMinusActual)
    throw std::runtime_error(path +
                             " is volcomp's CSV (header id,x[mm],...): its units and sign are in its header "
                             "(deviation + = material left); --report-unit, --decimal-comma and --deviation-sign are "
                             "for other CMM exports");
  if (layout) *layout = "volcomp's CSV";
  return read_volcomp_csv(path, report);
}

void write_cmm_report(std::ostream& out, const std::vector<CmmPoint>& points,
                      const std::vector<std::string>& comments) {
  for (const std::string& c : comments) out << "# " << c << '\n';
  out << "id,x[mm],y[mm],z[mm],i,j,k,deviation[um]\n";
  for (const CmmPoint& p : points) {
    out << p.id;
    for (int a = 0; a < 3; ++a) out << ',' << number_text(p.nominal[a]);
    for (int a = 0; a < 3; ++a) out << ',' << number_text(p.normal[a]);
    out << ',';
    if (p.deviation_mm) out << number_text(std::round(*p.deviation_mm * 1e7) / 1e4);  // 0.1 nm
    out << '\n';
  }
}

std::vector<CmmPoint> measure(const MachinedSurface& surface, std::vector<CmmPoint> plan, const CmmOptions& options) {
  std::mt19937_64 random(options.seed);
  std::normal_distribution<double> noise(0.0, options.noise_um * 1e-3);
  const double r = options.probe_radius_mm;
  for (CmmPoint& p : plan) {
    std::optional<double> at = surface.deviation(p.nominal, p.normal);
    if (!at)
      throw std::runtime_error("CMM point " + p.id + " (line " + std::to_string(p.line) +
                               ") lies on no surface the program cut");
    double reading = *at;
    if (r > 0) {
      // The ball rests on the highest material under it: its centre height over the
      // surface heights h(o) at offsets o in the tangent plane is max(h(o) + sqrt(r^2 - |o|^2)) - r.
      Eigen::Vector3d u = p.normal.unitOrthogonal(), v = p.normal.cross(u);
      for (int ring = 1; ring <= 4; ++ring) {
        const double rho = r * ring / 4.0 * 0.999;
        for (int k = 0; k < 8; ++k) {
          const double a = k * M_PI / 4;
          const Eigen::Vector3d o = rho * (std::cos(a) * u + std::sin(a) * v);
          if (const auto h = surface.deviation(p.nominal + o, p.normal))
            reading = std::max(reading, *h + std::sqrt(r * r - rho * rho) - r);
        }
      }
    }
    p.deviation_mm = reading + (options.noise_um > 0 ? noise(random) : 0.0);
  }
  return plan;
}

}  // namespace vc::shop
