// One figure of an acceptance test (A, E, ... of a diagonal, G(b), H, F of a circle): its value,
// the two parts of its standard uncertainty, its limit, and its row in the results file.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vc/acceptance/evaluation_file.hpp"

namespace vc::acceptance {

struct Figure {
  std::string symbol;  // A, E, R, B, M; G(b), H, F
  std::string name;    // accuracy, ...
  double value_mm = 0;
  double u_repeatability_mm = 0, u_instrument_mm = 0;
  std::optional<double> limit_mm;
  double expanded_mm() const;  // U = 2 sqrt(u_rep^2 + u_instr^2)
  bool passes() const { return !limit_mm || value_mm <= *limit_mm; }
};

// The figure's row of the results file (evaluation_file.hpp), in um, with its verdict if it has a limit.
EvaluationRow figure_row(const std::string& test, const std::string& kind, const Figure& f);

// The figures as a Markdown table (um): value, the two uncertainty parts (the instrument's named),
// U, limit, verdict ("within U of the limit" where the uncertainty could turn it).
std::string figures_markdown(const std::vector<Figure>& figures, const std::string& instrument);

}  // namespace vc::acceptance
