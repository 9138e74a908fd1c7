// Cost per pose of the volumetric error, the correction, its fixed-point inverse (uncorrect),
// the forward kinematics and one servo cycle's pair of kinematics calls on each shipped machine
// (MC-300: all 41 deviations), over 4096 random poses in the travel, cycled.
// Run: build/tests/bench/correction_benchmark --benchmark_repetitions=5
// The percentile counters time each call separately (steady_clock), since the servo thread's
// budget is set by the slowest cycle.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <cmath>
#include <random>

#include "test_support.hpp"
#include "vc/machine/contraction_bound.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/machine/term_types.hpp"

namespace vc::machine {
namespace {

// The servo thread's view of pose i: the world position one and two cycles before (a step of
// at most 0.1 mm and 0.06 deg per joint: 100 mm/s and 60 deg/s at 1 kHz), the joints the
// previous cycle's inverse gave, and the seeds volkins keeps: the correction the previous
// cycle applied (the forward's) and its quadratic extrapolation from the three before (the
// inverse's).
struct ServoCycle {
  Joints world, before, before_before;  // nominal joints (world = axes)
  Joints previous_joints;               // joints_from_world(before)
  Joints previous_correction;           // previous_joints - before
  Joints extrapolated_correction;       // from the corrections at world - k step, k = 1, 2, 3
  Joints feedback;                      // the joints the forward reads (empty: previous_joints)
  Joints feedback_correction;           // with feedback: the forward's seed, the same combination
                                        // of the corrections (volkins' way point)
  // The same two combinations of the full corrections (no pole fade), where volkins keeps them
  // (the contour; empty: none).
  Joints extrapolated_full, feedback_full;
};

struct Fixture {
  Model model;
  std::vector<Joints> poses;
  std::vector<Joints> corrected;
  std::vector<ServoCycle> cycles;
  ContractionBound bound;  // as volkins samples it at load
};

const Fixture& fixture(const std::string& name) {
  static std::map<std::string, Fixture> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  Model model = load_machine(test::machine_path(name));
  ContractionBound bound(model, {0.0, 100.0, 200.0, 300.0, 400.0, 500.0}, true);
  Fixture f{std::move(model), {}, {}, {}, std::move(bound)};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < 4096; ++k) {
    Joints q(f.model.joint_count()), step(f.model.joint_count());
    for (int j = 0; j < f.model.joint_count(); ++j) {
      q[j] = std::uniform_real_distribution<double>(f.model.axes[j].travel_min, f.model.axes[j].travel_max)(rng);
      step[j] = unit(rng) * (f.model.axes[j].type == AxisType::Linear ? 0.1 : 0.06);
    }
    f.poses.push_back(q);
    f.corrected.push_back(correct(f.model, q, f.model.tool_length_mm).joints);
    ServoCycle c{q, q - step, q - 2 * step, {}, {}, {}, {}, {}, {}, {}};
    joints_from_world(f.model, WorldConvention::Axes, c.before, f.model.tool_length_mm, c.previous_joints);
    c.previous_correction = c.previous_joints - c.before;
    const auto correction_at = [&](const Joints& nominal) {
      Joints joints;
      joints_from_world(f.model, WorldConvention::Axes, nominal, f.model.tool_length_mm, joints);
      return Joints(joints - nominal);
    };
    c.extrapolated_correction =
        3 * (c.previous_correction - correction_at(c.before_before)) + correction_at(q - 3 * step);
    f.cycles.push_back(c);
  }
  return cache.emplace(name, std::move(f)).first->second;
}

// The MC-300's servo cycles along the 5-axis contour of kins/configs/mc300/nc/contour_5axis.ngc
// (what servo_cost.sh runs in LinuxCNC): a 60 mm circle round X-360 Y-160 while Z dips 40 mm,
// B tilts to -60 and back (through the pole fade band at both ends) and C turns once, at
// F4000 (66.7 mm/s: 0.0637 deg of the circle per 1 ms cycle), seeded as volkins seeds them.
// The forward reads what LinuxCNC feeds back in a simulated loop: the joint command of the
// cubic interpolator (cubic.c, one point per servo period), its way point
// (q(k-3) + 4 q(k-2) + q(k-1)) / 6 of the inverse's outputs, not the last of them; volkins
// starts its forward at that way point less the same combination of the corrections it kept.
std::vector<ServoCycle> contour_cycles(const Model& model) {
  constexpr double kStepDeg = 4000.0 / 60.0 / 60.0 * 1e-3 / (3.14159265358979323846 / 180.0);
  const int n = static_cast<int>(360.0 / kStepDeg);
  std::vector<Joints> points, corrections, full;  // full: none at the pole (empty)
  for (int i = 0; i < n; ++i) {
    const double theta = i * kStepDeg, rad = theta * 3.14159265358979323846 / 180.0;
    Joints p(5), joints;
    p << -360.0 + 60.0 * std::cos(rad), -160.0 + 60.0 * std::sin(rad), -200.0 - 40.0 * std::sin(rad / 2),
        -60.0 * std::sin(rad / 2), theta;
    Correction report;
    joints_from_world(model, WorldConvention::Axes, p, model.tool_length_mm, joints, &report);
    points.push_back(p);
    corrections.push_back(joints - p);
    full.push_back(report.full_joints.size() ? Joints(report.full_joints - p)
                   : report.fade == 1.0      ? Joints(joints - p)
                                             : Joints());
  }
  std::vector<ServoCycle> cycles;
  const auto command = [&](int k) { return Joints(points[k] + corrections[k]); };
  const auto kept = [&](int from, int to) {  // volkins keeps full corrections since the pole
    for (int k = from; k <= to; ++k)
      if (full[k].size() == 0) return false;
    return true;
  };
  for (int i = 4; i < n; ++i)
    cycles.push_back({points[i], points[i - 1], points[i - 2], command(i - 1), corrections[i - 1],
                      3 * (corrections[i - 1] - corrections[i - 2]) + corrections[i - 3],
                      (command(i - 4) + 4 * command(i - 3) + command(i - 2)) / 6.0,
                      (corrections[i - 4] + 4 * corrections[i - 3] + corrections[i - 2]) / 6.0,
                      kept(i - 3, i - 1) ? Joints(3 * (full[i - 1] - full[i - 2]) + full[i - 3]) : Joints(),
                      kept(i - 4, i - 2) ? Joints((full[i - 4] + 4 * full[i - 3] + full[i - 2]) / 6.0) : Joints()});
  return cycles;
}

const std::vector<ServoCycle>& contour_of(const std::string& machine) {
  static std::map<std::string, std::vector<ServoCycle>> cache;
  auto it = cache.find(machine);
  if (it == cache.end()) it = cache.emplace(machine, contour_cycles(fixture(machine).model)).first;
  return it->second;
}

template <typename Call>
void run(benchmark::State& state, const std::string& machine, Call call, std::size_t count = 0) {
  const Fixture& f = fixture(machine);
  if (count == 0) count = f.poses.size();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(call(f, i));
    i = (i + 1) % count;
  }
  // Median, 99th and 99.9th percentile and worst of single calls over one pass through the poses.
  std::vector<double> ns;
  for (std::size_t k = 0; k < count; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(call(f, k));
    ns.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ns.begin(), ns.end());
  state.counters["median_ns"] = ns[ns.size() / 2];
  state.counters["p99_ns"] = ns[ns.size() * 99 / 100];
  state.counters["p999_ns"] = ns[ns.size() * 999 / 1000];
  state.counters["max_ns"] = ns.back();
}

