// The ISO 230-2 graph of laser runs (`volcomp identify laser --plot`): every run's deviations
// against the target position (up runs solid with upward triangles, down runs dashed with
// downward ones), the mean up and down with their +-2s bands and the mean bidirectional line,
// as ISO 230-2 draws them, and the evaluation's figures written beside the graph. The numbers
// all come from the evaluation the command prints (vc::identify::Iso230_2): nothing is
// computed again here, only converted to um (lengths) or urad (angles).
#pragma once

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "vc/identify/iso230_2.hpp"
#include "vc/identify/laser_runs.hpp"
#include "vc/plot/gnuplot.hpp"

namespace vc::plot {

struct LaserPlotText {
  std::string title;               // e.g. "EXX positioning of X, MC-300"
  std::vector<std::string> notes;  // the runs' metadata, the runs left out: under the figures
  // The figures as the command prints them, e.g. {"A", "18.96 um (up 17.1 um, down 16.2 um)"}.
  std::vector<std::pair<std::string, std::string>> figures;
};

// The figure for draw(): data (one row per target: the runs kept, the means, the +-2s lines)
// and script. `left_out` are the runs the evaluation left out (not drawn).
Figure laser_plot(const identify::LaserRuns& runs, const std::set<identify::RunKey>& left_out,
                  const identify::Iso230_2& evaluation, const LaserPlotText& text, const std::string& image);

}  // namespace vc::plot
