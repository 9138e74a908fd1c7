#include "vc/acceptance/diagonal_laser.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "simulated_instrument.hpp"
#include "vc/machine/forward.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::acceptance {

std::vector<identify::Reading> simulate_diagonal(const Plan& plan, const Diagonal& d, const LaserSimulation& sim,
                                                 int diagonal_index) {
  const machine::Model& truth = *sim.truth;
  const double L = plan.settings.tool_length_mm;
  const auto nominal = [&](double distance) { return joints_at(truth, plan.rest, d.at(distance)); };
  const auto commanded = [&](const machine::Joints& q) { return commanded_joints(sim, q, L, d.name); };
  const auto tip = [&](machine::Machine which, const machine::Joints& q) {
    return machine::tool_pose(truth, which, q, L).tip_mm;
  };
  const Eigen::Vector3d u =
      (tip(machine::Machine::Ideal, nominal(d.targets_mm.back())) - tip(machine::Machine::Ideal, nominal(0))).normalized();
  const Eigen::Vector3d zero = tip(machine::Machine::Real, commanded(nominal(0)));
  std::vector<double> truth_mm;  // at each target: the displacement along the line minus the distance
  for (double t : d.targets_mm) truth_mm.push_back((tip(machine::Machine::Real, commanded(nominal(t))) - zero).dot(u) - t);

  Gauss noise(sim.seed * 1000003u + static_cast<std::uint64_t>(diagonal_index));
  std::vector<identify::Reading> out;
  const auto read = [&](int run, identify::Direction way, std::size_t i) {
    identify::Reading r;
    r.run = run;
    r.direction = way;
    r.target = d.targets_mm[i];
    const double half = (way == identify::Direction::Up ? 0.5 : -0.5) * sim.reversal_mm;
    r.deviation = truth_mm[i] + half + (sim.noise_mm > 0 ? sim.noise_mm * noise() : 0.0);
    out.push_back(r);
  };
  for (int run = 1; run <= plan.settings.runs; ++run) {
    for (std::size_t i = 0; i < d.targets_mm.size(); ++i) read(run, identify::Direction::Up, i);
    for (std::size_t i = d.targets_mm.size(); i-- > 0;) read(run, identify::Direction::Down, i);
  }
  return out;
}

std::string laser_csv(const Diagonal& d, const std::vector<identify::Reading>& readings,
                      const std::vector<std::string>& comments) {
  std::ostringstream out;
  for (const std::string& c : comments) out << "# " << c << "\n";
  out << "# diagonal: " << d.name << "\n"
      << "target[mm],run,direction,deviation[um]\n";
  for (const identify::Reading& r : readings)
    out << fixed_text(r.target, 3) << "," << r.run << "," << (r.direction == identify::Direction::Up ? "+" : "-") << ","
        << fixed_text(r.deviation * 1e3, 9) << "\n";
  return out.str();
}

}  // namespace vc::acceptance
