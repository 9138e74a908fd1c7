// The real-time functions allocate nothing: malloc is counted (Eigen allocates through
// malloc, std containers through operator new, which ends in malloc on glibc) around calls of
// every function the servo thread will use, on every shipped machine.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <random>

#include "test_support.hpp"
#include "vc/machine/contraction_bound.hpp"
#include "vc/machine/held_rotary.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"
#ifdef VC_HAVE_KINS
#include <chrono>
#include <thread>

#include "reload_worker.hpp"
#endif

extern "C" void* __libc_malloc(std::size_t size);

namespace {
// Counted in the thread that set it only (the servo thread's calls; volkins' reload worker,
// another thread, allocates by design).
thread_local bool counting = false;
std::atomic<long> allocations{0};
}  // namespace

// Interposes glibc's malloc for this test program only.
extern "C" void* malloc(std::size_t size) {
  if (counting) allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}

namespace vc::machine {
namespace {

class NoAllocation : public ::testing::TestWithParam<std::string> {};

TEST_P(NoAllocation, RealTimeFunctionsNeverCallMalloc) {
  const Model model = load_machine(test::machine_path(GetParam()));
  Conditions at = model.reference_conditions();  // as volkins keeps them: the temperatures set
  for (std::size_t i = 0; i < model.temperatures.size(); ++i)
    at.temperature_degC[i] = 0.5 * (model.temperatures[i].min_degC + model.temperatures[i].max_degC);
  // Some compensation types off or on their way (volkins.type.*: the scaled terms' paths).
  Conditions switched = at;
  for (std::size_t t = 0; t < switched.type_gain.size(); ++t) switched.type_gain[t] = t % 3 == 0 ? 0.0 : 0.5;
  switched.fade.orientation = 0.5;
  std::mt19937_64 rng(7);
  std::vector<Joints> poses;
  for (int k = 0; k < 500; ++k) {
    Joints q(model.joint_count());
    for (int j = 0; j < model.joint_count(); ++j)
      q[j] = std::uniform_real_distribution<double>(model.axes[j].travel_min, model.axes[j].travel_max)(rng);
    poses.push_back(q);
    // The tilting axis (the first rotary one) at 6 deg: the pole fade band on the MC-300 and the
    // AC trunnion, whose solves take other paths.
    for (int j = 0; j < model.joint_count(); ++j)
      if (model.axes[j].type == AxisType::Rotary) {
        q[j] = 6.0;
        poses.push_back(q);
        break;
      }
  }
  const double L = model.tool_length_mm;
  const ContractionBound bound(model, {0.0, 2.0 * L}, true);  // as volkins builds it at load
  double sink = 0.0;
  allocations = 0;
  counting = true;
  for (const Joints& q : poses) {
    sink += volumetric_error(model, at, q, L).position_mm.norm();
    sink += volumetric_error(model, q, L).position_mm.norm();  // (at the file's conditions)
    const Correction c = correct(model, at, q, L);
    sink += c.residual_mm;
    sink += uncorrect(model, at, c.joints, L, 1.0, c.joints).nominal.sum();
    const Correction s = correct(model, switched, q, L);
    sink += s.residual_mm + uncorrect(model, switched, s.joints, L, 1.0, s.joints).nominal.sum();
    sink += volumetric_error(model, switched, q, L).position_mm.norm();
    for (WorldConvention w : {WorldConvention::Axes, WorldConvention::Tcp}) {
      Joints joints, world;
      sink += static_cast<double>(joints_from_world(model, w, q, L, joints));
      sink += static_cast<double>(world_from_joints(model, w, joints, L, world));
      // The module's calls: seeded, part of the correction.
      Applied inverse{0.5, &joints}, forward{0.5, &world};
      inverse.conditions = forward.conditions = &at;
      sink += static_cast<double>(joints_from_world(model, w, q, L, inverse, joints));
      const Joints correction = c.joints - q;
      Applied bounded{1.0, &joints, &correction, &bound};  // the unchecked step's path
      bounded.conditions = &at;
      sink += static_cast<double>(joints_from_world(model, w, q, L, bounded, joints));
      sink += static_cast<double>(world_from_joints(model, w, joints, L, forward, world));
      // With the full corrections volkins keeps (the fade band's seeds).
      const Joints full = (c.full_joints.size() ? c.full_joints : c.joints) - q;
      Applied kept_inverse{1.0, &joints, &correction, &bound, &full},
          kept_forward{1.0, &world, &correction, nullptr, &full};
      kept_inverse.conditions = kept_forward.conditions = &at;
      sink += static_cast<double>(joints_from_world(model, w, q, L, kept_inverse, joints));
      sink += static_cast<double>(world_from_joints(model, w, joints, L, kept_forward, world));
      sink += outside_tables(model, joints);
      // A clamped rotary joint (held_rotary.hpp): the held path.
      HeldRotary held;
      for (int j = 0; j < model.joint_count(); ++j)
        if (model.axes[j].type == AxisType::Rotary) {
          held.offset_deg[j] = 0.003;
          held.release[j] = 0.0;
          break;
        }
      Applied held_inverse{1.0, &joints}, held_forward{1.0, &world};
      held_inverse.held = held_forward.held = &held;
      sink += static_cast<double>(joints_from_world(model, w, q, L, held_inverse, joints));
      sink += static_cast<double>(world_from_joints(model, w, joints, L, held_forward, world));
      Applied switched_inverse{1.0, &joints}, switched_forward{1.0, &world};
      switched_inverse.conditions = switched_forward.conditions = &switched;
      sink += static_cast<double>(joints_from_world(model, w, q, L, switched_inverse, joints));
      sink += static_cast<double>(world_from_joints(model, w, joints, L, switched_forward, world));
    }
  }
  counting = false;
  EXPECT_EQ(allocations.load(), 0) << "allocations in the real-time path";
  int band = 0;
  for (const Joints& q : poses) band += correct(model, at, q, L).full_joints.size() > 0;
  if (GetParam() == "mc300") {
    EXPECT_GT(band, 100) << "the fade band's paths were not taken";
  }
  EXPECT_TRUE(std::isfinite(sink));
}

#ifdef VC_HAVE_KINS
// volkins.update's reload step (ReloadSequence::step) with a reload pending, through every
// state: requested, the worker reading (another thread, which allocates), ready, ramped out,
// swapped, ramped in; then a request while moving, given back. The servo thread's calls allocate
// nothing.
TEST(NoAllocation, ReloadStepsWithAReloadPending) {
  const std::string mill3 = test::machine_path("mill3");
  const auto build = [mill3] {
    return std::make_unique<kins::ModuleSettings>(kins::settings_from_parameters(mill3.c_str(), nullptr, nullptr));
  };
  const kins::ModuleSettings* settings = build().release();
  std::vector<std::string> messages;  // the worker's thread only, read after it is joined
  std::vector<int> states;
  {
    kins::ReloadWorker worker(
        settings, build, [](const Model&) { return 0x1234u; },
        [&messages](const std::string& m) { messages.push_back(m); }, 1);
    kins::ReloadSequence sequence;
    const kins::GainRamp enable{1.0, 0.0};
    const auto run = [&](bool moving, int periods_at_most) {
      for (int k = 0; k < periods_at_most; ++k) {
        counting = true;
        sequence.step(worker, settings, k > 0, moving, false, enable, 1e-3, 0.05);
        counting = false;
        if (states.empty() || states.back() != sequence.state) states.push_back(sequence.state);
        if (k > 0 && sequence.state == kins::kReloadIdle) return;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    };
    allocations = 0;
    run(false, 100000);
    EXPECT_EQ(sequence.reloads, 1);
    EXPECT_EQ(sequence.checksum, 0x1234u);
    while (worker.stage() != kins::ReloadStage::Idle) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    run(true, 100000);  // a request while moving: refused
    EXPECT_TRUE(sequence.failed);
    EXPECT_EQ(sequence.reloads, 1);
    EXPECT_EQ(allocations.load(), 0) << "allocations in the servo thread's reload step";
    // The worker deletes the replaced settings; the running ones are the caller's.
    while (worker.stage() != kins::ReloadStage::Idle) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  delete settings;
  EXPECT_EQ(states, (std::vector<int>{0, 1, 2, 3, 0, 1, 0}));
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0], "reload refused while an axis moves: reload at rest, e.g. M100 after the moves");
}
#endif

// The counter works: an allocation while counting is seen.
TEST(NoAllocationGuard, SeesAnAllocation) {
  allocations = 0;
  counting = true;
  auto* p = new std::vector<double>(100);
  counting = false;
  delete p;
  EXPECT_GE(allocations.load(), 1);
}

INSTANTIATE_TEST_SUITE_P(Shipped, NoAllocation, ::testing::ValuesIn(test::shipped_machines()),
                         [](const auto& param_info) { return param_info.param; });
// Tables over temperature inputs (the example, not a shipped machine: see machines/data).
INSTANTIATE_TEST_SUITE_P(Example, NoAllocation, ::testing::Values(std::string("mc300_thermal")),
                         [](const auto& param_info) { return param_info.param; });

}  // namespace
}  // namespace vc::machine
