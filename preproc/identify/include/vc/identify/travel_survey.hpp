// The volumetric survey over a machine's travel (volcomp check): the tool-tip error and the
// correction's convergence at the corners and middles of the travel and at random poses.
#pragma once

#include "vc/machine/model.hpp"

namespace vc::identify {

struct TravelSurvey {
  int poses = 0;
  double max_position_mm = 0.0, max_direction_rad = 0.0;  // the largest |error| of the tool tip, of its direction
  machine::Joints worst_position, worst_direction;        // ... and where
  int failures = 0;                                       // poses where the correction did not converge
  machine::Joints first_failure;
  int max_iterations = 0;  // of the converged corrections
  double max_residual_mm = 0.0;
};

// The 3^n corners and middles of the travel, then `samples` random poses (a fixed seed: the
// same poses every run), each at the model's tool length.
TravelSurvey survey_travel(const machine::Model& model, int samples);

}  // namespace vc::identify
