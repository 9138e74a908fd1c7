#include "vc/plot/machine_plot.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "plot_format.hpp"
#include "vc/plot/component_names.hpp"
#include "vc/tables/csv.hpp"

namespace vc::plot {
namespace {

constexpr double kArcsecPerRad = 648000.0 / M_PI;
const char* const kColour[] = {"#1f77b4", "#2ca02c", "#d62728", "#9467bd", "#ff7f0e", "#8c564b"};  // X Y Z A B C

// The unit a column's header cell gives in its table file ("EAX[arcsec]" -> "arcsec").
std::string header_unit(const tables::Column& column) {
  std::ifstream in(column.where.path);
  std::string line;
  for (int n = 0; n < column.where.line && std::getline(in, line);) ++n;
  for (const tables::CsvCell& cell : tables::split_csv_line(line))
    if (cell.column == column.where.column) {
      const std::size_t open = cell.text.find('['), close = cell.text.find(']');
      if (open != std::string::npos && close > open) return cell.text.substr(open + 1, close - open - 1);
    }
  return "";
}

}  // namespace

AxisPlot axis_plot(const machine::Model& model, int joint, const std::string& image) {
  const machine::Axis& axis = model.axes[static_cast<std::size_t>(joint)];
  const bool rotary = axis.type == machine::AxisType::Rotary;
  const char lower = static_cast<char>(std::tolower(static_cast<unsigned char>(axis.letter)));
  const std::string position_unit = rotary ? "deg" : "mm";
  AxisPlot result;
  std::vector<const tables::ErrorTable*> drawn;
  for (const int t : axis.tables) {
    const tables::ErrorTable& table = model.tables[static_cast<std::size_t>(t)].table;
    const auto& grid = table.grid();
    if (grid.size() == 1 && !grid[0].is_temperature() && grid[0].axis == axis.letter) {
      drawn.push_back(&table);
      continue;
    }
    std::string over;
    for (const tables::GridVariable& g : grid) over += (over.empty() ? "" : " and ") + g.name();
    result.not_drawn.push_back(table.path() + " (a table over " + over + ", not " + std::string(1, lower) + " alone)");
  }
  if (axis.thermal.input >= 0)
    result.not_drawn.push_back("the thermal expansion with " +
                               model.temperatures[static_cast<std::size_t>(axis.thermal.input)].name);
  if (drawn.empty()) return result;
  result.drawn = true;

  // Rotations in urad when every angular column of the axis's tables is in urad, mrad or rad.
  bool any_angle = false, any_length = false, radians = true;
  for (const tables::ErrorTable* table : drawn)
    for (const tables::Column& c : table->columns()) {
      if (c.symbol.quantity() == tables::Quantity::Length) {
        any_length = true;
        continue;
      }
      any_angle = true;
      const std::string u = header_unit(c);
      if (u != "urad" && u != "mrad" && u != "rad") radians = false;
    }
  const std::string angle_unit = radians ? "urad" : "arcsec";
  const double angle_factor = radians ? 1e6 : kArcsecPerRad;

  const std::string where = model.info.name + " (" + model.path + ")";
  std::ostringstream csv;
  csv << "# volcomp plot: the component errors of axis " << axis.letter << " of " << where << ", drawn in " << image
      << "\n# error = actual - nominal; translations in um, rotations in " << angle_unit << ", " << lower << " in "
      << position_unit
      << "; the values the model uses at the table's nodes (the table file's units converted, the "
         "machine file's scale and measured_at_mm applied)\n";
  double low = axis.travel_min, high = axis.travel_max;
  for (std::size_t k = 0; k < drawn.size(); ++k) {
    const tables::ErrorTable& table = *drawn[k];
    if (k > 0) csv << "\n\n";  // gnuplot's data blocks (index 0, 1, ...)
    csv << "# table " << k + 1 << ": " << table.path() << " ("
        << (table.interpolation() == tables::Interpolation::Cubic ? "cubic" : "linear") << " interpolation)\n"
        << lower << "[" << position_unit << "]";
    for (const tables::Column& c : table.columns())
      csv << "," << c.symbol.name() << "[" << (c.symbol.quantity() == tables::Quantity::Length ? "um" : angle_unit)
          << "]";
    csv << "\n";
    const std::vector<double>& nodes = table.grid()[0].nodes;
    low = std::min(low, nodes.front());
    high = std::max(high, nodes.back());
    for (int n = 0; n < table.node_count(); ++n) {
      csv << number(nodes[static_cast<std::size_t>(n)]);
      for (int c = 0; c < static_cast<int>(table.columns().size()); ++c) {
        const bool length = table.columns()[static_cast<std::size_t>(c)].symbol.quantity() == tables::Quantity::Length;
        csv << "," << number(table.value(n, c) * (length ? 1e3 : angle_factor));
      }
      csv << "\n";
    }
  }

  // One panel for the translations, one for the rotations (the two that are there). Within a
  // panel each curve is drawn thinner than the one before, with its own point type, so that
  // curves lying on each other (the MC-300's straightnesses) still show; a column equal to an
  // earlier one at every node says so in the legend.
  const auto same_values = [](const tables::ErrorTable& a, int ca, const tables::ErrorTable& b, int cb) {
    if (&a != &b) return false;
    for (int n = 0; n < a.node_count(); ++n)
      if (std::abs(a.value(n, ca) - b.value(n, cb)) > 1e-12) return false;
    return true;
  };
  const auto curves = [&](tables::Quantity quantity) {
    std::string plot;
    std::vector<std::pair<const tables::ErrorTable*, int>> earlier;
    for (std::size_t k = 0; k < drawn.size(); ++k) {
      const tables::ErrorTable& table = *drawn[k];
      const std::string file = std::filesystem::path(table.path()).filename().string();
      for (std::size_t c = 0; c < table.columns().size(); ++c) {
        const tables::ErrorSymbol& s = table.columns()[c].symbol;
        if (s.quantity() != quantity) continue;
        std::string title = s.name() + "  " + component_meaning(s);
        if (drawn.size() > 1) title += "  (" + file + ")";
        for (const auto& [other, column] : earlier)
          if (same_values(*other, column, table, static_cast<int>(c))) {
            title += "  (= " + other->columns()[static_cast<std::size_t>(column)].symbol.name() + ")";
            break;
          }
        const int order = static_cast<int>(earlier.size());
        earlier.emplace_back(&table, static_cast<int>(c));
        plot += std::string(plot.empty() ? "plot " : ", \\\n     ") + "DATA index " + std::to_string(k) +
                " using 1:" + std::to_string(c + 2) + " with linespoints lw " +
                number(std::max(1.0, 3.6 - 1.1 * order)) + " pt " +
                std::to_string(std::array{7, 5, 9, 11, 13, 15}[static_cast<std::size_t>(order % 6)]) + " ps " +
                number(std::max(0.5, 1.0 - 0.2 * order)) + " " + (k > 0 ? "dt 2 " : "") + "lc rgb '" +
                kColour[s.component] + "' title " + text_literal(title);
      }
    }
    return plot + ", \\\n     keyentry with lines dt 2 lw 1.5 lc rgb '#777777' title " +
           text_literal("travel " + number(axis.travel_min) + " .. " + number(axis.travel_max) + " " + position_unit) +
           "\n";
  };
  const double pad = (high - low) * 0.02;
  std::ostringstream gp;
  gp << "set datafile separator ','\n";
  std::string files;
  for (const tables::ErrorTable* table : drawn) files += (files.empty() ? "" : ", ") + table->path();
  gp << "set multiplot title "
     << text_literal(where + ": axis " + std::string(1, axis.letter) + " (" + (rotary ? "rotary" : "linear") +
                     "), component errors, error = actual - nominal\n" + "the model's values at the nodes of " + files +
                     " (units converted, the machine file's scale and measured_at_mm applied)")
     << " font 'sans,12'\n"
     << "set lmargin at screen 0.08\nset rmargin at screen 0.72\n"
     << "set grid xtics ytics mxtics mytics lw 1 lc rgb '#d0d0d0', lw 0.5 lc rgb '#ececec'\nset mxtics 2\nset mytics 2\n"
     << "set xzeroaxis lt -1 lw 1\n"
     << "set xrange [" << number(low - pad) << ":" << number(high + pad) << "]\n"
     << "set offsets 0, 0, graph 0.08, graph 0.08\n";
  if (rotary && high - low >= 180) gp << "set xtics 30\n";
  for (const double at : {axis.travel_min, axis.travel_max})
    gp << "set arrow from " << number(at) << ", graph 0 to " << number(at)
       << ", graph 1 nohead dt 2 lw 1.5 lc rgb '#777777'\n";
  const std::string xlabel =
      "set xlabel " + text_literal(std::string(1, axis.letter) + " position (" + position_unit + ")") + "\n";
  struct Panel {
    tables::Quantity quantity;
    std::string title, ylabel;
  };
  std::vector<Panel> panels;
  if (any_length)
    panels.push_back({tables::Quantity::Length,
                      rotary ? "translations: run-outs" : "translations: positioning and straightness",
                      "translation error (um)"});
  if (any_angle)
    panels.push_back({tables::Quantity::Angle,
                      rotary ? "rotations: angular positioning and tilts"
                      : axis.letter == 'Z' || axis.letter == 'W'
                          ? "rotations: roll and tilts"  // vertical: no pitch, yaw
                          : "rotations: roll, pitch and yaw",
                      "rotation error (" + angle_unit + ")"});
  const double top = 0.87, bottom = 0.08, gap = 0.08;
  const double height =
      (top - bottom - gap * static_cast<double>(panels.size() - 1)) / static_cast<double>(panels.size());
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const double panel_top = top - static_cast<double>(p) * (height + gap);
    gp << "set tmargin at screen " << number(panel_top) << "\nset bmargin at screen " << number(panel_top - height)
       << "\n"
       << "set title " << text_literal(panels[p].title) << " font 'sans,11'\n"
       << "set ylabel " << text_literal(panels[p].ylabel) << "\n"
       << (p + 1 == panels.size() ? xlabel : "unset xlabel\n") << "set key at screen 0.735, screen "
       << number(panel_top) << " left top Left reverse samplen 3 spacing 1.15 box lc rgb '#bbbbbb'\n"
       << curves(panels[p].quantity);
  }
  gp << "unset multiplot\n";
  result.figure = {image, csv.str(), gp.str(), 1400, panels.size() > 1 ? 1000 : 640};
  return result;
}

