// A circular test evaluated as ISO 230-4 asks (identify's evaluate_circular_test): the
// bidirectional circular deviation G(b), the circular hysteresis H and the radial deviation F
// (the larger of the two directions'), each with an uncertainty statement and, given limits,
// judged.
//
// The uncertainty (standard uncertainties, k = 1; U = 2 u_c, k = 2), simple and stated:
// - instrument part: the ballbar's standard uncertainty of one reading u_b
//   (--ballbar-uncertainty-um); G(b) and H are differences of two readings: sqrt(2) u_b; F one
//   reading against the bar's calibrated length: u_b;
// - repeatability part: not evaluated (one run per direction: repeat the test for it);
// - not evaluated: the thermal term, the set-up's centring (taken out by the least-squares
//   centre in G, not in F).
#pragma once

#include <string>
#include <vector>

#include "vc/acceptance/circles.hpp"
#include "vc/acceptance/figure.hpp"
#include "vc/acceptance/tolerances.hpp"
#include "vc/identify/iso230_4.hpp"

namespace vc::acceptance {

// A ballbar's standard uncertainty of one reading (--ballbar-uncertainty-um's default): a
// calibrated ballbar's stated accuracy of about +-1.25 um, taken as a rectangular distribution.
inline constexpr double kTypicalBallbarUncertaintyUm = 0.7;

struct CircleResult {
  Circle circle;
  identify::CircularEvaluation iso;
  std::vector<Figure> figures;  // G(b), H, F
  bool judged = false;          // limits given
  bool passes() const;
};

CircleResult evaluate_circle(const Circle& c, const identify::CircularTest& test, double ballbar_uncertainty_mm,
                             const Tolerances* tolerances);

// The run file read and checked against the plan: its plane and radius (the `# plane:` and
// `# radius_mm:` lines) the circle's, both directions present. Throws vc::LoadError at file:line.
identify::CircularTest read_circle_run(const std::string& path, const Circle& c);

// One row per circle and figure, kind "circle" (the plane is in the name).
std::vector<EvaluationRow> evaluation_rows(const std::vector<CircleResult>& results);

// The circles' part of the summary.
std::string circles_markdown(const std::vector<CircleResult>& results, double ballbar_uncertainty_mm);

}  // namespace vc::acceptance
