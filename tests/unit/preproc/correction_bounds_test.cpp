// The bounds that let the path corrector accept pieces unchecked: where the kinks of the
// correction lie (table nodes, grid ends, the periodic wrap), and that the slope and
// curvature bounds hold the tool-tip error LinuxCNC's straight interpolation between two
// corrected points makes, computed exactly with the core's correction and forward model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <thread>

#include "test_support.hpp"
#include "vc/machine/correct.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/correction_bounds.hpp"

namespace vc::predistort {
namespace {

using machine::Joints;

Joints joints(std::initializer_list<double> values) {
  Joints q(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double v : values) q[i++] = v;
  return q;
}

TEST(CorrectionBounds, KinksAreTheNodesOfLinearTablesAndThePeriodicWrap) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const CorrectionBounds bounds(model, model.reference_conditions());
  // MC-300 C table: 0:5:360 deg, linear, periodic; 1e-3 deg clear of a node.
  const auto c_move = [&](double from, double to) {
    return bounds.crosses_kink(joints({-301.3, -161.7, -201.9, -36.2, from}),
                               joints({-301.3, -161.7, -201.9, -36.2, to}));
  };
  EXPECT_FALSE(c_move(1.0, 4.0));
  EXPECT_TRUE(c_move(4.0, 6.0));
  EXPECT_TRUE(c_move(6.0, 4.0));
  EXPECT_TRUE(c_move(5.0, 9.0));
  EXPECT_FALSE(c_move(5.002, 9.0));
  EXPECT_TRUE(c_move(5.0005, 9.0));
  EXPECT_TRUE(c_move(358.0, 361.0));  // 360 = 0
  EXPECT_FALSE(c_move(361.0, 364.0));
  EXPECT_FALSE(c_move(-359.0, -356.0));
  EXPECT_TRUE(c_move(-1.0, 1.0));
  EXPECT_TRUE(c_move(1.0, 400.0));
}

// Short straight pieces everywhere in the travel, every other one where the orientation
// correction fades in (the correction bends most there): the exact tool-tip error at 1/4,
// 1/2, 3/4 of LinuxCNC's interpolation between the corrected ends, against the bounds.
void expect_bounds_hold(const std::string& machine_name) {
  const machine::Model model = machine::load_machine(test::machine_path(machine_name));
  CorrectionBounds bounds(model, model.reference_conditions());
  const double L = model.tool_length_mm;
  const int n = model.joint_count();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int smooth = 0, below_slope = 0, below_curvature = 0;
  double worst_slope = 0.0, worst_curvature = 0.0;  // error / bound
  double worst_slope_rad = 0.0, worst_curvature_rad = 0.0;
  for (int piece = 0; piece < 3000; ++piece) {
    Joints a(n), b(n);
    const double length = std::pow(10.0, -1.5 + 2.0 * unit(random));  // 0.03 .. 3 mm or deg
    const bool in_band = model.rotary_count() > 0 && piece % 2 == 1;
    for (int attempt = 0; attempt < 10000; ++attempt) {
      for (int j = 0; j < n; ++j) {
        const machine::Axis& axis = model.axes[static_cast<std::size_t>(j)];
        a[j] = axis.travel_min + length + unit(random) * (axis.travel_max - axis.travel_min - 2 * length);
        b[j] = a[j] + length * (2 * unit(random) - 1);
      }
      const double phi = machine::pole_angle(model, a, L);
      if (!in_band || (phi > model.fade.start_rad && phi < model.fade.full_rad)) break;
    }
    const machine::Correction ca = machine::correct(model, a, L), cb = machine::correct(model, b, L);
    ASSERT_EQ(ca.status, machine::Status::Ok);
    ASSERT_EQ(cb.status, machine::Status::Ok);
    double error = 0.0, error_rad = 0.0;
    for (double t : {0.25, 0.5, 0.75}) {
      const Joints commanded = ca.joints + t * (cb.joints - ca.joints);
      const machine::ToolPose real = machine::tool_pose(model, machine::Machine::Real, commanded, L);
      const Eigen::Vector3d ideal = machine::tool_pose(model, machine::Machine::Ideal, a + t * (b - a), L).tip_mm;
      error = std::max(error, (real.tip_mm - ideal).norm());
      // The direction against the exact correction's there (the pole fade leaves it off ideal).
      const machine::Correction exact = machine::correct(model, a + t * (b - a), L);
      const Eigen::Vector3d exact_direction =
          machine::tool_pose(model, machine::Machine::Real, exact.joints, L).direction;
      error_rad = std::max(error_rad, (real.direction - exact_direction).norm());
    }
    const CorrectionBounds::Bound slope = bounds.slope_bound(a, b, L);
    const CorrectionBounds::Bound curvature = bounds.curvature_bound(a, b, ca.joints, cb.joints, L);
    EXPECT_LE(error, slope.mm) << machine_name << " piece " << piece;
    const bool rotary = model.rotary_count() > 0;  // the direction is bounded (corrected) only there
    if (rotary) {
      EXPECT_LE(error_rad, slope.rad) << machine_name << " piece " << piece;
    }
    worst_slope = std::max(worst_slope, error / slope.mm);
    if (rotary) worst_slope_rad = std::max(worst_slope_rad, error_rad / slope.rad);
    below_slope += slope.mm <= 1.25e-4;
    if (std::isinf(curvature.mm)) continue;
    ++smooth;
    EXPECT_LE(error, curvature.mm) << machine_name << " piece " << piece << " from " << a.transpose() << " to "
                                   << b.transpose();
    if (rotary) {
      EXPECT_LE(error_rad, curvature.rad) << machine_name << " piece " << piece;
    }
    worst_curvature = std::max(worst_curvature, error / curvature.mm);
    if (rotary) worst_curvature_rad = std::max(worst_curvature_rad, error_rad / curvature.rad);
    below_curvature += curvature.mm <= 1.25e-4;
  }
  std::printf(
      "%s: 3000 pieces, %d cross no kink; largest error / bound: slope %.3f, curvature %.3f (tool "
      "direction: %.3f, %.3f); within a quarter of 0.5 um: slope %d, curvature %d\n",
      machine_name.c_str(), smooth, worst_slope, worst_curvature, worst_slope_rad, worst_curvature_rad, below_slope,
      below_curvature);
  EXPECT_GT(smooth, 300);  // the curvature bound is exercised
}

// The last search's answer is kept as a hint for the next: answers along a path, back and
// forth, across the wrap and far jumps must be those of a bounds object that never searched.
TEST(CorrectionBounds, KinkSearchesFromTheLastAnswerAnswerAsFreshOnes) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const CorrectionBounds walked(model, model.reference_conditions());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> jump(-400.0, 400.0), step(-3.0, 3.0), length(0.0, 8.0);
  Joints a = joints({-300.0, -160.0, -200.0, -35.0, 0.0});
  int crossings = 0;
  for (int k = 0; k < 2000; ++k) {
    for (int j = 0; j < 5; ++j) a[j] += k % 50 == 0 ? jump(rng) : step(rng);
    Joints b = a;
    for (int j = 0; j < 5; ++j) b[j] += (k % 2 ? 1 : -1) * length(rng);
    const bool fresh = CorrectionBounds(model, model.reference_conditions()).crosses_kink(a, b);
    ASSERT_EQ(walked.crosses_kink(a, b), fresh)
        << "query " << k << " from " << a.transpose() << " to " << b.transpose();
    crossings += fresh;
  }
  EXPECT_GT(crossings, 200);
  EXPECT_LT(crossings, 1800);
}

