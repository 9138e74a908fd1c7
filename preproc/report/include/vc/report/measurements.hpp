// The measurements of `volcomp report --measurements DIR`: every *.csv in DIR (not its
// sub-folders), by name, read as what its header says it is:
//   - laser runs (a `target[...]` column; identify laser's layouts): ISO 230-2 evaluated as
//     `volcomp identify laser` does (suspicious runs left out, named), the error it measures
//     from a `# error: EXX` line or else from the file's name (exx.csv, eyx_2026-11.csv);
//   - a circular test (an `angle[...]` column; identify circle's layouts): ISO 230-4 evaluated
//     as `volcomp identify circle` does.
// Other files are listed as skipped. A measurement file that cannot be read or evaluated stops
// the report with its file:line:column message: a report never leaves a measurement out silently.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "vc/plot/gnuplot.hpp"

namespace vc::report {

struct Measurement {
  std::string path;
  std::string kind;                                          // "laser" (ISO 230-2) or "circle" (ISO 230-4)
  std::string title;                                         // e.g. "EXX positioning of axis X (ISO 230-2)"
  std::vector<std::pair<std::string, std::string>> figures;  // name (with its symbol), value with unit
  std::vector<std::string> notes;                            // the file's metadata, runs left out
  plot::Figure figure;  // its plot (the image path: the caller's, set by image_path)
};

struct Measurements {
  std::vector<Measurement> found;
  std::vector<std::string> skipped;  // files that are neither, "name: why"
};

// `image_path(k)` gives the k-th plot's image path (a .png). Throws std::runtime_error for a
// folder that does not exist or cannot be read, vc::LoadError or std::runtime_error (with the
// file) for a measurement that cannot be read or evaluated.
Measurements read_measurements(const std::string& folder, const std::string& machine_name,
                               const std::function<std::string(std::size_t)>& image_path);

}  // namespace vc::report
