// What volkins.update moves smoothly: the compensation's enable ramp (the gain follows
// volkins.enable, 0 or 1) and the tool length the correction is computed for (it follows
// LinuxCNC's tool length offset after a G43). The joints move by gain x correction, and by the
// correction's change with L, on top of the program: both follow their targets with a bounded
// rate and a bounded change of rate, so the joints never see a step of velocity: not at the
// ends, and not when the target changes while the value is still on its way (a ramp that
// reverses or restarts at rest, as a smoothstep of a linear phase does, steps the joints'
// velocity by up to 2 x rate).
//
// A move of `span` from rest to rest takes `time` T: rate at most 2 span / T, change of rate at
// most 4 span / T^2 (half accelerating, half braking). Towards the target the rate is always
// one from which braking at the limit stops on it (the braking distance of whole periods), and
// never more than what is left in one period: it lands on the target exactly, within one
// change of rate, and is at rest a period later. Where a new target lies closer than braking
// from the current rate allows, the value passes it within the limits and comes back.
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

// A value and its rate (per second) following a target.
struct Follower {
  double value = 0.0;
  double rate = 0.0;

  // One period of `period_s` towards `target`, with the limits of a move of `span` in `time_s`
  // (time_s <= 0 or span <= 0: at once).
  void step(double target, double span, double period_s, double time_s) noexcept {
    if (!(time_s > 0.0) || !(period_s > 0.0) || !(span > 0.0)) {
      value = target;
      rate = 0.0;
      return;
    }
    const double most_rate = 2.0 * span / time_s, most_change = 4.0 * span / (time_s * time_s) * period_s;
    const double left = target - value;
    const double wanted = std::copysign(
        std::min({most_rate, braking_rate(std::abs(left), most_change, period_s), std::abs(left) / period_s}), left);
    rate += std::clamp(wanted - rate, -most_change, most_change);
    const double next = value + rate * period_s;
    // On the target (within rounding): exactly there, at the rate this period moved; the next
    // period, within one change of rate, brings it to rest.
    if (std::abs(target - next) <= 1e-12 * std::max(1.0, std::abs(target))) {
      rate = (target - value) / period_s;
      value = target;
      return;
    }
    value = next;  // (past the target only where it moved closer than braking allows)
  }
};

// The enable ramp: the gain (0..1) follows 0 or 1, a whole ramp (span 1) in ramp-time. The
// target is always an end and the rate always one that brakes within it, so braking towards
// one end stops within it when the target turns to the other: the gain stays within 0..1.
struct GainRamp {
  double gain = 0.0;  // 0..1
  double rate = 0.0;  // per second

  // One servo period of `period_s` towards `target` (0 or 1) over `ramp_time_s` (<= 0: at once).
  void step(double target, double period_s, double ramp_time_s) noexcept {
    Follower f{gain, rate};
    f.step(target, 1.0, period_s, ramp_time_s);
    gain = std::clamp(f.value, 0.0, 1.0);  // (rounding only)
    rate = f.rate;
  }
};

// The tool length L the correction is computed for, following LinuxCNC's tool length offset: a
// change of L takes the slew time. A new offset while L is still moving keeps the larger of
// the two moves' spans for the limits (braking from the current rate needs them; a small
// second change would otherwise stop a large first one abruptly).
struct ToolLengthSlew {
  Follower length;      // mm and mm/s
  double target = 0.0;  // mm: the offset it follows
  double span = 0.0;    // mm: the move whose limits apply

  void reset(double offset_mm) noexcept {
    length = {offset_mm, 0.0};
    target = offset_mm;
    span = 0.0;
  }
  void step(double offset_mm, double period_s, double slew_time_s) noexcept {
    if (offset_mm != target) {
      span = std::max(std::abs(offset_mm - length.value), length.rate != 0.0 ? span : 0.0);
      target = offset_mm;
    }
    length.step(target, span, period_s, slew_time_s);
  }
};

}  // namespace vc::kins
