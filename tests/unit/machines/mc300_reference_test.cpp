// The MC-300 at the 60 control points of Appendix 4, against the independent implementation
// of model.md (tests/reference/mc300): volumetric errors, pole fade, corrected joints, and each
// of the 41 deviations alone.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "vc/machine/correct.hpp"
#include "vc/machine/deviations.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::machine {
namespace {

constexpr double kErrorToleranceMm = 1e-9;    // reference README asks 1e-6
constexpr double kErrorToleranceRad = 1e-12;  // reference README asks 1e-9
constexpr double kJointTolerance = 1e-8;      // mm or deg; reference README asks 1e-6

// The six error components of one reference row.
void expect_matches(const VolumetricError& e, const test::CsvTable& ref, std::size_t row) {
  EXPECT_NEAR(e.position_mm.x(), ref.at(row, "ex"), kErrorToleranceMm);
  EXPECT_NEAR(e.position_mm.y(), ref.at(row, "ey"), kErrorToleranceMm);
  EXPECT_NEAR(e.position_mm.z(), ref.at(row, "ez"), kErrorToleranceMm);
  EXPECT_NEAR(e.direction_rad.x(), ref.at(row, "ekx"), kErrorToleranceRad);
  EXPECT_NEAR(e.direction_rad.y(), ref.at(row, "eky"), kErrorToleranceRad);
  EXPECT_NEAR(e.direction_rad.z(), ref.at(row, "ekz"), kErrorToleranceRad);
}

class Mc300Reference : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { model_ = new Model(load_machine(test::machine_path("mc300"))); }
  static void TearDownTestSuite() { delete model_; }
  static Model* model_;
};
Model* Mc300Reference::model_ = nullptr;

TEST_F(Mc300Reference, VolumetricErrorAtSixtyControlPoints) {
  const test::CsvTable ref(test::source_path("tests/reference/mc300/ctrl60_ref.csv"));
  ASSERT_EQ(ref.size(), 60u);
  for (std::size_t i = 0; i < ref.size(); ++i) {
    const Joints q = ref.joints(i, "xyzbc");
    const VolumetricError e = volumetric_error(*model_, q, model_->tool_length_mm);
    SCOPED_TRACE("control point " + std::to_string(i + 1));
    expect_matches(e, ref, i);
  }
}

TEST_F(Mc300Reference, CorrectedJointsAndFadeAtSixtyControlPoints) {
  const test::CsvTable ref(test::source_path("tests/reference/mc300/ctrl60_ref.csv"));
  for (std::size_t i = 0; i < ref.size(); ++i) {
    const Joints q = ref.joints(i, "xyzbc");
    const Correction c = correct(*model_, q, model_->tool_length_mm);
    SCOPED_TRACE("control point " + std::to_string(i + 1));
    ASSERT_EQ(c.status, Status::Ok) << describe(c.status);
    EXPECT_NEAR(c.pole_angle_rad * 180.0 / M_PI, ref.at(i, "pole_deg"), 1e-9);
    EXPECT_NEAR(c.fade, ref.at(i, "f"), 1e-12);
    const char* names[] = {"cx", "cy", "cz", "cb", "cc"};
    for (int j = 0; j < 5; ++j) EXPECT_NEAR(c.joints[j], ref.at(i, names[j]), kJointTolerance) << names[j];
    EXPECT_LT(c.residual_mm, 1e-9);
    EXPECT_NEAR(c.residual_rad, ref.at(i, "residual_rad"), 1e-9);
  }
}

// e-index of the listing -> ISO symbol in our machine file (seed000_B_model.md, s. 2.2).
// e30 and e31 (DSbx, DSbz) are never used by the listing: the reference gives zeros.
const char* const kListingSymbols[42] = {
    nullptr, "EZZ",   "EXZ", "EYZ", "EAZ", "EBZ", "ECZ",  "EA0Z", "EB0Z",           // e1..e8
    "EYY",   "EXY",   "EZY", "EAY", "EBY", "ECY", "EC0Y",                           // e9..e15
    "EXX",   "EYX",   "EZX", "EAX", "EBX", "ECX",                                   // e16..e21
    "EBB",   "EYB",   "EZB", "EXB", "ECB", "EAB", "EC0B", "EA0B",                   // e22..e29
    nullptr, nullptr,                                                               // e30, e31
    "ECC",   "EZC",   "EXC", "EYC", "EBC", "EAC", "EC0C", "EA0C", "EX0C", "EZ0C"};  // e32..e41

TEST_F(Mc300Reference, EachOfTheFortyOneDeviationsAlone) {
  const test::CsvTable ref(test::source_path("tests/reference/mc300/single_ctrl60_ref.csv"));
  ASSERT_EQ(ref.size(), 41u * 60u);
  for (int dev = 1; dev <= 41; ++dev) {
    std::vector<std::string> keep;
    if (kListingSymbols[dev]) keep.push_back(kListingSymbols[dev]);
    const Model single = keep_only(*model_, keep);
    for (std::size_t i = 0; i < ref.size(); ++i) {
      if (static_cast<int>(ref.at(i, "dev")) != dev) continue;
      const VolumetricError e = volumetric_error(single, ref.joints(i, "xyzbc"), single.tool_length_mm);
      SCOPED_TRACE("e" + std::to_string(dev) + " row " + std::to_string(i + 2));
      expect_matches(e, ref, i);
    }
  }
}

// Full-model figures at the control points (printed for the closing note and README):
// M = max |e|, Delta = max |e| - min |e| (seeds/000 L4592-4617).
TEST_F(Mc300Reference, FullModelFiguresAtControlPoints) {
  const test::CsvTable poses(test::source_path("tests/reference/mc300/ctrl60_poses.csv"));
  double max_e = 0.0, min_e = 1e9;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const double e = volumetric_error(*model_, poses.joints(i, "xyzbc"), model_->tool_length_mm).position_mm.norm();
    max_e = std::max(max_e, e);
    min_e = std::min(min_e, e);
  }
  std::printf("MC-300, 60 control points, full model: M = max|e| = %.6f mm, Delta = %.6f mm\n", max_e, max_e - min_e);
  EXPECT_GT(max_e, 0.02);  // tens of micrometres, as the source's machine
  EXPECT_LT(max_e, 0.15);
}

}  // namespace
}  // namespace vc::machine
