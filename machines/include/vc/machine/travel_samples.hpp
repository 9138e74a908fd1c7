// Points spread over a machine's travel, the same on every run (a fixed-seed generator), for
// the bounds that are sampled once at load (contraction_bound.cpp; the pre-distorter's
// correction_bounds.cpp).
#pragma once

#include <cstdint>

#include "vc/machine/model.hpp"

namespace vc::machine {

class TravelSamples {
 public:
  explicit TravelSamples(const Model& model) : model_(model) {}

  // The next point: each joint uniform over its travel.
  Joints next() {
    Joints q(model_.joint_count());
    for (int j = 0; j < model_.joint_count(); ++j) {
      const Axis& axis = model_.axes[static_cast<std::size_t>(j)];
      q[j] = axis.travel_min + uniform() * (axis.travel_max - axis.travel_min);
    }
    return q;
  }
  // A number uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + uniform() * (hi - lo); }

 private:
  double uniform() {  // [0, 1), 53 bits of a 64-bit LCG
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state_ >> 11) / 9007199254740992.0;
  }

  const Model& model_;
  std::uint64_t state_ = 0x9E3779B97F4A7C15ull;
};

}  // namespace vc::machine
