// What the simulated instruments (the laser along a line, the ballbar) share: the joints volkins
// commands for a planned point, and reproducible Gaussian noise.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>

#include "vc/acceptance/diagonal_laser.hpp"
#include "vc/machine/correct.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::acceptance {

// Box-Muller on mt19937_64's raw output (the <random> distributions differ between libraries).
class Gauss {
 public:
  explicit Gauss(std::uint64_t seed) : generator_(seed) {}
  double operator()() {
    const double u1 = (static_cast<double>(generator_() >> 11) + 1.0) / 9007199254740993.0;  // (0, 1]
    const double u2 = static_cast<double>(generator_() >> 11) / 9007199254740992.0;          // [0, 1)
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
  }

 private:
  std::mt19937_64 generator_;
};

// The joints at the nominal point q: q itself (compensation off) or the core's correction of the
// compensation file there for the tool length L; `test` names the test in the error.
inline machine::Joints commanded_joints(const LaserSimulation& sim, const machine::Joints& q, double L,
                                        const std::string& test) {
  if (!sim.compensation) return q;
  const machine::Correction c = machine::correct(*sim.compensation, q, L);
  if (c.status != machine::Status::Ok)
    throw std::runtime_error(test + ": the correction did not converge at " + number_text(q[0]) + ", " +
                             number_text(q[1]) + ", " + number_text(q[2]) + " mm");
  return c.joints;
}

}  // namespace vc::acceptance
