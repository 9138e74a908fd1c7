// invert_correction (the forward kinematics' Newton on the real pose) against two independent
// computations: the nominal joints the corrected ones were made from (correct() of known q_n),
// and the fixed point `uncorrect`, which only ever evaluates whole corrections. To 1e-9 on every
// shipped machine and the test machines (a rotary head; one rotary axis), with the seeds the
// servo thread gives (the previous cycle's answer, q_c itself, a far one), through the MC-300's
// pole fade band (also with the full corrections the servo thread keeps), and for a partial gain. Seeded; VC_RANDOM_POSES overrides the pose count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vc/machine/invert_correction.hpp"
#include "random_poses.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::machine {
namespace {

int pose_count() { return test::pose_count(4000); }
using test::random_pose;
using test::text;

double max_difference(const Joints& a, const Joints& b) { return (a - b).cwiseAbs().maxCoeff(); }

Model load(const std::string& name) {
  for (const char* test_only : {"bc_head", "xyza_table"})
    if (name == test_only) return load_machine(test::source_path("tests/unit/machines/data/" + name + ".toml"));
  return load_machine(test::machine_path(name));
}

std::vector<std::string> machines() {
  std::vector<std::string> all = test::shipped_machines();
  all.push_back("bc_head");
  all.push_back("xyza_table");
  return all;
}

class EveryMachine : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { model_ = load(GetParam()); }
  Model model_;
};

// The servo thread's seeds: the previous cycle's answer (one cycle at 100 mm/s and 60 deg/s
// at 1 kHz before), the corrected joints themselves, and one too far to help.
TEST_P(EveryMachine, FindsTheNominalJointsAndAgreesWithTheFixedPoint) {
  std::mt19937_64 rng(21);
  const double L = model_.tool_length_mm;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int newton_only = 0;
  for (int k = 0; k < pose_count(); ++k) {
    const Joints nominal = random_pose(model_, rng);
    const Correction c = correct(model_, nominal, L);
    ASSERT_EQ(c.status, Status::Ok) << text(nominal);
    Joints previous = nominal;
    for (int j = 0; j < model_.joint_count(); ++j)
      previous[j] += unit(rng) * (model_.axes[j].type == AxisType::Linear ? 0.1 : 0.06);
    const Uncorrection reference = uncorrect(model_, c.joints, L);
    ASSERT_EQ(reference.status, Status::Ok) << text(nominal);
    ASSERT_LT(max_difference(reference.nominal, nominal), 1e-9) << text(nominal);
    for (const Joints& seed : {previous, c.joints, random_pose(model_, rng)}) {
      const Uncorrection u = invert_correction(model_, c.joints, L, 1.0, seed);
      ASSERT_EQ(u.status, Status::Ok) << describe(u.status) << " at " << text(nominal) << " seed " << text(seed);
      ASSERT_LT(max_difference(u.nominal, nominal), 1e-9) << text(nominal) << " seed " << text(seed);
      ASSERT_LT(max_difference(u.nominal, reference.nominal), 1e-9) << text(nominal) << " seed " << text(seed);
    }
    // Outside the fade band a near seed needs no correction at all: a few Newton steps.
    const Uncorrection u = invert_correction(model_, c.joints, L, 1.0, previous);
    if (c.fade == 0.0 || c.fade == 1.0) {
      EXPECT_LE(u.iterations, 5) << text(nominal);
      newton_only += u.iterations <= 5;
    }
  }
  EXPECT_GT(newton_only, pose_count() / 2);
}

// The enable ramp: a partial correction is the fixed point's business; the answer is the same.
TEST_P(EveryMachine, PartialGainIsTheFixedPointsAnswer) {
  std::mt19937_64 rng(22);
  const double L = model_.tool_length_mm;
  for (int k = 0; k < pose_count() / 20; ++k) {
    const Joints nominal = random_pose(model_, rng);
    const double gain = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    const Joints corrected = nominal + gain * (correct(model_, nominal, L).joints - nominal);
    const Uncorrection u = invert_correction(model_, corrected, L, gain, corrected);
    ASSERT_EQ(u.status, Status::Ok);
    ASSERT_LT(max_difference(u.nominal, nominal), 1e-9) << text(nominal) << " gain " << gain;
  }
}

