#include "vc/report/measurements.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>

#include "vc/identify/iso230_4.hpp"
#include "vc/identify/iso230_2.hpp"
#include "vc/identify/laser_runs.hpp"
#include "vc/plot/circle_plot.hpp"
#include "vc/plot/component_names.hpp"
#include "vc/plot/laser_plot.hpp"
#include "vc/report/html.hpp"
#include "vc/tables/symbols.hpp"

namespace vc::report {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// The first line that is neither blank nor a "#" comment: the header, lower case.
std::string header_line(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot be read");
  for (std::string line; std::getline(in, line);) {
    const std::size_t at = line.find_first_not_of(" \t\r");
    if (at == std::string::npos || line[at] == '#') continue;
    return lower(line);
  }
  return "";
}

// A length in um, an angle in arcsec (and urad), as `volcomp identify laser` prints them.
std::string shown(double v, tables::Quantity q) {
  return q == tables::Quantity::Length ? fixed(v * 1e3, 2) + " um"
                                       : fixed(v * 648000.0 / M_PI, 2) + " arcsec (" + fixed(v * 1e6, 1) + " urad)";
}

// The error laser runs measure: "# error: EXX" in the file, else its name's first word.
tables::ErrorSymbol laser_error(const identify::LaserRuns& runs, const fs::path& file) {
  std::string named;
  for (const auto& [key, value] : runs.metadata)
    if (lower(key) == "error") named = value;
  if (named.empty()) {
    const std::string stem = file.stem().string();
    named = stem.substr(0, stem.find_first_of("_-. "));
  }
  std::string upper = named;
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  const auto symbol = tables::parse_error_symbol(upper);
  if (!symbol || symbol->location)
    throw std::runtime_error(file.string() +
                             ": laser runs of which component error? Name the file after it (exx.csv, "
                             "eyx_2026-11.csv) or add a line '# error: EXX' (\"" +
                             named + "\" is none)");
  const bool rotary_axis = symbol->axis == 'A' || symbol->axis == 'B' || symbol->axis == 'C';
  if (runs.rotary != rotary_axis)
    throw std::runtime_error(file.string() + ": the targets are in " + (runs.rotary ? "deg" : "mm") + " but " +
                             symbol->name() + " is an error of the " + (rotary_axis ? "rotary" : "linear") + " axis " +
                             std::string(1, symbol->axis));
  if (runs.quantity != symbol->quantity())
    throw std::runtime_error(file.string() + ": the deviations are " +
                             (runs.quantity == tables::Quantity::Length ? "lengths" : "angles") + " but " +
                             symbol->name() + " is " +
                             (symbol->quantity() == tables::Quantity::Length ? "a translation" : "a rotation"));
  return *symbol;
}

Measurement laser(const fs::path& file, const std::string& machine_name, const std::string& image) {
  const identify::LaserRuns runs = identify::read_laser_runs(file.string());
  const tables::ErrorSymbol symbol = laser_error(runs, file);
  std::set<identify::RunKey> left_out;
  Measurement m;
  m.path = file.string();
  m.kind = "laser";
  for (const auto& [key, value] : runs.metadata) m.notes.push_back(key + ": " + value);
  for (const identify::SuspiciousRun& s : identify::suspicious_runs(runs)) {
    left_out.insert(s.run);
    m.notes.push_back("left out (not drawn): " + s.reason);
  }
  const identify::Iso230_2 e = identify::evaluate_iso230_2(runs, left_out);
  const tables::Quantity q = runs.quantity;
  const auto up_down = [&](double up, double down) {
    return " (up " + shown(up, q) + ", down " + shown(down, q) + ")";
  };
  m.title = "ISO 230-2: " + symbol.name() + " " + plot::component_meaning(symbol) + " of axis " +
            std::string(1, symbol.axis) + ", " + machine_name;
  m.figures = {{"B", shown(e.reversal, q) + " (mean " + shown(e.mean_reversal, q) + ")"},
               {"R", shown(e.repeatability, q) + up_down(e.repeatability_up, e.repeatability_down)},
               {"E", shown(e.systematic, q) + up_down(e.systematic_up, e.systematic_down)},
               {"M", shown(e.range, q)},
               {"A", shown(e.accuracy, q) + up_down(e.accuracy_up, e.accuracy_down)}};
  plot::LaserPlotText text{m.title, m.notes, m.figures};
  m.figure = plot::laser_plot(runs, left_out, e, text, image);
  // The table's names in words, for the page (the plot writes the letters ISO 230-2 uses).
  const char* const names[] = {"reversal value B", "repeatability R", "systematic deviation E",
                               "mean bidirectional range M", "accuracy A"};
  for (std::size_t k = 0; k < m.figures.size(); ++k) m.figures[k].first = names[k];
  m.notes.insert(m.notes.begin(), std::to_string(e.targets.size()) + " targets, " + std::to_string(e.runs_up) +
                                      " runs up and " + std::to_string(e.runs_down) + " down evaluated");
  return m;
}

Measurement circle(const fs::path& file, const std::string& machine_name, const std::string& image) {
  const identify::CircularTest test = identify::read_circular_test(file.string());
  const identify::CircularEvaluation e = identify::evaluate_circular_test(test);
  const auto um = [](double mm) { return fixed(mm * 1e3, 2) + " um"; };
  const auto arcsec = [](double rad) { return fixed(rad * 648000.0 / M_PI, 2) + " arcsec"; };
  const std::string first(1, test.plane[0]), second(1, test.plane[1]);
  Measurement m;
  m.path = file.string();
  m.kind = "circle";
  m.title = "Circular test (ISO 230-4), plane " + test.plane + ", radius " + fixed(test.radius_mm, 1) + " mm, " +
            machine_name;
  m.figures.emplace_back("bidirectional circular deviation G(b)", um(e.circular_deviation_mm));
  if (test.runs.size() == 2) m.figures.emplace_back("circular hysteresis H", um(e.hysteresis_mm));
  std::vector<std::string> plotted;
  for (const auto& [name, value] : m.figures) plotted.push_back(name + " " + value);
  for (const identify::CircleFit& f : e.fits) {
    const std::string direction = f.ccw ? "ccw" : "cw";
    m.figures.emplace_back(direction + ": circular deviation G", um(f.circular_deviation_mm));
    m.figures.emplace_back(direction + ": radial deviation F", um(f.radial_deviation_mm));
    m.figures.emplace_back(direction + ": centre offset",
                           first + " " + um(f.centre_first_mm) + ", " + second + " " + um(f.centre_second_mm));
    m.figures.emplace_back(direction + ": left by the first-order fit (RMS)", um(f.residual_rms_mm));
    plotted.push_back(direction + ": G " + um(f.circular_deviation_mm) + ", F " + um(f.radial_deviation_mm));
  }
  m.figures.emplace_back("squareness (both directions' mean; " + first + "' = " + first + " + theta " + second + ")",
                         arcsec(e.squareness_rad));
  m.figures.emplace_back("scale mismatch e" + first + " - e" + second, fixed(e.scale_mismatch * 1e6, 2) + " um/m");
  plotted.push_back("squareness " + arcsec(e.squareness_rad));
  plotted.push_back("scale mismatch " + fixed(e.scale_mismatch * 1e6, 2) + " um/m");
  for (const auto& [key, value] : test.metadata)
    if (key != "plane" && key != "radius_mm") m.notes.push_back(key + ": " + value);
  plot::CirclePlotText text{m.title, m.notes, plotted};
  m.figure = plot::circle_plot(test, text, image);
  return m;
}

}  // namespace

