// Points spread over a machine's travel, the same on every run (a fixed-seed generator), for
// the bounds that are sampled once at load (correction_bounds.cpp, one_step_correction.cpp).
#pragma once

#include <cstdint>

#include "vc/machine/model.hpp"

namespace vc::predistort {

class TravelSamples {
 public:
  explicit TravelSamples(const machine::Model& model) : model_(model) {}

  // The next point: each joint uniform over its travel.
  machine::Joints next() {
    machine::Joints q(model_.joint_count());
    for (int j = 0; j < model_.joint_count(); ++j) {
      const machine::Axis& axis = model_.axes[static_cast<std::size_t>(j)];
      q[j] = axis.travel_min + uniform() * (axis.travel_max - axis.travel_min);
    }
    return q;
  }

 private:
  double uniform() {  // [0, 1), 53 bits of a 64-bit LCG
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state_ >> 11) / 9007199254740992.0;
  }

  const machine::Model& model_;
  std::uint64_t state_ = 0x9E3779B97F4A7C15ull;
};

}  // namespace vc::predistort
