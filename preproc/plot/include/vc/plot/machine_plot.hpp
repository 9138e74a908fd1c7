// `volcomp plot MACHINE`: the machine file's errors drawn. For each axis, its component errors
// against its position (translations in um, rotations in the unit family of its table files:
// arcsec where they are in arcsec or deg, urad where in urad, mrad or rad), one picture per
// axis with its data CSV; and the location errors (squareness, rotary axis offsets) listed
// with units. The values are the model's, as the compensation uses them: the table file's
// units converted, the machine file's `scale` and `measured_at_mm` applied.
#pragma once

#include <string>
#include <vector>

#include "vc/machine/model.hpp"
#include "vc/plot/gnuplot.hpp"

namespace vc::plot {

struct AxisPlot {
  bool drawn = false;                  // the axis has a table over its own position alone
  Figure figure;                       // when drawn
  std::vector<std::string> not_drawn;  // its other tables (over other axes or a temperature), why
};

// The tables of axis `joint` over its own position alone, drawn into `image`.
AxisPlot axis_plot(const machine::Model& model, int joint, const std::string& image);

struct LocationRow {
  std::string line;    // the axis letter, or "spindle"
  std::string symbol;  // EC0Y, EX0C, EA0S, ...
  std::string meaning;
  double value = 0.0;  // in `unit`
  std::string unit;    // um (lengths) or arcsec (angles)
};

// Every location error of every axis line and of the spindle line, zero or not, joint order.
std::vector<LocationRow> location_errors(const machine::Model& model);

// The CSV of location_errors, with a header comment naming the machine and the units.
std::string location_errors_csv(const machine::Model& model);

}  // namespace vc::plot
