// Single deviations with answers known in closed form (seed000_B_model.md s. 6 and 9):
// positioning shifts by exactly its table value, a roll moves the tip by R(a) r - r over its
// lever arm r, and squareness theta over a 150 mm circle gives a 2-lobe radial error of
// amplitude R * theta / 2.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "vc/machine/deviations.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::machine {
namespace {

constexpr double kArcsec = M_PI / 180.0 / 3600.0;

class Mc300Alone : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { full_ = new Model(load_machine(test::machine_path("mc300"))); }
  static void TearDownTestSuite() { delete full_; }
  static Model* full_;
};
Model* Mc300Alone::full_ = nullptr;

Joints pose(double x, double y, double z, double b, double c) {
  Joints q(5);
  q << x, y, z, b, c;
  return q;
}

TEST_F(Mc300Alone, PositioningAloneShiftsByExactlyItsTableValue) {
  const Model m = keep_only(*full_, {"EYY"});
  // EYY at y = -100 is 0.001 mm, at y = -230 it is 0.004 mm (psd43 L13917); between nodes the
  // interpolation is linear: at y = -315, (0.005 + 0.006) / 2. At B = C = 0 the part frame is
  // the bed frame. (1e-13: round-off of positions near 300 mm.)
  for (auto [y, eyy] : {std::pair{-100.0, 0.001}, {-230.0, 0.004}, {-275.0, 0.005}, {-315.0, 0.0055}}) {
    const VolumetricError e = volumetric_error(m, pose(-300, y, -150, 0, 0), 100.0);
    EXPECT_NEAR(e.position_mm.y(), eyy, 1e-13) << "y = " << y;
    EXPECT_EQ(e.position_mm.x(), 0.0);
    EXPECT_EQ(e.position_mm.z(), 0.0);
    EXPECT_EQ(e.direction_rad.norm(), 0.0);
  }
}

TEST_F(Mc300Alone, RollTimesLeverArm) {
  const Model m = keep_only(*full_, {"EAX"});
  const double x = -300.0, y = -150.0, z = -130.0;
  // EAX = 5 arcsec * sin(jj), jj = 0..180 deg across x = 0..-600: at x = -300, exactly 5".
  const double a = 5.0 * kArcsec;
  // Lever arm: the tool tip relative to the X slide's origin, in the X frame (model.md,
  // MC-300 table): Y pole + Y travel + Z pole + Z travel + tool.
  const Eigen::Vector3d r = Eigen::Vector3d(-300, -100, -300) + y * Eigen::Vector3d(0, -1, 0) +
                            Eigen::Vector3d(0, -100, -400) + z * Eigen::Vector3d(0, 0, 1) + Eigen::Vector3d(0, 0, -100);
  const Eigen::Vector3d expected = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()) * r - r;
  const VolumetricError e = volumetric_error(m, pose(x, y, z, 0, 0), 100.0);
  EXPECT_LT((e.position_mm - expected).norm(), 1e-13);
  EXPECT_NEAR(e.position_mm.norm(), a * std::hypot(r.y(), r.z()), 1e-12);
  EXPECT_NEAR(e.direction_rad.norm(), std::sin(a), 1e-16);  // |k x k*| = sin a: the tool tilts with the slide
}

// Squareness of Y to X of 100 arcsec (as Fig. 3.23 of the source), on a 150 mm circle in XY:
// after removing the centre shift, the radial error is a 2-lobe of amplitude R * theta / 2
// (36.4 um), with no other harmonics but second-order ones.
TEST_F(Mc300Alone, SquarenessOnACircleGivesTwoLobesOfHalfRTheta) {
  Model m = keep_only(*full_, {"EC0Y"});
  const double theta = 100.0 * kArcsec, radius = 150.0;
  Axis& y_axis = m.axes[m.joint_of('Y')];
  y_axis.location_rad = {0.0, 0.0, theta};
  y_axis.real_base = line_placement(y_axis.pole_mm, y_axis.location_mm, y_axis.location_rad);
  const int n = 360;
  std::array<double, 5> harmonic{};  // a0, a1, b1 (centre shift), a2, b2
  std::vector<double> radial(n);
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    // Tool tip on the circle: machine X and Y move by -x and -y (u = -x, -y).
    const Eigen::Vector3d dir(std::cos(t), std::sin(t), 0.0);
    const VolumetricError e =
        volumetric_error(m, pose(-300 - radius * dir.x(), -160 - radius * dir.y(), -150, 0, 0), 100.0);
    radial[i] = e.position_mm.dot(dir);
    harmonic[0] += radial[i] / n;
    harmonic[1] += 2.0 * radial[i] * std::cos(t) / n;
    harmonic[2] += 2.0 * radial[i] * std::sin(t) / n;
    harmonic[3] += 2.0 * radial[i] * std::cos(2 * t) / n;
    harmonic[4] += 2.0 * radial[i] * std::sin(2 * t) / n;
  }
  const double two_lobe = std::hypot(harmonic[3], harmonic[4]);
  EXPECT_NEAR(two_lobe, radius * theta / 2.0, 1e-8);
  EXPECT_NEAR(two_lobe * 1e3, 36.36, 0.01);  // um
  // Exactly: the tilted Y line moves the tip by y * (sin theta, 1 - cos theta), so the lobe is
  // (R sin theta / 2) sin 2t plus the second-order (R (1 - cos theta) / 2) cos 2t (8.8 nm):
  // the ellipse axes sit at +-45 deg.
  EXPECT_NEAR(std::abs(harmonic[4]), radius * std::sin(theta) / 2.0, 1e-12);
  EXPECT_NEAR(std::abs(harmonic[3]), radius * (1.0 - std::cos(theta)) / 2.0, 1e-12);
  double rest = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    const double fit = harmonic[0] + harmonic[1] * std::cos(t) + harmonic[2] * std::sin(t) +
                       harmonic[3] * std::cos(2 * t) + harmonic[4] * std::sin(2 * t);
    rest = std::max(rest, std::abs(radial[i] - fit));
  }
  EXPECT_LT(rest, 1e-12);  // nothing else
}

TEST_F(Mc300Alone, ToolOnTheSpindleAxisSeesNoSpindleYaw) {
  // e6 (ECZ): rotation about the spindle axis moves no point on it (seed000_B_model.md s. 9).
  const Model m = keep_only(*full_, {"ECZ"});
  const VolumetricError e = volumetric_error(m, pose(-325, -270, -86.69872981077806, 30, 0), 100.0);
  EXPECT_LT(e.position_mm.norm(), 1e-15);
}

}  // namespace
}  // namespace vc::machine
