// `volcomp report`: one self-contained HTML page of a machine's accuracy (issue 37): the machine
// (its file and every table file it loads, with SHA-256 checksums), the date, its error tables
// drawn, its location errors, the accuracy balance, the volume map (before correction, with a
// stock controller's tables by the usual practice and by the modified method, and what the full
// correction leaves), the laser runs and circular tests of a measurements folder with their
// ISO 230-2 / 230-4 figures and plots, and acceptance results side by side
// (acceptance_section.hpp). Pictures are PNGs embedded as data: URIs; no script, no font, no
// request: the page opens anywhere and prints on A4 (a page per section).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "vc/machine/model.hpp"
#include "vc/report/acceptance_section.hpp"

namespace vc::report {

struct ReportOptions {
  std::string measurements;                 // folder (optional)
  std::vector<double> tool_lengths_mm;      // of the volume map; default: 0 and the machine file's
  std::vector<AcceptanceInput> acceptance;  // `acceptance evaluate` results, each labelled (optional)
  std::string command;                      // the command line that made it, shown on the page
};

struct Report {
  std::string html;
  int sections = 0;  // each starts a printed page
  int figures = 0;   // <figure> elements, each holding one embedded PNG
  int measurements = 0;
  int acceptance = 0;  // results files in the acceptance section
};

// Progress goes to `progress` (one line per part). Throws what the parts throw (a measurement
// that cannot be read, gnuplot missing or failing, ...): then nothing is returned.
Report accuracy_report(const machine::Model& model, const ReportOptions& options, std::ostream& progress);

}  // namespace vc::report