// The bound on what an ideal Newton step leaves: the second-order remainder of the ideal pose
// along random steps (1e-4 to 1 mm or deg, where the remainder is far above rounding), the pose
// at the step's end through the 4x4 chain (part_T_tool), the first order from tool_pose's
// derivatives. Printed: how tight the bound is (largest remainder / bound).
TEST_P(EveryMachine, IdealStepRemainderBoundsTheSecondOrder) {
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), exponent(-4.0, 0.0), length(0.0, 300.0);
  double tightest_position = 0.0, tightest_direction = 0.0;
  for (int k = 0; k < pose_count(); ++k) {
    const Joints from = random_pose(model_, rng);
    const double L = length(rng);
    Joints to = from;
    const double scale = std::pow(10.0, exponent(rng));
    for (int j = 0; j < to.size(); ++j) to[j] += scale * unit(rng);
    PoseDerivatives d;
    const ToolPose start = tool_pose(model_, Machine::Ideal, from, L, d);
    const Joints step = to - from;
    const Eigen::Isometry3d end = part_T_tool(model_, Machine::Ideal, to, L);
    const double position = (end.translation() - start.tip_mm - d.tip.leftCols(step.size()) * step).norm();
    const double direction = (end.linear().col(2) - start.direction - d.direction.leftCols(step.size()) * step).norm();
    const StepRemainder bound = ideal_step_remainder(model_, from, to, L);
    // Rounding of the two chains: ~1e-13 mm, ~1e-16 rad.
    ASSERT_LE(position, bound.position_mm + 1e-12) << text(from) << " to " << text(to) << ", L " << L;
    ASSERT_LE(direction, bound.direction_rad + 1e-15) << text(from) << " to " << text(to) << ", L " << L;
    if (bound.position_mm > 1e-9) tightest_position = std::max(tightest_position, position / bound.position_mm);
    if (bound.direction_rad > 1e-12) tightest_direction = std::max(tightest_direction, direction / bound.direction_rad);
  }
  std::printf("%s: largest remainder / bound: position %.3f, direction %.3f\n", GetParam().c_str(), tightest_position,
              tightest_direction);
}

// Started ~1e-11 to 1e-7 off (LinuxCNC's feedback less the correction volkins keeps for it),
// the forward ends on a proved step as a rule, with the same answer.
TEST_P(EveryMachine, NearSeedsEndOnAProvedStepWithTheSameAnswer) {
  std::mt19937_64 rng(25);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), exponent(-11.0, -7.0), length(0.0, 300.0);
  int proved = 0, full = 0;
  for (int k = 0; k < pose_count(); ++k) {
    const Joints nominal = random_pose(model_, rng);
    const double L = length(rng);
    const Correction c = correct(model_, nominal, L);
    ASSERT_EQ(c.status, Status::Ok) << text(nominal);
    Joints seed = nominal;
    const double scale = std::pow(10.0, exponent(rng));
    for (int j = 0; j < seed.size(); ++j) seed[j] += scale * unit(rng);
    const Uncorrection u = invert_correction(model_, c.joints, L, 1.0, seed);
    ASSERT_EQ(u.status, Status::Ok) << text(nominal);
    ASSERT_LT(max_difference(u.nominal, nominal), 1e-9) << text(nominal) << " seed off by " << scale;
    full += c.fade == 1.0 || model_.rotary_count() == 0;
    if (!u.unchecked_step) continue;
    ++proved;
    ASSERT_TRUE(c.fade == 1.0 || model_.rotary_count() == 0) << "a proved step in the fade band at " << text(nominal);
    // The real tool at q_c where the ideal one is at the answer (4x4 chain, not the solver's).
    const Eigen::Isometry3d real = part_T_tool(model_, Machine::Real, c.joints, L);
    const Eigen::Isometry3d ideal = part_T_tool(model_, Machine::Ideal, u.nominal, L);
    ASSERT_LT((real.translation() - ideal.translation()).norm(), model_.solver.position_tolerance_mm + 1e-12)
        << text(nominal);
  }
  std::printf("%s: %d of %d poses at full correction ended on a proved step\n", GetParam().c_str(), proved, full);
  EXPECT_GT(proved, full / 2);
}

