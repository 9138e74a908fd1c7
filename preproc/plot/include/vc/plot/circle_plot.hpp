// The ballbar polar plot of a circular test (`volcomp identify circle --plot`): the nominal
// circle and each direction's measured radius deviation magnified about it (ccw blue, cw red),
// the scale stated in um per division, angles from the plane's first axis towards its second
// (XY: +X at 0 deg, +Y at 90 deg), and the figures the command prints written beside it. The
// deviations drawn are the file's, as measured (about the nominal centre), converted to um.
#pragma once

#include <string>
#include <vector>

#include "vc/identify/iso230_4.hpp"
#include "vc/plot/gnuplot.hpp"

namespace vc::plot {

struct CirclePlotText {
  std::string title;                 // e.g. "Circular test (ISO 230-4), plane XY, R 150 mm"
  std::vector<std::string> notes;    // the file's metadata: under the title
  std::vector<std::string> figures;  // the lines the command prints (G(b), H, per direction ...)
};

// A "nice" scale (1, 2 or 5 times a power of ten, um per division) that fits the largest
// deviation `largest_um` into 3.5 divisions.
double circle_scale_um_per_division(double largest_um);

// The figure for draw(): data (per direction a block of angle, deviation, plotted radius) and script.
Figure circle_plot(const identify::CircularTest& test, const CirclePlotText& text, const std::string& image);

}  // namespace vc::plot
