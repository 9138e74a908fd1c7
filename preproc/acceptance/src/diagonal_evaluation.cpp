#include "vc/acceptance/diagonal_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "vc/tables/number_text.hpp"

namespace vc::acceptance {

bool DiagonalResult::passes() const {
  return std::all_of(figures.begin(), figures.end(), [](const Figure& f) { return f.passes(); });
}

DiagonalResult evaluate_diagonal(const Diagonal& d, const identify::LaserRuns& runs, double laser_uncertainty_mm,
                                 const Tolerances* tolerances) {
  DiagonalResult r;
  r.diagonal = d;
  r.iso = identify::evaluate_iso230_2(runs);
  const identify::Iso230_2& e = r.iso;
  // An axis run's limits are [axis]'s, a diagonal's [diagonal]'s.
  const std::map<std::string, double>* limits =
      tolerances ? (d.axis_run() ? &tolerances->axis_mm : &tolerances->diagonal_mm) : nullptr;
  const int n = std::min(e.runs_up, e.runs_down);
  double s_max = 0;
  for (const identify::TargetStatistics& t : e.targets) s_max = std::max({s_max, t.s_up, t.s_down});
  const double u_mean = s_max / std::sqrt(static_cast<double>(n));
  const double two = std::sqrt(2.0);
  const auto figure = [&](const char* symbol, const char* name, double value, bool from_scatter) {
    Figure f;
    f.symbol = symbol;
    f.name = name;
    f.value_mm = value;
    f.u_repeatability_mm = from_scatter ? value / std::sqrt(2.0 * (n - 1)) : two * u_mean;
    f.u_instrument_mm = from_scatter ? 0.0 : two * laser_uncertainty_mm;
    if (limits)
      if (const auto it = limits->find(symbol); it != limits->end()) f.limit_mm = it->second;
    r.figures.push_back(f);
  };
  figure("A", "accuracy", e.accuracy, false);
  figure("E", "systematic deviation", e.systematic, false);
  figure("R", "repeatability", e.repeatability, true);
  figure("B", "reversal value", e.reversal, false);
  figure("M", "range of the mean bidirectional deviation", e.range, false);
  r.judged = limits && !limits->empty();
  return r;
}

std::vector<EvaluationRow> evaluation_rows(const std::vector<DiagonalResult>& results) {
  std::vector<EvaluationRow> rows;
  for (const DiagonalResult& r : results)
    for (const Figure& f : r.figures)  // the face is in the name
      rows.push_back(figure_row(r.diagonal.name,
                                r.diagonal.axis_run()        ? "axis run"
                                : r.diagonal.kind == "body" ? "body diagonal"
                                                            : "face diagonal",
                                f));
  return rows;
}

std::string summary_markdown(const std::vector<DiagonalResult>& results, const std::string& plan_dir,
                             const std::string& measurements, const std::string& tolerances,
                             double laser_uncertainty_mm) {
  std::ostringstream m;
  const bool judged = std::any_of(results.begin(), results.end(), [](const DiagonalResult& r) { return r.judged; });
  const bool all = std::all_of(results.begin(), results.end(), [](const DiagonalResult& r) { return r.passes(); });
  const auto runs = std::count_if(results.begin(), results.end(), [](const DiagonalResult& r) { return r.diagonal.axis_run(); });
  const std::size_t diagonals = results.size() - static_cast<std::size_t>(runs);
  m << "# Acceptance: "
    << (runs == 0          ? "ISO 230-6 diagonal displacement tests"
        : diagonals == 0 ? "ISO 230-2 linear positioning tests"
                         : "ISO 230-6 diagonal displacement tests and ISO 230-2 linear positioning tests")
    << "\n\n"
    << "Plan `" << plan_dir << "`, measurements `" << measurements << "`, tolerances "
    << (tolerances.empty() ? std::string("none (figures only, no verdict)") : "`" + tolerances + "`") << ".\n\n";
  if (judged) m << "**" << (all ? "PASS" : "FAIL") << "**: " << diagonals << " diagonals, " << runs << " axis runs.\n\n";
  for (const DiagonalResult& r : results) {
    m << "## " << r.diagonal.name << " (" << r.diagonal.kind << ", " << fixed_text(r.diagonal.length_mm(), 3)
      << " mm, " << r.iso.targets.size() << " targets, " << r.iso.runs_up << " runs + and " << r.iso.runs_down
      << " -)" << (r.judged ? (r.passes() ? ": PASS" : ": FAIL") : "") << "\n\n"
      << figures_markdown(r.figures, "laser") << "\n";
  }
  m << "## Uncertainty\n\n"
    << "Standard uncertainties (k = 1), U = 2 u_c (k = 2). Repeatability part from the runs: a target's mean "
       "deviation has u_mean = s_max / sqrt(n) (s_max the largest unidirectional standard deviation of any target, n "
       "runs per direction); A, E, B, M are differences of two means, sqrt(2) u_mean; R is 4 s from n runs, "
       "u(R) = R / sqrt(2 (n - 1)). Instrument part: the laser's "
    << number_text(laser_uncertainty_mm * 1e3)
    << " um per reading (--laser-uncertainty-um), sqrt(2) times that for A, E, B, M, none for R (its scatter is "
       "in the runs'). **Not evaluated**: the thermal term (ISO/TR 16907 8.3: the machine's thermal state, ISO "
       "230-3; ISO/TR 16015's thermal influence on the length measurement), the beam's misalignment (cosine "
       "error) and the dead path. A verdict is the figure against its limit; \"within U\" marks one that the "
       "uncertainty could turn.\n";
  return m.str();
}

}  // namespace vc::acceptance
