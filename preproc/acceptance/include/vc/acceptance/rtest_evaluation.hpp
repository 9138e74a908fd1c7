// The R-test simulated on a true machine and evaluated as ISO 10791-6 reports it: per sequence
// the sphere centre's deviation in the workpiece (part) frame at each pose (the reading turned
// into the part frame by the ideal machine at the commanded pose, from the nest's centre, minus
// the sphere's planned place), its range along x, y and z (X, Y, Z) and its largest distance from
// the sequence's mean (D), with the sensors' uncertainty and, given limits ([rtest] X_um, Y_um,
// Z_um, D_um), judged.
//
// Uncertainty (k = 1; U = 2 u_c): instrument part, the sensors' standard uncertainty of a reading
// u_s (--sensor-uncertainty-um): a range is the difference of two readings, sqrt(2) u_s; D's taken
// the same. Not evaluated: the repeatability (one reading per pose), the thermal term, the
// sphere's form error and the nest's calibration.
#pragma once

#include <string>
#include <vector>

#include "vc/acceptance/diagonal_laser.hpp"
#include "vc/acceptance/figure.hpp"
#include "vc/acceptance/tolerances.hpp"
#include "vc/identify/rtest.hpp"

namespace vc::acceptance {

// A displacement sensor's standard uncertainty of one reading (--sensor-uncertainty-um's default).
inline constexpr double kTypicalSensorUncertaintyUm = 0.3;

// The readings file of the planned poses in order (identify rtest's layout): what the sensors read
// on `sim.truth`, compensated or not, the sphere set where the true machine puts the nest at rest.
std::string simulate_rtest_csv(const Plan& plan, const LaserSimulation& sim, const std::vector<std::string>& comments);

// The file read and checked against the plan (a row per planned pose, in order, each at its
// commanded joints to 1e-3 mm / deg). Throws vc::LoadError at file:line.
std::vector<identify::RTestReading> read_planned_rtest(const std::string& path, const Plan& plan,
                                                      const machine::Model& model);

struct RTestResult {
  std::string name;               // the sequence's
  std::vector<Figure> figures;    // X, Y, Z, D
  bool judged = false;
  bool passes() const;
};

std::vector<RTestResult> evaluate_rtest(const Plan& plan, const machine::Model& model,
                                        const std::vector<identify::RTestReading>& readings,
                                        double sensor_uncertainty_mm, const Tolerances* tolerances);

std::vector<EvaluationRow> evaluation_rows(const std::vector<RTestResult>& results);
std::string rtest_markdown(const std::vector<RTestResult>& results, double sensor_uncertainty_mm);

}  // namespace vc::acceptance
