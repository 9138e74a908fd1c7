// The compensation's enable ramp (volkins.update): the gain follows volkins.enable (0 or 1)
// with a bounded rate and a bounded change of rate, so that the joints, which move by gain x
// correction on top of the program, never see a step of velocity: not at the ends, and not when
// enable switches while the gain is still on its way (a ramp that reverses at once, as a
// smoothstep of a linear phase does, steps the joints' velocity by 2 x rate x correction).
//
// Rate at most 2 / T, change of rate at most 4 / T^2 (T: ramp-time): from rest to rest 0 -> 1
// takes T (half accelerating, half braking). The rate is always one from which braking at the
// limit stops on the target (the braking distance of whole periods), and never more than what
// is left in one period: it lands on 0 or 1 exactly and never passes them (braking towards one
// end stops within it when the target turns to the other).
// Servo thread: no allocation, bounded arithmetic.
#pragma once

#include <algorithm>
#include <cmath>

namespace vc::kins {

// The largest rate from which braking by `change` (rate) a period, down to rest, covers at
// most `left` (>= 0): from (m + f) change, m whole and 0 <= f < 1, the periods cover
// ((m + 1) f + m (m + 1) / 2) change x period.
inline double braking_rate(double left, double change, double period_s) noexcept {
  const double steps = left / (change * period_s);
  const double m = std::floor((std::sqrt(1.0 + 8.0 * steps) - 1.0) / 2.0);
  const double f = (steps - m * (m + 1.0) / 2.0) / (m + 1.0);
  return (m + std::clamp(f, 0.0, 1.0)) * change;
}

struct GainRamp {
  double gain = 0.0;  // 0..1
  double rate = 0.0;  // per second

  // One servo period of `period_s` towards `target` (0 or 1) over `ramp_time_s` (<= 0: at once).
  void step(double target, double period_s, double ramp_time_s) noexcept {
    if (!(ramp_time_s > 0.0) || !(period_s > 0.0)) {
      gain = target;
      rate = 0.0;
      return;
    }
    const double most_rate = 2.0 / ramp_time_s, most_change = 4.0 / (ramp_time_s * ramp_time_s) * period_s;
    const double left = target - gain;
    const double wanted =
        std::copysign(std::min({most_rate, braking_rate(std::abs(left), most_change, period_s), std::abs(left) / period_s}),
                      left);
    rate += std::clamp(wanted - rate, -most_change, most_change);
    const double next = gain + rate * period_s;
    // On the target (within rounding; the last period's rate is below one change) or past it
    // by rounding: there, at rest.
    if (left != 0.0 && ((target - next) * left <= 0.0 || std::abs(target - next) <= 1e-12)) {
      gain = target;
      rate = 0.0;
      return;
    }
    gain = std::clamp(next, 0.0, 1.0);  // (braking towards an end stops within it: rounding only)
  }
};

}  // namespace vc::kins
