#include "vc/identify/travel_survey.hpp"

#include <algorithm>
#include <random>

#include "vc/machine/correct.hpp"

namespace vc::identify {
namespace {

void survey_pose(const machine::Model& model, const machine::Joints& q, TravelSurvey& s) {
  const double L = model.tool_length_mm;
  const machine::VolumetricError e = machine::volumetric_error(model, q, L);
  ++s.poses;
  if (e.position_mm.norm() > s.max_position_mm) {
    s.max_position_mm = e.position_mm.norm();
    s.worst_position = q;
  }
  if (e.direction_rad.norm() > s.max_direction_rad) {
    s.max_direction_rad = e.direction_rad.norm();
    s.worst_direction = q;
  }
  const machine::Correction c = machine::correct(model, q, L);
  if (c.status != machine::Status::Ok) {
    if (s.failures++ == 0) s.first_failure = q;
    return;
  }
  s.max_iterations = std::max(s.max_iterations, c.iterations);
  s.max_residual_mm = std::max(s.max_residual_mm, c.residual_mm);
}

}  // namespace

TravelSurvey survey_travel(const machine::Model& model, int samples) {
  TravelSurvey s;
  const int n = model.joint_count();
  int grid = 1;
  for (int j = 0; j < n; ++j) grid *= 3;
  machine::Joints q(n);
  for (int k = 0; k < grid; ++k) {
    for (int j = 0, rest = k; j < n; ++j, rest /= 3) {
      const machine::Axis& a = model.axes[j];
      q[j] = a.travel_min + 0.5 * (rest % 3) * (a.travel_max - a.travel_min);
    }
    survey_pose(model, q, s);
  }
  std::mt19937_64 rng(20261123);
  for (int k = 0; k < samples; ++k) {
    for (int j = 0; j < n; ++j)
      q[j] = std::uniform_real_distribution<double>(model.axes[j].travel_min, model.axes[j].travel_max)(rng);
    survey_pose(model, q, s);
  }
  return s;
}

}  // namespace vc::identify
