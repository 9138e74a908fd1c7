// A diagonal evaluated as ISO 230-6 asks: the ISO 230-2 figures along the line (identify's
// evaluate_iso230_2: A accuracy, E systematic deviation, R repeatability, B reversal value, M range
// of the mean bidirectional deviation), each with an uncertainty statement and, given limits,
// judged.
//
// The uncertainty (standard uncertainties, k = 1; U = 2 u_c, k = 2), simple and stated:
// - repeatability part, from the runs: the standard uncertainty of a target's mean deviation,
//   u_mean = s_max / sqrt(n) (s_max the largest unidirectional standard deviation s_i of any
//   target, n the fewer of the runs + and -); E, M, A and B are differences of two such means:
//   u = sqrt(2) u_mean; R = 4 s from n runs: u(R) = R / sqrt(2 (n - 1)) (a sample deviation's);
// - instrument part: the laser's standard uncertainty of one reading u_L (--laser-uncertainty-um),
//   E, M, A, B differences of two readings: sqrt(2) u_L; R: 0 (the laser's scatter is in the runs');
// - not evaluated: the thermal term (ISO/TR 16907 8.3: the machine's thermal state, ISO 230-3;
//   ISO/TR 16015's thermal influence on the length measurement), the beam's alignment (cosine
//   error), the dead path.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vc/acceptance/diagonals.hpp"
#include "vc/acceptance/evaluation_file.hpp"
#include "vc/acceptance/figure.hpp"
#include "vc/acceptance/tolerances.hpp"
#include "vc/identify/iso230_2.hpp"

namespace vc::acceptance {

// The typical laser's standard uncertainty of one reading (--laser-uncertainty-um's default):
// a laser interferometer with its air and material compensation over about 1 m.
inline constexpr double kTypicalLaserUncertaintyUm = 0.5;

struct DiagonalResult {
  Diagonal diagonal;
  identify::Iso230_2 iso;
  std::vector<Figure> figures;  // A, E, R, B, M
  bool judged = false;          // limits given
  bool passes() const;
};

DiagonalResult evaluate_diagonal(const Diagonal& d, const identify::LaserRuns& runs, double laser_uncertainty_mm,
                                 const Tolerances* tolerances);

// One row per diagonal and figure (A, E, R, B, M), in um, kind "body diagonal" or "face diagonal";
// a figure with a limit has its verdict.
std::vector<EvaluationRow> evaluation_rows(const std::vector<DiagonalResult>& results);

// The summary: per diagonal the figures with their uncertainty and verdict, the overall verdict,
// what the uncertainty holds and leaves out.
std::string summary_markdown(const std::vector<DiagonalResult>& results, const std::string& plan_dir,
                             const std::string& measurements, const std::string& tolerances,
                             double laser_uncertainty_mm);

}  // namespace vc::acceptance
