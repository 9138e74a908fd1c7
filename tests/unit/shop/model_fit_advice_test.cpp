// What volcomp selftune --strategy model advises after a fit: the deviations the part did not
// see (resolution under 0.05), the next part's largest sensitivities to the undetermined rest
// (0.05 um per unit and more, six at most, largest first), and a fit that spent over half the
// points on its unknowns.
#include <gtest/gtest.h>

#include "vc/shop/model_fit_advice.hpp"

namespace vc::shop {
namespace {

TEST(ModelFitAdvice, TheUnseenAreTheDeviationsUnderTheSeenShareInTheFitsOrder) {
  ModelFit fit;
  fit.seen = {{"EXX", 0.9}, {"EYX", 0.3}, {"EX0C", 0.049}, {"EAX", 0.05}, {"EC0C", 0.0}};
  EXPECT_EQ(advise(fit).unseen, (std::vector<std::string>{"EX0C", "EC0C"}));
}

TEST(ModelFitAdvice, TheNextPartFeelsItsLargestSensitivitiesSixAtMost) {
  ModelFit fit;
  for (int k = 0; k < 8; ++k) fit.next_unseen.push_back({"E" + std::to_string(k), k % 2 == 1, (10 - k) * 1e-4});
  const ModelFitAdvice advice = advise(fit);
  ASSERT_EQ(advice.felt_by_next.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(advice.felt_by_next[k].symbol, fit.next_unseen[k].symbol);
    EXPECT_EQ(advice.felt_by_next[k].angle, fit.next_unseen[k].angle);
  }
}

TEST(ModelFitAdvice, TheNamedOnesStopAtTheFirstTheNextPartHardlyFeels) {
  ModelFit fit;
  fit.next_unseen = {{"EXX", false, 2e-4}, {"EA0C", true, 0.5e-4}, {"EYX", false, 0.4e-4}};
  const ModelFitAdvice advice = advise(fit);
  ASSERT_EQ(advice.felt_by_next.size(), 2u);  // 0.05 um per unit is felt
  EXPECT_EQ(advice.felt_by_next[1].symbol, "EA0C");
  fit.next_unseen = {{"EXX", false, 0.4e-4}, {"EYX", false, 2e-4}};  // largest first: nothing after the first below
  EXPECT_TRUE(advise(fit).felt_by_next.empty());
}

TEST(ModelFitAdvice, AFitOverfitsWhenItsUnknownsTakeOverHalfThePoints) {
  ModelFit fit;
  fit.points = 40;
  fit.effective_unknowns = 20.0;
  EXPECT_FALSE(advise(fit).overfitted);
  fit.effective_unknowns = 20.5;
  EXPECT_TRUE(advise(fit).overfitted);
}

}  // namespace
}  // namespace vc::shop