void BM_VolumetricError(benchmark::State& state, const std::string& machine) {
  run(state, machine, [](const Fixture& f, std::size_t i) {
    return volumetric_error(f.model, f.poses[i], f.model.tool_length_mm).position_mm.x();
  });
}

// The pieces of a correction: one chain walk of the real machine, and of the ideal one with
// the derivatives that give Newton its Jacobian.
void BM_RealPose(benchmark::State& state, const std::string& machine) {
  run(state, machine, [](const Fixture& f, std::size_t i) {
    return tool_pose(f.model, Machine::Real, f.poses[i], f.model.tool_length_mm).tip_mm.x();
  });
}

void BM_IdealPoseDerivatives(benchmark::State& state, const std::string& machine) {
  run(state, machine, [](const Fixture& f, std::size_t i) {
    PoseDerivatives d;
    return tool_pose(f.model, Machine::Ideal, f.poses[i], f.model.tool_length_mm, d).tip_mm.x() + d.tip(0, 0);
  });
}

void BM_Correct(benchmark::State& state, const std::string& machine) {
  run(state, machine,
      [](const Fixture& f, std::size_t i) { return correct(f.model, f.poses[i], f.model.tool_length_mm).joints[0]; });
}

// The servo thread seeds with the previous cycle's solution, a few micrometres away.
void BM_CorrectSeeded(benchmark::State& state, const std::string& machine) {
  run(state, machine, [](const Fixture& f, std::size_t i) {
    return correct(f.model, f.poses[i], f.model.tool_length_mm, f.corrected[i]).joints[0];
  });
}