// Correctors on two threads share the sampling at a tool length (each samples a part): both
// get exactly the bounds of a corrector that sampled alone, and so does one that asks later
// or finds no other to share with.
TEST(CorrectionBounds, SharedSamplingGivesTheBoundsOfOneSamplingAlone) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const double L = 100.0;
  const Joints a = joints({-301.3, -161.7, -201.9, -36.2, 20.0}), b = joints({-300.9, -161.2, -201.5, -35.9, 20.4});
  const Joints ca = machine::correct(model, a, L).joints, cb = machine::correct(model, b, L).joints;
  const auto bounds_of = [&](CorrectionBounds& bounds) {
    return std::array<double, 4>{bounds.slope_bound(a, b, L).mm, bounds.curvature_bound(a, b, ca, cb, L).mm,
                                 bounds.slope_bound(a, b, L).rad, bounds.curvature_bound(a, b, ca, cb, L).rad};
  };
  CorrectionBounds alone(model, model.reference_conditions());
  const std::array<double, 4> expected = bounds_of(alone);
  ASSERT_GT(expected[0], 0.0);
  ASSERT_TRUE(std::isfinite(expected[1]));

  CorrectionBounds::Shared shared;
  const machine::Conditions reference = model.reference_conditions();
  CorrectionBounds first(model, reference, &shared), second(model, reference, &shared),
      later(model, reference, &shared);
  std::array<double, 4> got_first{}, got_second{};
  std::thread other([&] { got_second = bounds_of(second); });
  got_first = bounds_of(first);
  other.join();
  EXPECT_EQ(got_first, expected);
  EXPECT_EQ(got_second, expected);
  EXPECT_EQ(bounds_of(later), expected);

  CorrectionBounds::Shared unshared;
  CorrectionBounds single(model, model.reference_conditions(), &unshared);
  EXPECT_EQ(bounds_of(single), expected);
}

TEST(CorrectionBounds, HoldTheInterpolationErrorOnMc300) { expect_bounds_hold("mc300"); }
TEST(CorrectionBounds, HoldTheInterpolationErrorOnAcTrunnion) { expect_bounds_hold("ac_trunnion"); }
TEST(CorrectionBounds, HoldTheInterpolationErrorOnMill3) { expect_bounds_hold("mill3"); }

}  // namespace
}  // namespace vc::predistort
