// The local strategy's estimate of the tool's displacement and tilt (vc/shop/local_fit.hpp)
// against known answers: deviations of a wall and a floor that a displaced, tilted flat end
// mill leaves, computed by the virtual CMM's geometry (the swept cylinder, MachinedSurface),
// not by the fit's linear model; and an exact rotation for a corner.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "vc/shop/local_fit.hpp"
#include "vc/shop/machined_surface.hpp"

namespace vc {
namespace {

constexpr double kRadius = 5.0;

// A pass along x from -50 to 50 of a flat end mill (radius 5): tip at (x, y0, z0), its axis
// tilted by `tilt` rad toward +y, sampled every 2 mm.
shop::ToolPath pass(double y0, double z0, double tilt) {
  shop::ToolPath path;
  for (int k = 0; k <= 50; ++k) {
    shop::PathSample s;
    s.move = 1;
    s.cutting = true;
    s.radius_mm = kRadius;
    s.tip = {-50 + 2.0 * k, y0, z0};
    s.axis = {0, std::sin(tilt), std::cos(tilt)};
    path.push_back(s);
  }
  return path;
}

// The report of that pass's nominal (y0 = z0 = tilt = 0) wall y = -5 (material below, normal
// +y) at `heights` along the tool and of its floor z = 0 under the tip (normal +z), as the
// fit's anchors: the tool frame is the part frame (a vertical tool), the cut's tip the
// nominal one at the point's x.
std::vector<shop::Anchor> anchors(const shop::ToolPath& path, const std::vector<double>& heights, bool floor) {
  const shop::MachinedSurface surface(path);
  std::vector<shop::Anchor> out;
  for (int i = -10; i <= 10; ++i) {
    const double x = 3.0 * i;
    for (const double h : heights) {
      const Eigen::Vector3d p(x, -kRadius, h), n(0, 1, 0);
      out.push_back({Eigen::Vector3d(x, 0, 0), n, h, surface.deviation(p, n).value()});
    }
    if (floor) {
      const Eigen::Vector3d p(x, 0, 0), n(0, 0, 1);  // under the tip: the tilted end passes at its height
      out.push_back({Eigen::Vector3d(x, 0, 0), n, 0.0, surface.deviation(p, n).value()});
    }
  }
  return out;
}

TEST(LocalFit, ASwarfWallTellsTheTiltTowardsItFromAShiftOfTheTip) {
  const double y0 = -0.002, z0 = 0.0015, tilt = 1e-4;  // 2 um into the wall, 1.5 um above the floor, 100 urad
  const std::vector<shop::Anchor> a = anchors(pass(y0, z0, tilt), {2, 6, 10, 14, 18}, true);
  const shop::LocalFit fit =
      shop::fit_tool_displacement(a, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), {40.0, 0.0, true, 1.0, 0.0});
  ASSERT_TRUE(fit.covered);
  EXPECT_EQ(fit.tilt_components, 1) << "the wall sees the tilt towards it only";
  // Turning e_z toward +y by `tilt` is a rotation of -tilt about x.
  EXPECT_NEAR(fit.tilt_rad.x(), -tilt, 0.01 * tilt);
  EXPECT_EQ(fit.tilt_rad.y(), 0.0) << "the tilt along the wall moves no point of it";
  EXPECT_NEAR(fit.shift_mm.y(), y0, 2e-5);
  EXPECT_NEAR(fit.shift_mm.z(), z0, 2e-5);
  EXPECT_EQ(fit.shift_mm.x(), 0.0) << "no normal sees x: it stays at zero";

  // The same points fitted with a shift alone: the tilt's mean over the heights is taken as a
  // shift, the rest is left.
  const shop::LocalFit shift_only = shop::fit_tool_displacement(a, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                                                                {40.0, 0.0, false, 1.0, 0.0});
  EXPECT_EQ(shift_only.tilt_components, 0);
  EXPECT_NEAR(shift_only.shift_mm.y(), y0 + 10 * tilt, 2e-5);
}

TEST(LocalFit, PointsAtOneHeightOrOnTheFloorDoNotTellATilt) {
  const shop::ToolPath path = pass(-0.002, 0.001, 1e-4);
  for (const auto& [heights, floor] : {std::pair{std::vector<double>{8}, true}, std::pair{std::vector<double>{}, true},
                                       std::pair{std::vector<double>{9.5, 10, 10.5}, false}}) {
    const std::vector<shop::Anchor> a = anchors(path, heights, floor);
    const shop::LocalFit with = shop::fit_tool_displacement(a, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                                                            {40.0, 0.0, true, 1.0, 0.0});
    const shop::LocalFit without = shop::fit_tool_displacement(a, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                                                               {40.0, 0.0, false, 1.0, 0.0});
    EXPECT_EQ(with.tilt_components, 0) << heights.size() << " heights";
    EXPECT_EQ(with.tilt_rad, Eigen::Vector3d::Zero());
    EXPECT_EQ(with.shift_mm, without.shift_mm) << "the tip's shift as without the tilt";
  }
}

// The noise test against its own statistics: a wall with no tilt and 1 um of noise on each
// point (its standard error: some 25 urad) is refused as noise in 68 % of 300 draws (z^2 <= 1,
// chi-square with one degree of freedom), which checks the tilt's standard error; with
// 1000 urad it is kept in every draw, shrunk by 1 - 1/z^2 (z near 40: by 0.1 %).
TEST(LocalFit, ATiltWithinItsNoiseIsNotKept) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.001);
  const shop::LocalFitOptions options{40.0, 0.0, true, 1.0, 0.001};
  for (const double tilt : {0.0, 1e-3}) {
    const std::vector<shop::Anchor> exact = anchors(pass(0.0, 0.0, tilt), {3, 9, 15}, false);
    int refused = 0;
    const int draws = 300;
    for (int draw = 0; draw < draws; ++draw) {
      std::vector<shop::Anchor> a = exact;
      for (std::size_t k = 0; k < a.size(); ++k) {
        a[k].deviation_mm += noise(random);
        a[k].point = static_cast<int>(k);
      }
      const shop::LocalFit fit =
          shop::fit_tool_displacement(a, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), options);
      if (fit.tilt == shop::TiltFit::BelowNoise) {
        ++refused;
        EXPECT_EQ(fit.tilt_rad, Eigen::Vector3d::Zero());
      } else if (tilt > 0) {
        EXPECT_NEAR(fit.tilt_rad.x(), -tilt, 0.1 * tilt);
      }
    }
    if (tilt == 0) {
      EXPECT_GT(refused, 0.60 * draws);
      EXPECT_LT(refused, 0.76 * draws);
    } else {
      EXPECT_EQ(refused, 0);
    }
  }
}