void BM_Uncorrect(benchmark::State& state, const std::string& machine) {
  run(state, machine, [](const Fixture& f, std::size_t i) {
    return uncorrect(f.model, f.corrected[i], f.model.tool_length_mm).nominal[0];
  });
}

// The forward as volkins calls it (invert_correction: Newton on the real pose) of the joints
// the last inverse commanded, seeded with the previous cycle's world position and the last
// correction.
void BM_ForwardSeeded(benchmark::State& state, const std::string& machine) {
  run(state, machine, [](const Fixture& f, std::size_t i) {
    const ServoCycle& c = f.cycles[i];
    Joints world;
    world_from_joints(f.model, WorldConvention::Axes, c.previous_joints, f.model.tool_length_mm,
                      Applied{1.0, &c.before_before, &c.previous_correction}, world);
    return world[0];
  });
}

// One servo cycle's kinematics as motion-controller calls them (control.c: the forward of the
// joint feedback, seeded with the previous world position, then the inverse of the new
// command, seeded with the previous joints) and as volkins seeds them (with the corrections
// it keeps) and stops them (the inverse's last step unchecked where the contraction bound
// proves it): the pair the 2.5 us target is for. Without `correction_seeds`, the seeds
// LinuxCNC gives alone (volkins before it kept corrections); without `bound`, every step
// checked (volkins before the bound).
double servo_pair(const Fixture& f, const ServoCycle& c, bool correction_seeds, bool bound,
                  const Conditions* conditions = nullptr) {
  const double L = f.model.tool_length_mm;
  const Joints* forward_seed = !correction_seeds   ? nullptr
                               : c.feedback.size() ? &c.feedback_correction
                                                   : &c.previous_correction;
  const Joints* inverse_seed = correction_seeds ? &c.extrapolated_correction : nullptr;
  const auto full = [correction_seeds](const Joints& kept) {
    return correction_seeds && kept.size() ? &kept : nullptr;
  };
  Joints world, joints;
  const Applied forward{1.0,       &c.before_before,      forward_seed,
                        nullptr,   full(c.feedback_full), std::numeric_limits<double>::quiet_NaN(),
                        conditions};
  world_from_joints(f.model, WorldConvention::Axes, c.feedback.size() ? c.feedback : c.previous_joints, L, forward,
                    world);
  const Applied inverse{1.0,
                        &c.previous_joints,
                        inverse_seed,
                        bound ? &f.bound : nullptr,
                        full(c.extrapolated_full),
                        std::numeric_limits<double>::quiet_NaN(),
                        conditions};
  joints_from_world(f.model, WorldConvention::Axes, c.world, L, inverse, joints);
  return world[0] + joints[0];
}

void BM_ServoCycle(benchmark::State& state, const std::string& machine, bool correction_seeds, bool bound,
                   bool contour = false) {
  static const std::vector<ServoCycle> none;
  const std::vector<ServoCycle>& along_contour = contour ? contour_of(machine) : none;
  run(
      state, machine,
      [correction_seeds, bound, contour, &along_contour](const Fixture& f, std::size_t i) {
        return servo_pair(f, contour ? along_contour[i] : f.cycles[i], correction_seeds, bound);
      },
      contour ? along_contour.size() : 0);
}