// In the pole fade band, with full corrections as the servo thread keeps them (full_joints of
// the last commands, combined: ~1e-11 to 1e-6 off here), the inverse's full Newton and the
// forward's band solve start next to their answers: the answers are the same (to 1e-9, against
// q_n and the unseeded solves), with fewer Newton steps and corrections. A crude full correction
// (1e-3 off) changes no answer either.
TEST_P(EveryMachine, KeptFullCorrectionsStartTheFadeBandsSolvesNotTheirAnswers) {
  if (model_.rotary_count() == 0) GTEST_SKIP() << "no rotary joints: no fade band";
  std::mt19937_64 rng(26);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), exponent(-11.0, -6.0);
  const double L = model_.tool_length_mm;
  const auto off = [&](const Joints& q, double scale) {
    Joints r = q;
    for (int j = 0; j < r.size(); ++j) r[j] += scale * unit(rng);
    return r;
  };
  int band = 0;
  long forward_without = 0, forward_with = 0, inverse_without = 0, inverse_with = 0;
  for (int tries = 0; band < 200 && tries < 100 * pose_count(); ++tries) {
    const Joints nominal = random_pose(model_, rng);
    const Correction c = correct(model_, nominal, L);
    ASSERT_EQ(c.status, Status::Ok) << text(nominal);
    if (!(c.fade > 0.0 && c.fade < 1.0)) continue;
    ++band;
    // full_joints is the full correction (its own solve, unseeded).
    ASSERT_EQ(c.full_joints.size(), nominal.size()) << text(nominal);
    ASSERT_LT(max_difference(c.full_joints, full_correction(model_, nominal, L, nominal).joints), 1e-9)
        << text(nominal);
    const double scale = std::pow(10.0, exponent(rng));
    const Joints full = off(Joints(c.full_joints - nominal), scale), crude = off(Joints(c.full_joints - nominal), 1e-3);
    // The forward.
    const Joints seed = off(nominal, scale);
    const Uncorrection plain = invert_correction(model_, c.joints, L, 1.0, seed);
    ASSERT_EQ(plain.status, Status::Ok) << text(nominal);
    ASSERT_LT(max_difference(plain.nominal, nominal), 1e-9) << text(nominal);
    forward_without += plain.iterations;
    for (const Joints* d : {&full, &crude}) {
      const Uncorrection u = invert_correction(model_, c.joints, L, 1.0, seed, d);
      ASSERT_EQ(u.status, Status::Ok) << text(nominal);
      ASSERT_LT(max_difference(u.nominal, nominal), 1e-9)
          << text(nominal) << ", D off by " << (d == &full ? scale : 1e-3);
      ASSERT_LT(max_difference(u.nominal, plain.nominal), 1e-9) << text(nominal);
      if (d == &full) forward_with += u.iterations;
    }
    // The inverse: started at the faded answer and the full one, each as far off.
    const Joints faded_seed = off(c.joints, scale), full_seed = nominal + full;
    const Correction bare = correct(model_, nominal, L, faded_seed, nullptr);
    const Correction kept = correct(model_, nominal, L, faded_seed, nullptr, &full_seed);
    ASSERT_EQ(bare.status, Status::Ok) << text(nominal);
    ASSERT_EQ(kept.status, Status::Ok) << text(nominal);
    ASSERT_LT(max_difference(bare.joints, c.joints), 1e-9) << text(nominal);
    ASSERT_LT(max_difference(kept.joints, c.joints), 1e-9) << text(nominal);
    ASSERT_LT(max_difference(kept.full_joints, c.full_joints), 1e-9) << text(nominal);
    inverse_without += bare.iterations;
    inverse_with += kept.iterations;
  }
  std::printf(
      "%s: %d poses in the fade band; forward's steps and corrections %ld -> %ld, inverse's Newton steps "
      "%ld -> %ld with the full corrections kept\n",
      GetParam().c_str(), band, forward_without, forward_with, inverse_without, inverse_with);
  if (band == 0) GTEST_SKIP() << "the tool never comes near a rotary axis line: no fade band";
  EXPECT_GE(band, 50);
  EXPECT_LT(forward_with, forward_without);
  EXPECT_LT(inverse_with, inverse_without);
}

TEST_P(EveryMachine, RefusesWhatIsNotANumber) {
  std::mt19937_64 rng(23);
  const Joints q = random_pose(model_, rng);
  Joints nan = q;
  nan[0] = std::nan("");
  EXPECT_EQ(invert_correction(model_, nan, 100.0, 1.0, q).status, Status::NonFinite);
  EXPECT_EQ(invert_correction(model_, q, 100.0, 1.0, nan).status, Status::NonFinite);
  EXPECT_EQ(invert_correction(model_, q, std::nan(""), 1.0, q).status, Status::NonFinite);
  EXPECT_EQ(invert_correction(model_, q, 100.0, std::nan(""), q).status, Status::NonFinite);
  const Uncorrection off = invert_correction(model_, q, 100.0, 0.0, q);
  EXPECT_EQ(off.status, Status::Ok);
  EXPECT_EQ(off.nominal, q);
}

INSTANTIATE_TEST_SUITE_P(Machines, EveryMachine, ::testing::ValuesIn(machines()),
                         [](const auto& param_info) { return param_info.param; });

// The MC-300's pole is at B = 0 (phi = |B|): a sweep of B through the pole and both fade bands
// (2 to 10 deg), seeded as the servo thread seeds it, with the previous cycle's answer.
TEST(PoleFade, Mc300SweepThroughThePoleAgreesWithTheFixedPoint) {
  const Model model = load_machine(test::machine_path("mc300"));
  const double L = model.tool_length_mm;
  Joints nominal(5);
  nominal << -320.0, -170.0, -140.0, -15.0, 37.0;
  Joints previous = nominal;
  int band = 0, pole = 0;
  for (double b = -15.0; b <= 15.0; b += 0.01) {
    nominal[3] = b;
    nominal[4] += 0.005;
    const Correction c = correct(model, nominal, L);
    ASSERT_EQ(c.status, Status::Ok) << "b = " << b;
    band += c.fade > 0.0 && c.fade < 1.0;
    pole += c.fade == 0.0;
    const Uncorrection u = invert_correction(model, c.joints, L, 1.0, previous);
    ASSERT_EQ(u.status, Status::Ok) << describe(u.status) << " at b = " << b;
    ASSERT_LT(max_difference(u.nominal, nominal), 1e-9) << "b = " << b;
    ASSERT_LT(max_difference(u.nominal, uncorrect(model, c.joints, L).nominal), 1e-9) << "b = " << b;
    previous = u.nominal;
  }
  EXPECT_GT(band, 1500);
  EXPECT_GT(pole, 350);
}

}  // namespace
}  // namespace vc::machine