// The cuts of one pass next to a wall point, their tool frames turned by a few degrees: the
// point's normal in them spreads by +-3 deg, which does not tell a shift along the wall.
TEST(LocalFit, NormalsAFewDegreesApartDoNotTellAShiftAlongTheSurface) {
  std::vector<shop::Anchor> a;
  for (int point = 0; point < 20; ++point)
    for (int cut = -3; cut <= 3; ++cut) {
      const double turn = (cut + 0.3 * (point % 3)) * M_PI / 180;      // not symmetric about the point
      const double deviation = 0.010 + 0.001 * ((point * 7) % 5 - 2);  // 10 um, +-2 um of scatter
      a.push_back({Eigen::Vector3d(0.5 * cut, 2.0 * point - 20, 0), Eigen::Vector3d(std::cos(turn), std::sin(turn), 0),
                   5.0, deviation, Eigen::Matrix3d::Identity(), point});
    }
  const shop::LocalFit fit = shop::fit_tool_displacement(a, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                                                         {40.0, 0.0, false, 1.0, 0.0});
  EXPECT_NEAR(fit.shift_mm.x(), 0.010, 0.002);
  // Along the mean normal (turned by 0.3 deg: 0.05 um of y), not the least-squares answer.
  EXPECT_LT(std::abs(fit.shift_mm.y()), 1e-4);
  EXPECT_EQ(fit.shift_mm.z(), 0.0);
}

// The support counts measured points, not cuts: a point's cuts share its noise.
TEST(LocalFit, SupportIsTheEffectiveNumberOfPointsNotOfCuts) {
  std::vector<shop::Anchor> a;
  for (int point = 0; point < 4; ++point)
    for (int cut = 0; cut < 25; ++cut)
      a.push_back({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 0.0, 0.001, Eigen::Matrix3d::Identity(), point});
  const shop::LocalFitOptions options{40.0, 0.0, false, 1.0, 0.0};
  EXPECT_NEAR(shop::fit_tool_displacement(a, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), options).support,
              4.0, 1e-12);
  // One point more, far out and with one cut (weight exp(-2 * 0.75^2) = 0.32 against the others' 25): 4.03.
  a.push_back({Eigen::Vector3d(30, 0, 0), Eigen::Vector3d(1, 0, 0), 0.0, 0.001, Eigen::Matrix3d::Identity(), 4});
  const double support =
      shop::fit_tool_displacement(a, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), options).support;
  EXPECT_GT(support, 4.0);
  EXPECT_LT(support, 4.1);
}

TEST(LocalFit, TwoWallsAtACornerTellBothComponentsOfTheTilt) {
  // Deviations of a tool turned by an exact rotation about its tip, on walls facing +y and +x.
  const Eigen::Vector3d v(0.001, -0.0015, 0.0005), w(3e-5, -5e-5, 0);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  std::vector<shop::Anchor> a;
  for (const Eigen::Vector3d& n : {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 0, 0)})
    for (int i = -5; i <= 5; ++i)
      for (const double h : {3.0, 9.0, 15.0}) {
        const Eigen::Vector3d along = n.cross(Eigen::Vector3d::UnitZ());
        const Eigen::Vector3d tip = 2.0 * i * along;
        const Eigen::Vector3d on_tool = h * Eigen::Vector3d::UnitZ() - kRadius * n;  // the side touching the wall
        a.push_back({tip, n, h, n.dot(v + turn * on_tool - on_tool)});
      }
  const shop::LocalFit fit =
      shop::fit_tool_displacement(a, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), {40.0, 0.0, true, 1.0, 0.0});
  EXPECT_EQ(fit.tilt_components, 2);
  EXPECT_NEAR((fit.tilt_rad - w).norm(), 0.0, 1e-3 * w.norm());
  EXPECT_NEAR(fit.shift_mm.x(), v.x(), 1e-7);
  EXPECT_NEAR(fit.shift_mm.y(), v.y(), 1e-7);
}

}  // namespace
}  // namespace vc
