// The report's pictures: each plot is drawn by vc::plot::draw (gnuplot, checked) into a scratch
// folder of its own and read back as PNG bytes to embed; the folder and everything in it is
// removed when the Drawings go (the report leaves no file but itself).
#pragma once

#include <string>

#include "vc/plot/gnuplot.hpp"

namespace vc::report {

class Drawings {
 public:
  Drawings();  // throws std::runtime_error when no scratch folder can be made
  Drawings(const Drawings&) = delete;
  Drawings& operator=(const Drawings&) = delete;
  ~Drawings();

  // A path in the scratch folder for an image named `name` (a .png name).
  std::string path(const std::string& name) const;
  // Draws `figure` (its image is a path() of this scratch folder) and returns the PNG's bytes.
  std::string png(const plot::Figure& figure) const;

 private:
  std::string folder_;
};

}  // namespace vc::report
