#include "vc/acceptance/figure.hpp"

#include <cmath>
#include <sstream>

#include "vc/tables/number_text.hpp"

namespace vc::acceptance {

double Figure::expanded_mm() const {
  return 2 * std::sqrt(u_repeatability_mm * u_repeatability_mm + u_instrument_mm * u_instrument_mm);
}

EvaluationRow figure_row(const std::string& test, const std::string& kind, const Figure& f) {
  EvaluationRow row;
  row.test = test;
  row.kind = kind;
  row.figure = f.symbol;
  row.name = f.name;
  row.value = f.value_mm * 1e3;
  row.u_repeatability = f.u_repeatability_mm * 1e3;
  row.u_instrument = f.u_instrument_mm * 1e3;
  row.expanded = f.expanded_mm() * 1e3;
  if (f.limit_mm) {
    row.limit = *f.limit_mm * 1e3;
    row.verdict = f.passes() ? "PASS" : "FAIL";
  }
  row.unit = "um";
  return row;
}

std::string figures_markdown(const std::vector<Figure>& figures, const std::string& instrument) {
  const auto um = [](double mm) { return fixed_text(mm * 1e3, 3); };
  std::ostringstream m;
  m << "| figure | value [um] | u repeatability [um] | u " << instrument
    << " [um] | U (k = 2) [um] | limit [um] | verdict |\n|---|---:|---:|---:|---:|---:|---|\n";
  for (const Figure& f : figures) {
    std::string verdict;
    if (f.limit_mm) {
      verdict = f.passes() ? "PASS" : "FAIL";
      if (std::abs(*f.limit_mm - f.value_mm) < f.expanded_mm()) verdict += " (within U of the limit)";
    }
    m << "| " << f.symbol << " " << f.name << " | " << um(f.value_mm) << " | " << um(f.u_repeatability_mm) << " | "
      << um(f.u_instrument_mm) << " | " << um(f.expanded_mm()) << " | " << (f.limit_mm ? um(*f.limit_mm) : "-") << " | "
      << verdict << " |\n";
  }
  return m.str();
}

}  // namespace vc::acceptance
