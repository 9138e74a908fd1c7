// Drawing with gnuplot, the one way every volcomp plot is made: the data the plot draws is
// written as a CSV next to the image (a spreadsheet opens it; the image's name with .csv),
// gnuplot runs a script over it, and the image is checked (there, not empty, the format's
// signature) before it and its CSV are renamed into place. Nothing is ever half-written: both
// are made under temporary names beside their targets, and on any failure both temporaries
// are removed and the error says why (gnuplot missing from PATH, its own message).
#pragma once

#include <string>

namespace vc::plot {

struct Figure {
  std::string image;  // where the picture goes: a .png (pngcairo) or .svg (svg) file
  std::string data;   // the CSV text the plot draws: written to data_path(image)
  // gnuplot commands after the terminal and output are set; DATA is a gnuplot string
  // variable holding the data file's path (`plot DATA using 1:2`).
  std::string script;
  int width = 1400, height = 800;  // pixels (SVG: its size in the same numbers)
};

// The CSV that goes with an image: its name with the extension .csv (plots/x.png -> plots/x.csv).
std::string data_path(const std::string& image);

// Throws std::runtime_error (and writes nothing) when the extension is neither .png nor .svg,
// gnuplot cannot be run or fails, or its output is not a valid image.
void draw(const Figure& figure);

// `text` as a gnuplot double-quoted string literal: quotes and backslashes escaped, a line
// break as \n (gnuplot breaks the line there in titles and labels).
std::string text_literal(const std::string& text);

}  // namespace vc::plot
