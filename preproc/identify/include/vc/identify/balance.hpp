// The accuracy balance of a machine (seeds/000 sec. 3.3.3.3 and Appendix 6: "the sensitivity
// matrix is the accuracy balance of the machine"): what each primary deviation alone does to
// the tool tip over the travel, so that a user knows which measurement pays before measuring.
//
// For every deviation of the machine file (each table column, each non-zero location error)
// the machine with only that deviation is run over a grid of poses covering the travel (every
// joint at `levels` positions; a full turn without repeating 360 deg) at one tool length; its
// tool-tip error (real tip - ideal tip, mm) gives the source's criteria M = max |error| and
// delta = max |error| - min |error|, and the RMS. The share is RMS^2 over the sum of all
// deviations' RMS^2: each deviation's part of the mean-square error if they were independent
// (the contributions of real machines partly cancel or add; `total` is the error with all of
// them). Load time only: allocates.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::identify {

struct BalanceOptions {
  int levels = 5;                        // positions per joint (2..21)
  std::optional<double> tool_length_mm;  // default: the machine file's tool_length_mm
};

struct DeviationEffect {
  std::string symbol;     // EXX, EC0Y, ... ("all" for the total)
  double max_um = 0.0;    // M: largest |tool-tip error|
  double delta_um = 0.0;  // max - min |tool-tip error|
  double rms_um = 0.0;
  double share = 0.0;     // 0..1 of the sum of RMS^2
  double max_urad = 0.0;  // largest tool-direction error
};

struct Balance {
  int poses = 0;
  double tool_length_mm = 0.0;
  DeviationEffect total;                 // all deviations together
  std::vector<DeviationEffect> effects;  // largest M first
};

// Throws std::invalid_argument for levels outside 2..21.
Balance accuracy_balance(const machine::Model& model, const BalanceOptions& options);

}  // namespace vc::identify
