#include "vc/acceptance/circle_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "vc/tables/number_text.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::acceptance {

bool CircleResult::passes() const {
  return std::all_of(figures.begin(), figures.end(), [](const Figure& f) { return f.passes(); });
}

CircleResult evaluate_circle(const Circle& c, const identify::CircularTest& test, double ballbar_uncertainty_mm,
                             const Tolerances* tolerances) {
  CircleResult r;
  r.circle = c;
  r.iso = identify::evaluate_circular_test(test);
  double radial = 0;
  for (const identify::CircleFit& f : r.iso.fits) radial = std::max(radial, f.radial_deviation_mm);
  const auto figure = [&](const char* symbol, const char* name, double value, double readings) {
    Figure f;
    f.symbol = symbol;
    f.name = name;
    f.value_mm = value;
    f.u_instrument_mm = std::sqrt(readings) * ballbar_uncertainty_mm;
    if (tolerances)
      if (const auto it = tolerances->circle_mm.find(symbol); it != tolerances->circle_mm.end()) f.limit_mm = it->second;
    r.figures.push_back(f);
  };
  figure("G(b)", "bidirectional circular deviation", r.iso.circular_deviation_mm, 2);
  figure("H", "circular hysteresis", r.iso.hysteresis_mm, 2);
  figure("F", "radial deviation", radial, 1);
  r.judged = tolerances && !tolerances->circle_mm.empty();
  return r;
}

identify::CircularTest read_circle_run(const std::string& path, const Circle& c) {
  identify::CircularTest t = identify::read_circular_test(path);
  const auto said = [&](const std::string& key) {
    for (const auto& [k, v] : t.metadata)
      if (k == key) return true;
    return false;
  };
  if (!said("plane") || t.plane != c.plane)
    throw LoadError({path}, c.name + " runs in " + c.plane + ": the file needs '# plane: " + c.plane + "'");
  if (!said("radius_mm") || std::abs(t.radius_mm - c.radius_mm) > 1e-6)
    throw LoadError({path}, c.name + "'s ballbar is " + number_text(c.radius_mm) + " mm: the file needs '# radius_mm: " +
                                number_text(c.radius_mm) + "'");
  bool ccw = false, cw = false;
  for (const identify::CircleRun& run : t.runs) (run.ccw ? ccw : cw) = true;
  if (!ccw || !cw) throw LoadError({path}, c.name + ": ISO 230-4 asks for both directions, ccw and cw; the file has one");
  return t;
}

std::vector<EvaluationRow> evaluation_rows(const std::vector<CircleResult>& results) {
  std::vector<EvaluationRow> rows;
  for (const CircleResult& r : results)
    for (const Figure& f : r.figures) rows.push_back(figure_row(r.circle.name, "circle", f));
  return rows;
}

std::string circles_markdown(const std::vector<CircleResult>& results, double ballbar_uncertainty_mm) {
  std::ostringstream m;
  const bool judged = !results.empty() && results.front().judged;
  const bool all = std::all_of(results.begin(), results.end(), [](const CircleResult& r) { return r.passes(); });
  m << "# Acceptance: ISO 230-4 circular tests\n\n";
  if (judged) m << "**" << (all ? "PASS" : "FAIL") << "**: " << results.size() << " circles.\n\n";
  for (const CircleResult& r : results) {
    m << "## " << r.circle.name << " (" << r.circle.plane << ", radius " << number_text(r.circle.radius_mm)
      << " mm, centre offset";
    for (const identify::CircleFit& f : r.iso.fits)
      m << " " << (f.ccw ? "ccw" : "cw") << " " << fixed_text(f.centre_first_mm * 1e3, 3) << ", "
        << fixed_text(f.centre_second_mm * 1e3, 3) << " um";
    m << ")" << (r.judged ? (r.passes() ? ": PASS" : ": FAIL") : "") << "\n\n"
      << figures_markdown(r.figures, "ballbar") << "\n";
  }
  m << "## Uncertainty of the circles\n\n"
    << "Standard uncertainties (k = 1), U = 2 u_c (k = 2). Instrument part: the ballbar's "
    << number_text(ballbar_uncertainty_mm * 1e3)
    << " um per reading (--ballbar-uncertainty-um), sqrt(2) times that for G(b) and H (differences of two readings), "
       "once for F (one reading against the bar's calibrated length). **Not evaluated**: the repeatability (one run "
       "per direction: repeat the test for it), the thermal term, the set-up's centring in F.\n";
  return m.str();
}

}  // namespace vc::acceptance