std::vector<LocationRow> location_errors(const machine::Model& model) {
  std::vector<LocationRow> rows;
  const auto add = [&](char line, bool rotary, const Eigen::Vector3d& mm, const Eigen::Vector3d& rad) {
    for (int component = 0; component < 6; ++component) {
      const tables::ErrorSymbol s{component, line, true};
      const bool length = component < 3;
      rows.push_back({line == 'S' ? "spindle" : std::string(1, line), s.name(), location_meaning(s, rotary),
                      length ? mm[component] * 1e3 : rad[component - 3] * kArcsecPerRad, length ? "um" : "arcsec"});
    }
  };
  for (const machine::Axis& a : model.axes)
    add(a.letter, a.type == machine::AxisType::Rotary, a.location_mm, a.location_rad);
  add('S', false, model.spindle.location_mm, model.spindle.location_rad);
  return rows;
}

std::string location_errors_csv(const machine::Model& model) {
  std::ostringstream csv;
  csv << "# volcomp plot: the location errors of " << model.info.name << " (" << model.path
      << "), every axis line and the spindle line; 0: not in the file (or 0 there)\n"
      << "# error = actual - nominal; lengths in um, angles in arcsec (1 arcsec = 4.848 urad)\n"
      << "line,symbol,meaning,value,unit\n";
  for (const LocationRow& r : location_errors(model))
    csv << r.line << "," << r.symbol << "," << r.meaning << "," << number(r.value) << "," << r.unit << "\n";
  return csv.str();
}

}  // namespace vc::plot
