// The rotary poses of probe-plan's --grid: every combination of the axes' positions, one
// position per axis in joint order, the first axis varying fastest.
#include <gtest/gtest.h>

#include "vc/identify/rotary_grid.hpp"

namespace vc::identify {
namespace {

using Poses = std::vector<std::vector<double>>;

TEST(RotaryGrid, EveryCombinationTheFirstAxisFastest) {
  EXPECT_EQ(rotary_grid({{0, -30}, {0, 90, 180}}), (Poses{{0, 0}, {-30, 0}, {0, 90}, {-30, 90}, {0, 180}, {-30, 180}}));
}

TEST(RotaryGrid, OneAxisGivesItsPositionsInTheirOrder) {
  EXPECT_EQ(rotary_grid({{0, 90, 180, 270}}), (Poses{{0}, {90}, {180}, {270}}));
}

TEST(RotaryGrid, TheCountIsTheProductOfTheAxesPositions) {
  EXPECT_EQ(rotary_grid({{0, -30, -60, -90}, {0, 90, 180, 270}, {1, 2}}).size(), 32u);
}

TEST(RotaryGrid, NoRotaryAxisGivesOneEmptyPose) { EXPECT_EQ(rotary_grid({}), (Poses{{}})); }

}  // namespace
}  // namespace vc::identify
