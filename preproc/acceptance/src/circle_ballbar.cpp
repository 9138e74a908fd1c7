#include "vc/acceptance/circle_ballbar.hpp"

#include <cmath>
#include <sstream>

#include "simulated_instrument.hpp"
#include "vc/machine/forward.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::acceptance {
namespace {

constexpr double kDeg = M_PI / 180;

// Degrees after the nearest axis reversal passed in the run's direction (reversals every 90 deg).
double after_reversal_deg(double angle_deg, bool ccw) {
  const double since = std::fmod(ccw ? angle_deg : 360 - angle_deg, 90.0);
  return since < 0 ? since + 90 : since;
}

}  // namespace

identify::CircularTest simulate_circle(const Plan& plan, const Circle& c, const LaserSimulation& sim, int circle_index) {
  const machine::Model& truth = *sim.truth;
  const double L = plan.settings.tool_length_mm;
  const auto ball = [&](const Eigen::Vector3d& xyz) {
    const machine::Joints q = commanded_joints(sim, joints_at(truth, plan.rest, xyz), L, c.name);
    return machine::tool_pose(truth, machine::Machine::Real, q, L).tip_mm;
  };
  const Eigen::Vector3d pivot = ball(c.centre_mm);
  Gauss noise(sim.seed * 1000003u + 1000u + static_cast<std::uint64_t>(circle_index));
  identify::CircularTest test;
  test.plane = c.plane;
  test.radius_mm = c.radius_mm;
  for (const bool ccw : {true, false}) {
    identify::CircleRun run;
    run.ccw = ccw;
    for (int k = 0; k < kBallbarPointsPerTurn; ++k) {
      const double deg = 360.0 * k / kBallbarPointsPerTurn;
      double reading = (ball(c.at(deg * kDeg)) - pivot).norm() - c.radius_mm;
      if (after_reversal_deg(deg, ccw) < 3) reading += sim.reversal_mm;
      if (sim.noise_mm > 0) reading += sim.noise_mm * noise();
      run.points.push_back({deg * kDeg, reading});
    }
    test.runs.push_back(run);
  }
  return test;
}

std::string ballbar_csv(const Plan& plan, const Circle& c, const machine::Model& model, const identify::CircularTest& test,
                        const std::vector<std::string>& comments) {
  std::ostringstream out;
  for (const std::string& line : comments) out << "# " << line << "\n";
  out << "# plane: " << c.plane << "\n# radius_mm: " << number_text(c.radius_mm)
      << "\n# tool_length_mm: " << number_text(plan.settings.tool_length_mm) << "\n# centre: ";
  const machine::Joints q = joints_at(model, plan.rest, c.centre_mm);
  for (int k = 0; k < q.size(); ++k)
    out << (k ? ", " : "") << plan.coordinates[static_cast<std::size_t>(k)] << "=" << number_text(q[k]);
  out << "\nangle[deg],direction,deviation[um]\n";
  for (const identify::CircleRun& run : test.runs)
    for (const auto& [angle, deviation] : run.points)
      out << fixed_text(angle / kDeg, 3) << "," << (run.ccw ? "ccw" : "cw") << "," << fixed_text(deviation * 1e3, 6)
          << "\n";
  return out.str();
}

}  // namespace vc::acceptance
