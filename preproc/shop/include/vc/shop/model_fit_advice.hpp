// What a model fit of self-tuning (selftune_model.hpp) tells the user to do next (volcomp
// selftune --strategy model): which deviations the measured part did not see (they stay at the
// model's values), which of those the next part's points feel most (measure them), and whether
// the fit spent so much of the points on its unknowns that the report's noise went into the tables.
#pragma once

#include <string>
#include <vector>

#include "vc/shop/selftune_model.hpp"

namespace vc::shop {

// A resolution below this: the part does not see the deviation.
constexpr double kSeenShare = 0.05;
// The next part feels an undetermined deviation when its points move by this much per unit
// (um per um or urad) of it, um; at most kMostFelt of them are named.
constexpr double kFeltUmPerUnit = 0.05;
constexpr int kMostFelt = 6;

struct ModelFitAdvice {
  std::vector<std::string> unseen;             // the fit's deviations with a resolution below kSeenShare, in its order
  std::vector<ModelFit::Unseen> felt_by_next;  // the next part's largest sensitivities (largest first)
  bool overfitted = false;                     // the effective unknowns exceed half the points
};

ModelFitAdvice advise(const ModelFit& fit);

}  // namespace vc::shop
