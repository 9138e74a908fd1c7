// What volcomp identify laser puts into the table: each target's value by --direction, its
// standard uncertainty (the solve's weights), and the rows, where a rotary axis measured over
// exactly one turn holds the mean of its 0 and 360 deg readings at both ends.
#include <gtest/gtest.h>

#include <cmath>

#include "vc/identify/laser_table.hpp"

namespace vc::identify {
namespace {

TargetStatistics target(double at, double up, double down, double s_up = 0.0, double s_down = 0.0) {
  TargetStatistics t;
  t.target = at;
  t.mean_up = up;
  t.mean_down = down;
  t.mean = (up + down) / 2;
  t.s_up = s_up;
  t.s_down = s_down;
  return t;
}

Iso230_2 evaluation(std::vector<TargetStatistics> targets, int runs_up = 4, int runs_down = 4) {
  Iso230_2 e;
  e.targets = std::move(targets);
  e.runs_up = runs_up;
  e.runs_down = runs_down;
  return e;
}

TEST(LaserTable, TheValueIsTheBidirectionalMeanOrOneDirections) {
  const TargetStatistics t = target(100, 0.004, 0.002);
  EXPECT_DOUBLE_EQ(table_value(t, TableValue::Bidirectional), 0.003);
  EXPECT_DOUBLE_EQ(table_value(t, TableValue::Up), 0.004);
  EXPECT_DOUBLE_EQ(table_value(t, TableValue::Down), 0.002);
}

TEST(LaserTable, TheUncertaintyIsThatOfAMeanOfTheRuns) {
  const Iso230_2 e = evaluation({target(0, 0, 0, 0.002, 0.001)}, 4, 9);
  const TargetStatistics& t = e.targets.front();
  EXPECT_DOUBLE_EQ(table_value_uncertainty(t, e, TableValue::Up), 0.002 / 2);
  EXPECT_DOUBLE_EQ(table_value_uncertainty(t, e, TableValue::Down), 0.001 / 3);
  EXPECT_DOUBLE_EQ(table_value_uncertainty(t, e, TableValue::Bidirectional), std::hypot(0.001, 0.001 / 3) / 2);
}

TEST(LaserTable, OneTurnIsARotaryAxisFrom0To360WithMoreThanTwoTargets) {
  const Iso230_2 turn = evaluation({target(0, 0, 0), target(180, 0, 0), target(360, 0, 0)});
  EXPECT_TRUE(spans_one_turn(turn, true));
  EXPECT_FALSE(spans_one_turn(turn, false));  // the same numbers in mm: a linear axis
  EXPECT_FALSE(spans_one_turn(evaluation({target(0, 0, 0), target(180, 0, 0), target(350, 0, 0)}), true));
  EXPECT_FALSE(spans_one_turn(evaluation({target(0, 0, 0), target(360, 0, 0)}), true));
}

TEST(LaserTable, OverOneTurnBothEndsHoldTheMeanOfTheirReadings) {
  const Iso230_2 e =
      evaluation({target(0, 2e-6, 2e-6), target(120, 5e-6, 5e-6), target(240, 1e-6, 1e-6), target(360, 4e-6, 4e-6)});
  const std::vector<TableRow> rows = laser_table_rows(e, true, TableValue::Bidirectional);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_DOUBLE_EQ(rows.front().value, 3e-6);
  EXPECT_DOUBLE_EQ(rows.back().value, 3e-6);
  EXPECT_DOUBLE_EQ(rows[1].value, 5e-6);
  EXPECT_DOUBLE_EQ(rows[2].value, 1e-6);
}

TEST(LaserTable, ALinearAxisKeepsEveryTargetsValueInAscendingOrder) {
  const Iso230_2 e = evaluation({target(-100, 0.001, 0.003), target(0, 0.0, 0.0), target(100, -0.002, 0.0)});
  const std::vector<TableRow> rows = laser_table_rows(e, false, TableValue::Down);
  ASSERT_EQ(rows.size(), 3u);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_DOUBLE_EQ(rows[k].target, e.targets[k].target);
    EXPECT_DOUBLE_EQ(rows[k].value, e.targets[k].mean_down);
  }
}

}  // namespace
}  // namespace vc::identify
