// Random poses over a machine's travel for the tests that check the correction everywhere, and
// a pose printed to the last digit for their failure messages.
#pragma once

#include <cstdlib>
#include <random>
#include <sstream>
#include <string>

#include "vc/machine/model.hpp"

namespace vc::test {

// How many poses a test checks: VC_RANDOM_POSES, else `fallback`.
inline int pose_count(int fallback) {
  const char* env = std::getenv("VC_RANDOM_POSES");
  return env ? std::atoi(env) : fallback;
}

// Joints drawn uniformly within each axis's travel.
inline machine::Joints random_pose(const machine::Model& model, std::mt19937_64& rng) {
  machine::Joints q(model.joint_count());
  for (int j = 0; j < model.joint_count(); ++j)
    q[j] = std::uniform_real_distribution<double>(model.axes[j].travel_min, model.axes[j].travel_max)(rng);
  return q;
}

inline std::string text(const machine::Joints& q) {
  std::ostringstream s;
  s.precision(17);
  s << q.transpose();
  return s.str();
}

}  // namespace vc::test
