// The accuracy balance: a positioning error reaches the tool tip one to one (checked against
// its table, independently of the kinematic chain), the shares add up, and on the MC-300 the
// largest effects are those the source's sensitivity matrix ranks highest (Appendix 6, a
// qualitative oracle: seed 000, section 3.3.3.3 and Appendix 6, the accuracy balance).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "test_support.hpp"
#include "vc/identify/balance.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::identify {
namespace {

const DeviationEffect& effect(const Balance& b, const std::string& symbol) {
  const auto it = std::find_if(b.effects.begin(), b.effects.end(), [&](const auto& e) { return e.symbol == symbol; });
  if (it == b.effects.end()) throw std::runtime_error("no " + symbol);
  return *it;
}

TEST(AccuracyBalance, PositioningErrorReachesTheTipOneToOne) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const Balance b = accuracy_balance(model, {});
  EXPECT_EQ(b.poses, 5 * 5 * 5);
  // EXX straight from its table at the grid's five X positions.
  const int x = model.joint_of('X');
  const machine::Axis& axis = model.axes[static_cast<std::size_t>(x)];
  double largest = 0, least = INFINITY;
  for (int k = 0; k < 5; ++k) {
    const double at = axis.travel_min + (axis.travel_max - axis.travel_min) * k / 4;
    double exx = 0;
    for (int t : axis.tables) {
      const tables::ErrorTable& table = model.tables[static_cast<std::size_t>(t)].table;
      tables::ErrorTable::Sample sample;
      table.evaluate(&at, sample, false);
      for (std::size_t c = 0; c < table.columns().size(); ++c)
        if (table.columns()[c].symbol.name() == "EXX") exx += sample.value[c];
    }
    largest = std::max(largest, std::abs(exx) * 1e3);
    least = std::min(least, std::abs(exx) * 1e3);
  }
  EXPECT_GT(largest, 1.0);
  EXPECT_NEAR(effect(b, "EXX").max_um, largest, 1e-6);
  EXPECT_NEAR(effect(b, "EXX").delta_um, largest - least, 1e-6);
  EXPECT_EQ(effect(b, "EXX").max_urad, 0.0);

  double shares = 0;
  for (std::size_t k = 0; k < b.effects.size(); ++k) {
    shares += b.effects[k].share;
    if (k) {
      EXPECT_LE(b.effects[k].max_um, b.effects[k - 1].max_um);  // largest first
    }
  }
  EXPECT_NEAR(shares, 1.0, 1e-12);
  EXPECT_GT(b.total.max_um, 0.0);
}

TEST(AccuracyBalance, Mc300RanksTheSourcesLargestSensitivitiesHigh) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const Balance b = accuracy_balance(model, {});
  EXPECT_EQ(b.tool_length_mm, 100.0);
  // Appendix 6's eight largest |DMAX|: EAX EBX ECB EBY EAY ECX theta_byz (EA0B) ECC.
  int found = 0;
  for (const char* s : {"EAX", "EBX", "ECB", "EBY", "EAY", "ECX", "EA0B", "ECC"})
    for (std::size_t k = 0; k < 10 && k < b.effects.size(); ++k)
      if (b.effects[k].symbol == s) ++found;
  EXPECT_GE(found, 5);
  // The angular deviations act through lever arms, the linear ones one to one (L4641-4650):
  // the largest effect is an angular one and larger than any table's largest translation.
  EXPECT_EQ(b.effects.front().symbol.substr(0, 2) == "EA" || b.effects.front().symbol.substr(0, 2) == "EB" ||
                b.effects.front().symbol.substr(0, 2) == "EC",
            true)
      << b.effects.front().symbol;
}

TEST(AccuracyBalance, RefusesAGridItCannotMake) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  BalanceOptions options;
  options.levels = 1;
  EXPECT_THROW(accuracy_balance(model, options), std::invalid_argument);
}

}  // namespace
}  // namespace vc::identify
