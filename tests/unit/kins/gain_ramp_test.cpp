// volkins' enable ramp and tool-length slew (kins/src/gain_ramp.hpp) against what the joints
// need: from rest to rest in ramp-time, the gain's rate within 2 / T and its change of rate
// within 4 / T^2 at every period, enable switched at random moments (during ramps too: where a
// ramp of a linear phase reverses at once), the gain within 0..1 and exactly 0 or 1 at rest.
// The same for the tool length L, whose limits scale with the change of L, with new offsets
// arriving at random moments during a slew (where a smoothstep restarted at rest).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gain_ramp.hpp"

namespace vc::kins {
namespace {

constexpr double kPeriod = 1e-3;

TEST(GainRamp, FromRestToRestInRampTime) {
  for (const double ramp_time : {0.05, 0.5, 1.0, 2.0}) {
    GainRamp ramp;
    int periods = 0;
    while (ramp.gain != 1.0 && periods < 10'000) {
      ramp.step(1.0, kPeriod, ramp_time);
      ++periods;
    }
    EXPECT_EQ(ramp.gain, 1.0);
    // Whole periods: within a few of T.
    EXPECT_NEAR(periods * kPeriod, ramp_time, 3 * kPeriod) << "ramp-time " << ramp_time;
    EXPECT_LE(ramp.rate, 4.0 / (ramp_time * ramp_time) * kPeriod * (1 + 1e-6))
        << "the last period: within one change of rate";
    ramp.step(1.0, kPeriod, ramp_time);
    EXPECT_EQ(ramp.gain, 1.0);  // it stays, at rest
    EXPECT_EQ(ramp.rate, 0.0);
  }
}

TEST(GainRamp, RateAndItsChangeStayBoundedWhenEnableSwitchesAnyTime) {
  std::mt19937_64 random(3);
  std::uniform_int_distribution<int> hold(1, 800);  // periods between switches
  for (const double ramp_time : {0.2, 1.0}) {
    GainRamp ramp;
    double target = 1.0, previous_rate = 0.0, previous_gain = 0.0;
    double largest_rate = 0.0, largest_change = 0.0;
    int reversals = 0;
    for (int k = 0, next_switch = hold(random); k < 200'000; ++k) {
      if (k == next_switch) {
        reversals += ramp.gain > 0.0 && ramp.gain < 1.0;
        target = 1.0 - target;
        next_switch += hold(random);
      }
      ramp.step(target, kPeriod, ramp_time);
      ASSERT_GE(ramp.gain, 0.0);
      ASSERT_LE(ramp.gain, 1.0);
      // The rate the joints see is the gain's difference per period.
      const double rate = (ramp.gain - previous_gain) / kPeriod;
      largest_rate = std::max(largest_rate, std::abs(rate));
      largest_change = std::max(largest_change, std::abs(rate - previous_rate) / kPeriod);
      previous_rate = rate;
      previous_gain = ramp.gain;
    }
    EXPECT_GT(reversals, 100) << "enable should switch during ramps";
    const double rate_limit = 2.0 / ramp_time, change_limit = 4.0 / (ramp_time * ramp_time);
    EXPECT_LE(largest_rate, rate_limit * (1 + 1e-9)) << "ramp-time " << ramp_time;
    EXPECT_LE(largest_change, change_limit * (1 + 1e-6)) << "ramp-time " << ramp_time;
    std::printf(
        "ramp-time %.1f s: %d reversals during a ramp; largest rate %.4f /s (limit %.4f), largest change "
        "of rate %.4f /s^2 (limit %.4f)\n",
        ramp_time, reversals, largest_rate, rate_limit, largest_change, change_limit);
  }
}

TEST(GainRamp, WithoutRampTimeTheGainFollowsAtOnce) {
  GainRamp ramp;
  ramp.step(1.0, kPeriod, 0.0);
  EXPECT_EQ(ramp.gain, 1.0);
  ramp.step(0.0, kPeriod, -1.0);
  EXPECT_EQ(ramp.gain, 0.0);
}

TEST(ToolLengthSlew, OneChangeFromRestToRestInSlewTime) {
  for (const double change : {100.0, -35.0, 0.01}) {
    ToolLengthSlew slew;
    slew.reset(80.0);
    const double to = 80.0 + change, time = 0.25;
    int periods = 0;
    double previous = slew.length.value, previous_rate = 0.0, largest_change = 0.0;
    while (slew.length.value != to && periods < 10'000) {
      slew.step(to, kPeriod, time);
      const double rate = (slew.length.value - previous) / kPeriod;
      EXPECT_LE(std::abs(rate), 2.0 * std::abs(change) / time * (1 + 1e-9));
      largest_change = std::max(largest_change, std::abs(rate - previous_rate) / kPeriod);
      EXPECT_LE((slew.length.value - 80.0) / change, 1.0 + 1e-12) << "never past the new length";
      previous = slew.length.value;
      previous_rate = rate;
      ++periods;
    }
    EXPECT_EQ(slew.length.value, to);
    EXPECT_NEAR(periods * kPeriod, time, 3 * kPeriod) << "change " << change;
    slew.step(to, kPeriod, time);
    EXPECT_EQ(slew.length.value, to);
    EXPECT_EQ(slew.length.rate, 0.0) << "at rest a period later";
    EXPECT_LE(largest_change, 4.0 * std::abs(change) / (time * time) * (1 + 1e-6)) << "change " << change;
  }
}

// Tool changes at random moments, many of them while L is still moving (a second G43 soon
// after the first, a G49, a correction of the offset): L's rate stays within 2 x span / T and
// its change of rate within 4 x span / T^2 at every period, span the larger of the moves in
// progress, and every slew ends at rest on the last offset.
TEST(ToolLengthSlew, RateAndItsChangeStayBoundedWhenTheOffsetChangesDuringASlew) {
  std::mt19937_64 random(5);
  std::uniform_int_distribution<int> hold(1, 400);              // periods between changes
  std::uniform_real_distribution<double> offset(-20.0, 150.0);  // mm
  const double time = 0.25;
  ToolLengthSlew slew;
  slew.reset(0.0);
  double previous = 0.0, previous_rate = 0.0, span = 0.0, worst_rate = 0.0, worst_change = 0.0;
  int during = 0, settled = 0;
  double target = 0.0;
  for (int k = 0, next_change = hold(random); k < 400'000; ++k) {
    if (k == next_change) {
      const double moving = slew.length.rate != 0.0;
      during += moving;
      // The limits that apply: the larger of the move just asked for and the one in progress.
      target = offset(random);
      span = std::max(std::abs(target - slew.length.value), moving ? span : 0.0);
      next_change += hold(random);
    }
    slew.step(target, kPeriod, time);
    const double rate = (slew.length.value - previous) / kPeriod;
    ASSERT_TRUE(std::isfinite(rate));
    if (span > 0.0) {
      worst_rate = std::max(worst_rate, std::abs(rate) / (2.0 * span / time));
      worst_change = std::max(worst_change, std::abs(rate - previous_rate) / kPeriod / (4.0 * span / (time * time)));
    }
    settled += slew.length.rate == 0.0 && slew.length.value == target && previous_rate != 0.0;
    previous = slew.length.value;
    previous_rate = rate;
  }
  for (int k = 0; k < 1000; ++k) slew.step(target, kPeriod, time);
  EXPECT_EQ(slew.length.value, target) << "at rest on the last offset";
  EXPECT_EQ(slew.length.rate, 0.0);
  EXPECT_GT(during, 300) << "changes should arrive during slews";
  EXPECT_GT(settled, 300);
  EXPECT_LE(worst_rate, 1.0 + 1e-9);
  EXPECT_LE(worst_change, 1.0 + 1e-6);
  std::printf(
      "%d offset changes during a slew, %d slews settled; largest rate %.4f and change of rate %.4f of "
      "their limits\n",
      during, settled, worst_rate, worst_change);
}

TEST(ToolLengthSlew, WithoutSlewTimeLFollowsAtOnce) {
  ToolLengthSlew slew;
  slew.reset(10.0);
  slew.step(50.0, kPeriod, 0.0);
  EXPECT_EQ(slew.length.value, 50.0);
  slew.step(50.0, kPeriod, 0.25);
  EXPECT_EQ(slew.length.value, 50.0);
}

}  // namespace
}  // namespace vc::kins
