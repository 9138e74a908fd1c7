// volkins' enable ramp (kins/src/gain_ramp.hpp) against what the joints need: from rest to
// rest in ramp-time, the gain's rate within 2 / T and its change of rate within 4 / T^2 at
// every period, enable switched at random moments (during ramps too: where a ramp of a linear
// phase reverses at once), the gain within 0..1 and exactly 0 or 1 at rest.
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
    EXPECT_EQ(ramp.rate, 0.0);
    // Whole periods: within a few of T.
    EXPECT_NEAR(periods * kPeriod, ramp_time, 3 * kPeriod) << "ramp-time " << ramp_time;
    ramp.step(1.0, kPeriod, ramp_time);
    EXPECT_EQ(ramp.gain, 1.0);  // it stays
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
    std::printf("ramp-time %.1f s: %d reversals during a ramp; largest rate %.4f /s (limit %.4f), largest change "
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

}  // namespace
}  // namespace vc::kins