// The pair with L-ANG and R-POR switched off (volkins.type.*.enable 0, ramped to 0): every
// term scaled by its type's gain, every step evaluated (the contraction bound holds for the
// whole model only), seeded with the whole model's corrections as in the cycles after a switch.
void BM_ServoCycleTypesOff(benchmark::State& state, const std::string& machine) {
  static Conditions off;
  off = fixture(machine).model.reference_conditions();
  off.type_gain[static_cast<std::size_t>(BasicType::LAng)] = 0.0;
  off.type_gain[static_cast<std::size_t>(BasicType::RPor)] = 0.0;
  run(state, machine, [](const Fixture& f, std::size_t i) { return servo_pair(f, f.cycles[i], true, false, &off); });
}

// The same pair along the contour with cold caches: before each call a buffer larger than the
// last-level cache is written, as other threads and processes do between two servo cycles (in
// LinuxCNC the module's cost lies between this and the hot one: the caches are partly warm).
// What it measures is the footprint: the model's data, the code and the stack a cycle touches.
void BM_ServoCycleColdCaches(benchmark::State& state, const std::string& machine) {
  const Fixture& f = fixture(machine);
  const std::vector<ServoCycle>& cycles = contour_of(machine);
  static std::vector<char> other(64 << 20, 1);
  std::size_t i = 0;
  std::vector<double> ns;
  for (auto _ : state) {
    for (std::size_t k = 0; k < other.size(); k += 64) ++other[k];
    const ServoCycle& c = cycles[i];
    i = (i + 97) % cycles.size();  // spread over the contour
    const auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(servo_pair(f, c, true, true));
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(elapsed);
    ns.push_back(elapsed * 1e9);
  }
  std::sort(ns.begin(), ns.end());
  state.counters["median_ns"] = ns[ns.size() / 2];
  state.counters["p99_ns"] = ns[ns.size() * 99 / 100];
}

BENCHMARK_CAPTURE(BM_VolumetricError, mc300, std::string("mc300"));
BENCHMARK_CAPTURE(BM_RealPose, mc300, std::string("mc300"));
BENCHMARK_CAPTURE(BM_IdealPoseDerivatives, mc300, std::string("mc300"));
BENCHMARK_CAPTURE(BM_Correct, mc300, std::string("mc300"));
BENCHMARK_CAPTURE(BM_CorrectSeeded, mc300, std::string("mc300"));
BENCHMARK_CAPTURE(BM_Uncorrect, mc300, std::string("mc300"));
BENCHMARK_CAPTURE(BM_ForwardSeeded, mc300, std::string("mc300"));
BENCHMARK_CAPTURE(BM_ServoCycle, mc300, std::string("mc300"), true, true);
BENCHMARK_CAPTURE(BM_ServoCycle, mc300_every_step_checked, std::string("mc300"), true, false);
BENCHMARK_CAPTURE(BM_ServoCycle, mc300_joint_seeds, std::string("mc300"), false, false);
BENCHMARK_CAPTURE(BM_ServoCycle, mc300_contour, std::string("mc300"), true, true, true);
BENCHMARK_CAPTURE(BM_ServoCycle, mc300_contour_every_step_checked, std::string("mc300"), true, false, true);
BENCHMARK_CAPTURE(BM_ServoCycleTypesOff, mc300, std::string("mc300"));
BENCHMARK_CAPTURE(BM_ServoCycleColdCaches, mc300_contour, std::string("mc300"))->UseManualTime()->Iterations(1000);
BENCHMARK_CAPTURE(BM_ServoCycle, ac_trunnion, std::string("ac_trunnion"), true, true);
BENCHMARK_CAPTURE(BM_Correct, mill3, std::string("mill3"));
BENCHMARK_CAPTURE(BM_Correct, ac_trunnion, std::string("ac_trunnion"));

}  // namespace
}  // namespace vc::machine

BENCHMARK_MAIN();
