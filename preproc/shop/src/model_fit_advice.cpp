#include "vc/shop/model_fit_advice.hpp"

namespace vc::shop {

ModelFitAdvice advise(const ModelFit& fit) {
  ModelFitAdvice advice;
  for (const ModelFit::Seen& s : fit.seen)
    if (s.share < kSeenShare) advice.unseen.push_back(s.symbol);
  // next_unseen is largest first: the named ones are its head.
  for (const ModelFit::Unseen& u : fit.next_unseen) {
    if (u.largest_mm_per_unit * 1e3 < kFeltUmPerUnit || static_cast<int>(advice.felt_by_next.size()) == kMostFelt)
      break;
    advice.felt_by_next.push_back(u);
  }
  advice.overfitted = fit.effective_unknowns > 0.5 * fit.points;
  return advice;
}

}  // namespace vc::shop
