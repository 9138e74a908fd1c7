#include "vc/acceptance/rtest_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "simulated_instrument.hpp"
#include "vc/machine/forward.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::acceptance {

bool RTestResult::passes() const {
  return std::all_of(figures.begin(), figures.end(), [](const Figure& f) { return f.passes(); });
}

std::string simulate_rtest_csv(const Plan& plan, const LaserSimulation& sim, const std::vector<std::string>& comments) {
  const machine::Model& truth = *sim.truth;
  const double L = plan.settings.tool_length_mm;
  const machine::Joints rest = joints_at(truth, machine::Joints::Zero(truth.joint_count()), plan.rtest.sphere_joints_mm);
  // The set-up: the sphere where the true machine puts the nest with the rest pose commanded.
  const Eigen::Vector3d sphere =
      machine::tool_pose(truth, machine::Machine::Real, commanded_joints(sim, rest, L, "rtest"), L).tip_mm;
  std::mt19937_64 rng(sim.seed * 1000003u + 2000u);
  std::ostringstream out;
  for (const std::string& c : comments) out << "# " << c << "\n";
  for (char c : plan.coordinates) out << c << ",";
  out << "dx[um],dy[um],dz[um]\n";
  for (const RTestSequence& s : plan.rtest.sequences)
    for (const machine::Joints& q : s.poses) {
      const Eigen::Vector3d r =
          identify::rtest_reading(truth, commanded_joints(sim, q, L, s.name), L, sphere, sim.noise_mm, &rng);
      for (int j = 0; j < q.size(); ++j) out << fixed_text(q[j], 6) << ",";
      out << fixed_text(r.x() * 1e3, 6) << "," << fixed_text(r.y() * 1e3, 6) << "," << fixed_text(r.z() * 1e3, 6) << "\n";
    }
  return out.str();
}

std::vector<identify::RTestReading> read_planned_rtest(const std::string& path, const Plan& plan,
                                                      const machine::Model& model) {
  std::vector<identify::RTestReading> readings = identify::read_rtest_readings(path, model);
  std::size_t k = 0;
  for (const RTestSequence& s : plan.rtest.sequences)
    for (std::size_t i = 0; i < s.poses.size(); ++i, ++k) {
      if (k == readings.size())
        throw LoadError({path}, std::to_string(readings.size()) + " readings; the plan has " +
                                    std::to_string(k + s.poses.size() - i) + " poses or more (" + s.name + ", pose " +
                                    std::to_string(i + 1) + " has none)");
      if ((readings[k].joints - s.poses[i]).cwiseAbs().maxCoeff() > 1e-3)
        throw LoadError({path, readings[k].line}, "not the plan's pose " + std::to_string(k + 1) + " (" + s.name +
                                                      "): the readings come in the program's order, at its joints");
    }
  if (k != readings.size())
    throw LoadError({path, readings[k].line}, "more readings than the plan's " + std::to_string(k) + " poses");
  return readings;
}

std::vector<RTestResult> evaluate_rtest(const Plan& plan, const machine::Model& model,
                                        const std::vector<identify::RTestReading>& readings,
                                        double sensor_uncertainty_mm, const Tolerances* tolerances) {
  const double L = plan.settings.tool_length_mm;
  std::vector<RTestResult> out;
  std::size_t k = 0;
  for (const RTestSequence& s : plan.rtest.sequences) {
    // The sphere centre's deviation in the part frame at each pose of the sequence.
    std::vector<Eigen::Vector3d> d;
    for (std::size_t i = 0; i < s.poses.size(); ++i, ++k) {
      const Eigen::Isometry3d nest = machine::part_T_tool(model, machine::Machine::Ideal, readings[k].joints, L);
      d.push_back(nest * readings[k].deviation_mm - plan.rtest.sphere_mm);
    }
    Eigen::Vector3d lo = d.front(), hi = d.front(), mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& v : d) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v), mean += v / static_cast<double>(d.size());
    double largest = 0;
    for (const Eigen::Vector3d& v : d) largest = std::max(largest, (v - mean).norm());
    RTestResult r;
    r.name = s.name;
    const auto figure = [&](const char* symbol, const char* name, double value) {
      Figure f;
      f.symbol = symbol;
      f.name = name;
      f.value_mm = value;
      f.u_instrument_mm = std::sqrt(2.0) * sensor_uncertainty_mm;
      if (tolerances)
        if (const auto it = tolerances->rtest_mm.find(symbol); it != tolerances->rtest_mm.end()) f.limit_mm = it->second;
      r.figures.push_back(f);
    };
    figure("X", "range of the sphere centre's x deviation", hi.x() - lo.x());
    figure("Y", "range of the sphere centre's y deviation", hi.y() - lo.y());
    figure("Z", "range of the sphere centre's z deviation", hi.z() - lo.z());
    figure("D", "largest distance of the sphere centre from its mean", largest);
    r.judged = tolerances && !tolerances->rtest_mm.empty();
    out.push_back(r);
  }
  return out;
}

std::vector<EvaluationRow> evaluation_rows(const std::vector<RTestResult>& results) {
  std::vector<EvaluationRow> rows;
  for (const RTestResult& r : results)
    for (const Figure& f : r.figures) rows.push_back(figure_row(r.name, "R-test", f));
  return rows;
}

std::string rtest_markdown(const std::vector<RTestResult>& results, double sensor_uncertainty_mm) {
  std::ostringstream m;
  const bool judged = !results.empty() && results.front().judged;
  const bool all = std::all_of(results.begin(), results.end(), [](const RTestResult& r) { return r.passes(); });
  m << "# Acceptance: ISO 10791-6 R-test\n\n";
  if (judged) m << "**" << (all ? "PASS" : "FAIL") << "**: " << results.size() << " sequences.\n\n";
  for (const RTestResult& r : results)
    m << "## " << r.name << (r.judged ? (r.passes() ? ": PASS" : ": FAIL") : "") << "\n\n"
      << figures_markdown(r.figures, "sensors") << "\n";
  m << "## Uncertainty of the R-test\n\n"
    << "Standard uncertainties (k = 1), U = 2 u_c (k = 2). Instrument part: the sensors' "
    << number_text(sensor_uncertainty_mm * 1e3)
    << " um per reading (--sensor-uncertainty-um), sqrt(2) times that for each range and for D. **Not evaluated**: "
       "the repeatability (one reading per pose), the thermal term, the sphere's form error and the nest's "
       "calibration.\n";
  return m.str();
}

}  // namespace vc::acceptance
