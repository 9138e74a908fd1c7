#include "vc/plot/volume_map_plot.hpp"

#include <algorithm>
#include <sstream>

#include "plot_format.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::plot {
namespace {

std::string letter(const machine::Model& model, int joint) {
  return std::string(1, model.axes[static_cast<std::size_t>(joint)].letter);
}

}  // namespace

std::string volume_map_name(const MapSheet& sheet) {
  return "volume_L" + number(sheet.tool_length_mm) + (sheet.rotary.worst ? "_worst" : "_rotary0");
}

Figure volume_map_plot(const VolumeMap& map, std::size_t sheet_index, const machine::Model& model,
                       const std::string& image) {
  const MapSheet& sheet = map.sheets.at(sheet_index);
  const std::string x = letter(model, map.first_joint), y = letter(model, map.second_joint),
                    z = letter(model, map.level_joint);
  const std::size_t rows = sheet.error_um.size(), columns = map.levels_mm.size();
  // One colour scale for the sheet: the uncompensated error's largest value (never below 1 um,
  // so that a nearly perfect machine does not look red all over).
  const double top = std::max(1.0, sheet.max_um.front());

  std::ostringstream data;
  data << "# volume map of " << map.machine_name << " (" << map.machine_path
       << "): tool-tip error |e|, L = " << number(sheet.tool_length_mm) << " mm, " << sheet.rotary.label << "\n"
       << "# columns: " << x << "[mm]," << y << "[mm],e[um] (joint positions; |real tip - ideal tip|)\n"
       << "# blocks (gnuplot index) compensation-major: ";
  for (std::size_t c = 0; c < rows; ++c)
    for (std::size_t l = 0; l < columns; ++l)
      data << (c || l ? "; " : "") << c * columns + l << " = " << map.compensations[c] << " at " << z << " "
           << number(map.levels_mm[l]) << " mm";
  data << "\n";
  for (std::size_t c = 0; c < rows; ++c)
    for (std::size_t l = 0; l < columns; ++l) {
      if (c || l) data << "\n\n";
      data << "# " << map.compensations[c] << ", " << z << " = " << number(map.levels_mm[l]) << " mm\n";
      const std::vector<double>& e = sheet.error_um[c][l];
      for (std::size_t j = 0; j < map.second_mm.size(); ++j)
        for (std::size_t i = 0; i < map.first_mm.size(); ++i)
          data << number(map.first_mm[i]) << ',' << number(map.second_mm[j]) << ','
               << number(e[j * map.first_mm.size() + i]) << '\n';
    }

  std::ostringstream gp;
  const std::string title = map.machine_name + ": tool-tip error |e| (um) over " + x + "-" + y +
                            ", L = " + number(sheet.tool_length_mm) + " mm, " + sheet.rotary.label +
                            (sheet.rotary.worst ? " (the worst rotary position)" : "") +
                            (map.controller_title.empty()
                                 ? ""
                                 : "\nrows: no compensation; the tables by the usual practice; by the modified method"
                                   "\ntables: " +
                                       map.controller_title) +
                            "\n" + full_correction_statement(map);
  gp << "set datafile separator ','\n"
     << "set multiplot layout " << rows << "," << columns << " title " << text_literal(title) << " font 'sans,12'\n"
     << "set palette defined (0 '#f7fbff', 0.25 '#9ecae1', 0.5 '#fdd049', 0.75 '#f16913', 1 '#99000d')\n"
     << "set cbrange [0:" << number(top) << "]\n"  // no colour-box label: the title says |e| in um
     << "set xrange [" << number(map.first_mm.front()) << ":" << number(map.first_mm.back()) << "]\n"
     << "set yrange [" << number(map.second_mm.front()) << ":" << number(map.second_mm.back()) << "]\n"
     << "set xlabel " << text_literal(x + " (mm)") << "\nset ylabel " << text_literal(y + " (mm)") << "\n"
     << "set tics out\nunset key\n";
  for (std::size_t c = 0; c < rows; ++c)
    for (std::size_t l = 0; l < columns; ++l) {
      const std::vector<double>& e = sheet.error_um[c][l];
      const double largest = *std::max_element(e.begin(), e.end());
      gp << "set title "
         << text_literal(map.compensations[c] + ", " + z + " " + number(map.levels_mm[l]) + " mm: max " +
                         fixed_text(largest, 1) + " um")
         << "\nplot DATA index " << c * columns + l << " using 1:2:3 with image\n";
    }
  gp << "unset multiplot\n";
  return {image, data.str(), gp.str(), 1500, static_cast<int>(170 + 400 * rows)};
}

}  // namespace vc::plot