Measurements read_measurements(const std::string& folder, const std::string& machine_name,
                               const std::function<std::string(std::size_t)>& image_path) {
  std::error_code error;
  if (!fs::exists(folder, error)) throw std::runtime_error("--measurements " + folder + ": no such folder");
  if (!fs::is_directory(folder, error)) throw std::runtime_error("--measurements " + folder + ": not a folder");
  std::vector<fs::path> files;
  fs::directory_iterator it(folder, error);
  for (; !error && it != fs::directory_iterator(); it.increment(error)) files.push_back(it->path());
  if (error)
    throw std::runtime_error("--measurements " + folder + ": cannot read the folder (" + error.message() + ")");
  std::sort(files.begin(), files.end());

  Measurements result;
  for (const fs::path& file : files) {
    if (!fs::is_regular_file(file)) continue;
    if (lower(file.extension().string()) != ".csv") {
      result.skipped.push_back(file.filename().string() + ": not a .csv file");
      continue;
    }
    const std::string header = header_line(file);
    const std::string image = image_path(result.found.size());
    if (header.find("target") != std::string::npos)
      result.found.push_back(laser(file, machine_name, image));
    else if (header.find("angle") != std::string::npos)
      result.found.push_back(circle(file, machine_name, image));
    else
      result.skipped.push_back(
          file.filename().string() +
          ": neither laser runs (a target[mm] or target[deg] column) nor a circular test (an angle[deg] column)");
  }
  return result;
}

}  // namespace vc::report
