#include "vc/plot/circle_plot.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "plot_format.hpp"

namespace vc::plot {
namespace {

// The nominal circle is drawn at this many divisions from the centre; the rings reach 9.
constexpr double kNominalRing = 5.0, kOuterRing = 9.0;

}  // namespace

double circle_scale_um_per_division(double largest_um) {
  const double wanted = std::max(largest_um, 1e-3) / 3.5;
  double decade = std::pow(10.0, std::floor(std::log10(wanted)));
  for (;; decade *= 10)
    for (const double step : {1.0, 2.0, 5.0})
      if (step * decade >= wanted * (1 - 1e-12)) return step * decade;
}

Figure circle_plot(const identify::CircularTest& test, const CirclePlotText& text, const std::string& image) {
  double largest_um = 0;
  for (const identify::CircleRun& run : test.runs)
    for (const auto& [angle, deviation] : run.points) largest_um = std::max(largest_um, std::abs(deviation) * 1e3);
  const double scale = circle_scale_um_per_division(largest_um);
  const std::string first(1, test.plane[0]), second(1, test.plane[1]);

  std::ostringstream csv;
  csv << "# volcomp identify circle --plot: the polar plot " << image << " draws these numbers\n"
      << "# run: " << test.path << ", plane " << test.plane << ", radius " << number(test.radius_mm) << " mm\n"
      << "# angle from +" << first << " towards +" << second << "; deviation = measured radius - nominal, um\n"
      << "# scale " << number(scale) << " um/div: plotted_radius = " << number(kNominalRing)
      << " div (the nominal circle) + deviation / scale; a run covering the turn is closed by its first reading "
         "repeated at +360 deg\n";
  for (const std::string& f : text.figures) csv << "# " << f << "\n";
  for (std::size_t k = 0; k < test.runs.size(); ++k) {
    const identify::CircleRun& run = test.runs[k];
    if (k > 0) csv << "\n\n";  // gnuplot's data blocks (index 0, 1)
    csv << "direction,angle[deg],deviation[um],plotted_radius[div]\n";
    auto row = [&](double angle_rad, double deviation_mm) {
      csv << (run.ccw ? "ccw" : "cw") << "," << number(angle_rad * 180 / M_PI) << "," << number(deviation_mm * 1e3)
          << "," << number(kNominalRing + deviation_mm * 1e3 / scale) << "\n";
    };
    for (const auto& [angle, deviation] : run.points) row(angle, deviation);
    // Closed where the readings cover the turn (a gap of at most 10 deg at the start).
    if (run.points.size() > 2 &&
        run.points.front().first + 2 * M_PI - run.points.back().first <= 10 * M_PI / 180 + 1e-12)
      row(run.points.front().first + 2 * M_PI, run.points.front().second);
  }

  std::string figures;
  for (const std::string& f : text.figures) figures += (figures.empty() ? "" : "\n") + f;
  std::string subtitle = test.path;
  for (const std::string& note : text.notes) subtitle += "\n" + note;
  const auto angle_label = [&](int degrees) {
    const char* names[] = {"+", "+", "-", "-"};
    std::string label = std::to_string(degrees) + "°";
    if (degrees % 90 == 0) label += std::string("  ") + names[degrees / 90] + (degrees / 90 % 2 ? second : first);
    return label;
  };
  std::ostringstream gp;
  gp << "set datafile separator ','\n"
     << "set title " << text_literal(text.title + "\n" + subtitle) << " font 'sans,12'\n"
     << "set polar\nset angles degrees\nset size square\nunset border\nunset xtics\nunset ytics\nunset raxis\n"
     << "set lmargin at screen 0.06\nset rmargin at screen 0.60\nset tmargin at screen 0.86\nset bmargin at screen 0.05\n"
     << "set rrange [0:" << number(kOuterRing) << "]\nset trange [0:360]\nset samples 721\n"
     << "set rtics 1 format '' scale 0\nset ttics (";
  for (int d = 0; d < 360; d += 30) gp << (d ? ", " : "") << text_literal(angle_label(d)) << " " << d;
  gp << ") font 'sans,10'\n"
     << "set grid polar 30 r lt 1 lw 0.8 lc rgb '#d8d8d8'\n"
     << "set key at screen 0.62, screen 0.86 left top Left reverse samplen 3 spacing 1.2 box lc rgb '#bbbbbb'\n"
     << "set label 1 "
     << text_literal("scale " + number(scale) + " um/div\nrings every " + number(scale) +
                     " um of radius deviation; the nominal circle\n(R " + number(test.radius_mm) +
                     " mm) lies 5 divisions out")
     << " at screen 0.625, screen 0.725 left front font 'sans,11'\n"
     << "set label 2 " << text_literal(figures) << " at screen 0.625, screen 0.61 left front font 'sans,10'\n"
     << "plot " << number(kNominalRing) << " with lines lw 3 lc rgb '#9a9a9a' title "
     << text_literal("nominal circle, R " + number(test.radius_mm) + " mm");
  for (std::size_t k = 0; k < test.runs.size(); ++k)
    gp << ", \\\n     DATA index " << k << " using 2:4 with lines lw 2 lc rgb '"
       << (test.runs[k].ccw ? "#1f5fbf" : "#c0392b") << "' title "
       << text_literal(test.runs[k].ccw ? "counterclockwise (ccw)" : "clockwise (cw)");
  gp << "\n";
  return {image, csv.str(), gp.str(), 1400, 900};
}

}  // namespace vc::plot
