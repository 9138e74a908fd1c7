// A session under faults: tests/soak/run_soak.sh runs a headless LinuxCNC on the MC-300 thermal
// configuration (volkins) for VC_SOAK_SECONDS (default 150) with faults injected at random from
// VC_SOAK_SEED (default 1): part programs with tool changes and G43 / G43.1 / G49, MDI between
// them, volkins.enable toggled (moving and at rest), temperature inputs ramped, NaN and out of
// range and back, feed override changes, pause and resume, abort and e-stop in the middle of a
// move, re-homing after each e-stop. Every servo period is recorded (trace.bin); this test
// asserts over all of them (tests/soak/README.md):
// - no NaN in any recorded pin but the two sensor readings the soak makes NaN on purpose;
// - each joint's acceleration (second difference of motor-pos-cmd at the 1 ms period, where
//   motion is enabled) within its [JOINT_n]MAX_ACCELERATION, and the share of volkins' enable
//   ramp in it within 5 % of that, the bound of Mc300Session.TogglingWhileMovingStaysWithinJointLimits;
// - after every homing, at rest, the joints are the core's correction (vc::machine) of the
//   commanded position at the gain, L and filtered temperatures volkins reports, to 1e-9;
// - volkins' temperature filter replicated from the recorded readings, held while faulty, with the
//   fault pin raised then and only then;
// - rtapi_app's VmRSS flat after warm-up (256 kB, see the README);
// - no inverse refused, no error message, every fault kind injected at least once;
// and prints volkins.inverse-time (ns) median, p99 and max, and motion-controller.time.
//
// Long: flock /tmp/vc-linuxcnc.lock env VC_SOAK_SECONDS=3600 VC_SOAK_SEED=7 build/tests/soak_session_test
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "linuxcnc_run.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
using machine::Joints;
using machine::WorldConvention;

const std::string kIni = "kins/configs/mc300/mc300_thermal.ini";  // soak.ini's limits are these
constexpr double kDt = 1e-3;                                      // servo period, s
constexpr int kJoints = 5;

double env_number(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::stod(v) : fallback;
}

struct Event {
  int id;
  double seconds;
  std::string kind, detail;
};

std::vector<Event> read_events(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<Event> events;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string id, seconds, kind, detail;
    std::getline(s, id, ',');
    std::getline(s, seconds, ',');
    std::getline(s, kind, ',');
    std::getline(s, detail);
    events.push_back({std::stoi(id), std::stod(seconds), kind, detail});
  }
  return events;
}

class Soak : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = new machine::Model(machine::load_machine(test::machine_path("mc300_thermal")));
  }
  static void TearDownTestSuite() { delete model_; }
  static machine::Model* model_;
};
machine::Model* Soak::model_ = nullptr;

TEST_F(Soak, ASessionUnderRandomFaultsStaysWithinItsBounds) {
  const double seconds = env_number("VC_SOAK_SECONDS", 150);
  const int seed = static_cast<int>(env_number("VC_SOAK_SEED", 1));
  // VC_SOAK_RUN=DIR: check the outputs of an earlier run_soak.sh DIR (no new session).
  const char* earlier = std::getenv("VC_SOAK_RUN");
  fs::path out;
  std::size_t reported_samples = 0;
  if (earlier && *earlier) {
    out = fs::path(earlier) / "kins/configs/mc300";
  } else {
    const fs::path dir = test::run_folder("soak");
    const test::CommandResult r = test::run_in(dir,
                                               "bash " + test::source_path("tests/soak/run_soak.sh") + " " +
                                                   std::to_string(static_cast<long>(seconds)) + " " +
                                                   (dir / "run").string() + " " + std::to_string(seed),
                                               static_cast<int>(seconds) + 1200);
    ASSERT_EQ(r.exit_code, 0) << r.out;
    std::cout << r.out;
    out = dir / "run/kins/configs/mc300";
  }
  {
    std::ifstream result(out / "result.txt");
    std::string first;
    std::getline(result, first);
    ASSERT_EQ(first.rfind("ok ", 0), 0u) << "the soak did not end cleanly: " << first;
    reported_samples = std::stoul(first.substr(3));
  }

  // The columns and the events.
  std::vector<std::string> names;
  {
    std::ifstream in(out / "trace.columns");
    for (std::string name; std::getline(in, name);)
      if (!name.empty()) names.push_back(name);
  }
  std::map<std::string, std::size_t> col;
  for (std::size_t c = 0; c < names.size(); ++c) col[names[c]] = c;
  const auto at = [&](const std::string& name) {
    const auto it = col.find(name);
    if (it == col.end()) throw std::runtime_error("no column " + name);
    return it->second;
  };
  const std::vector<Event> events = read_events(out / "events.csv");
  std::map<std::string, int> counts;
  std::map<int, std::string> kind_of;
  for (const Event& e : events) {
    ++counts[e.kind];
    kind_of[e.id] = e.kind;
  }

  // Fault kinds: each injected at least once. Enable toggled while moving and at rest, at least
  // one program ran to its end, temperature faults of both kinds came back.
  std::size_t toggles_moving = 0, programs_ended = 0;
  for (const Event& e : events) {
    toggles_moving += e.kind == "enable_toggle" && e.detail.find(" moving ") != std::string::npos;
    programs_ended += e.kind == "program_end";
    if (e.kind != "message") continue;
    // LinuxCNC's messages: none but the note motion gives when it is enabled again after an
    // e-stop with motion.eoffset-limited set (its teleop check flags a world position at or
    // beyond an axis limit: a program may stop at one). The configuration homes inside its
    // limits (volcomp check --ini), so a move right after homing is never refused.
    const bool note = e.detail.find("Note: Motion enabled after reaching a coordinate soft limit") != std::string::npos;
    if (!note) ADD_FAILURE() << "LinuxCNC reported: " << e.detail;
  }
  for (const char* kind : {"program", "mdi", "abort", "estop", "pause", "resume", "enable_toggle", "feed_override",
                           "temperature_nan", "temperature_out_of_range", "temperature_ramp", "temperature_back"})
    EXPECT_GE(counts[kind], 1) << "no " << kind << " injected";
  EXPECT_GE(toggles_moving, 1u) << "volkins.enable never toggled while moving";
  EXPECT_GE(programs_ended, 1u);
  EXPECT_EQ(counts["temperature_back"], counts["temperature_nan"] + counts["temperature_out_of_range"]);
  EXPECT_EQ(counts["homed"], counts["estop"] + 1) << "a homing after every e-stop";
  EXPECT_EQ(counts["rest_check"], counts["homed"]);

  // The joint limits.
  std::array<double, kJoints> a_max{};
  for (int j = 0; j < kJoints; ++j) a_max[j] = test::ini_value(kIni, "JOINT_" + std::to_string(j), "MAX_ACCELERATION");

  // The core's joints and full correction at a sample's filtered temperatures.
  const machine::Model& model = *model_;
  const int coolant = model.temperature_of("coolant"), spindle = model.temperature_of("spindle");
  const std::size_t c_x = at("x"), c_j0 = at("j0"), c_q0 = at("q0"), c_gain = at("gain"), c_L = at("correction_length"),
                    c_tc = at("temperature_coolant"), c_ts = at("temperature_spindle"), c_rc = at("coolant_sensor"),
                    c_rs = at("spindle_sensor"), c_fault = at("temperature_fault"), c_en = at("motion_enabled"),
                    c_event = at("event"), c_event1 = at("event1"), c_inv = at("inverse_time"),
                    c_ctl = at("controller_time"), c_fail = at("failures"), c_tool = at("tool_offset"),
                    c_h0 = at("homed0"), c_eoffset = at("eoffset_limited");
  const auto world_of = [&](const std::vector<double>& row) {
    Joints w(kJoints);
    for (int j = 0; j < kJoints; ++j) w[j] = row[c_x + j];
    return w;
  };
  machine::Conditions conditions = model.reference_conditions();  // the module's filtered temperatures, row by row
  const auto at_temperatures = [&](const std::vector<double>& row) {
    conditions.temperature_degC[static_cast<std::size_t>(coolant)] = row[c_tc];
    conditions.temperature_degC[static_cast<std::size_t>(spindle)] = row[c_ts];
  };
  const auto core_joints = [&](const std::vector<double>& row) {
    at_temperatures(row);
    Joints q;
    machine::Applied applied{row[c_gain], nullptr};
    applied.conditions = &conditions;
    machine::joints_from_world(model, WorldConvention::Axes, world_of(row), row[c_L], applied, q);
    return q;
  };
  const auto full_correction = [&](const std::vector<double>& row) {
    at_temperatures(row);
    Joints full, nominal;
    machine::Applied applied;
    applied.conditions = &conditions;
    machine::joints_from_world(model, WorldConvention::Axes, world_of(row), row[c_L], applied, full);
    machine::nominal_inverse(model, WorldConvention::Axes, world_of(row), row[c_L], nominal);
    return Joints(full - nominal);
  };

  // One pass over the trace, four rows kept.
  std::ifstream bin(out / "trace.bin", std::ios::binary);
  ASSERT_TRUE(bin) << "no trace";
  const std::size_t width = names.size();
  std::deque<std::vector<double>> last;  // newest at the back
  std::size_t samples = 0, nan_values = 0, sensor_nan = 0, excluded = 0, event_mismatch = 0, tool_changes = 0;
  std::size_t eoffset_limited = 0, faulty_samples = 0, filter_mismatch = 0, fault_pin_mismatch = 0, ramping = 0,
              failures = 0;
  std::array<double, kJoints> a_peak{}, a_ramp{};
  std::array<std::size_t, kJoints> a_at{};
  std::vector<std::int32_t> inverse_ns, controller_ticks;
  // Rest windows (between rest_check and rest_end, after every homing).
  std::size_t rest_windows = 0, rest_samples = 0, rest_not_still = 0;
  double rest_worst = 0;
  std::vector<Joints> rest_expected;  // the core's joints of the window's samples so far
  const double tau = 0.5;             // soak_thermal.hal's volkins.temperature-time-constant
  const auto valid = [&](int input, double reading) {
    const machine::TemperatureInput& in = model_->temperatures[static_cast<std::size_t>(input)];
    return std::isfinite(reading) && reading >= in.min_degC && reading <= in.max_degC;
  };
  std::vector<double> row(width);
  while (bin.read(reinterpret_cast<char*>(row.data()), static_cast<std::streamsize>(width * sizeof(double)))) {
    ++samples;
    for (std::size_t c = 0; c < width; ++c) {
      if (!std::isnan(row[c])) continue;
      if (c == c_rc || c == c_rs) {
        ++sensor_nan;  // injected on purpose
      } else if (nan_values++ < 10) {
        ADD_FAILURE() << "NaN in " << names[c] << " at sample " << samples - 1;
      }
    }
    eoffset_limited += row[c_eoffset] == 1.0;
    failures = std::max(failures, static_cast<std::size_t>(std::max(0.0, row[c_fail])));
    if (row[c_en] == 1.0) {
      inverse_ns.push_back(static_cast<std::int32_t>(row[c_inv]));
      controller_ticks.push_back(static_cast<std::int32_t>(row[c_ctl]));
    }
    last.push_back(row);
    if (last.size() > 4) last.pop_front();
    if (last.size() < 2) continue;
    const std::vector<double>& now = last[last.size() - 1];
    const std::vector<double>& before = last[last.size() - 2];
    tool_changes += now[c_tool] != before[c_tool];
    // The event marker in both channels (they may differ in one period: the driver set it between
    // the two samplers' functions).
    event_mismatch += now[c_event] != now[c_event1] && before[c_event] != before[c_event1];

    // volkins' temperature filter, replicated.
    {
      const bool bad_c = !valid(coolant, now[c_rc]), bad_s = !valid(spindle, now[c_rs]);
      faulty_samples += bad_c || bad_s;
      const auto next = [&](double previous, bool bad, double reading) {
        return bad ? previous : previous + (reading - previous) * kDt / (tau + kDt);
      };
      filter_mismatch += std::abs(now[c_tc] - next(before[c_tc], bad_c, now[c_rc])) > 1e-12 ||
                         std::abs(now[c_ts] - next(before[c_ts], bad_s, now[c_rs])) > 1e-12;
      fault_pin_mismatch += now[c_fault] != ((bad_c || bad_s) ? 1.0 : 0.0);
    }

    // Rest windows: the core's joints, LinuxCNC's interpolation of them, against joint.N.pos-cmd.
    const int event = static_cast<int>(now[c_event]);
    if (kind_of.count(event) && kind_of[event] == "rest_check") {
      if (static_cast<int>(before[c_event]) != event) {
        ++rest_windows;
        rest_expected.clear();
      }
      rest_expected.push_back(core_joints(now));
      bool still = now[c_en] == 1.0;
      for (int j = 0; j < kJoints; ++j) still = still && now[c_x + j] == before[c_x + j] && now[c_h0 + j] == 1.0;
      rest_not_still += !still;
      const std::size_t n = rest_expected.size();
      if (n >= 4) {
        const Joints expected = (rest_expected[n - 4] + 4.0 * rest_expected[n - 3] + rest_expected[n - 2]) / 6.0;
        double worst = 0;
        for (int j = 0; j < kJoints; ++j) worst = std::max(worst, std::abs(now[c_q0 + j] - expected[j]));
        rest_worst = std::max(rest_worst, worst);
        ++rest_samples;
      }
    }

    if (last.size() < 3) continue;
    // Acceleration at the middle sample of the last three, where motion is enabled at all three
    // (an e-stop stops the commands in one period, as it stops a real machine's drives).
    const std::vector<double>& mid = last[last.size() - 2];
    const std::vector<double>& first = last[last.size() - 3];
    if (first[c_en] != 1.0 || mid[c_en] != 1.0 || now[c_en] != 1.0) {
      ++excluded;
      continue;
    }
    for (int j = 0; j < kJoints; ++j) {
      const double a = std::abs(now[c_j0 + j] - 2 * mid[c_j0 + j] + first[c_j0 + j]) / (kDt * kDt);
      if (a > a_peak[j]) {
        a_peak[j] = a;
        a_at[j] = samples - 2;
      }
    }
    // The enable ramp's share (TogglingWhileMovingStaysWithinJointLimits): cycle k outputs
    // n_k + g_k D_k; the ramp adds (g_k+1 - g_k) D_k+1 + (g_k-1 - g_k) D_k-1 to the second difference.
    if (now[c_gain] != mid[c_gain] || first[c_gain] != mid[c_gain]) {
      ++ramping;
      const Joints d_next = full_correction(now), d_prev = full_correction(first);
      for (int j = 0; j < kJoints; ++j)
        a_ramp[j] = std::max(
            a_ramp[j], std::abs((now[c_gain] - mid[c_gain]) * d_next[j] + (first[c_gain] - mid[c_gain]) * d_prev[j]) /
                           (kDt * kDt));
    }
  }
  ASSERT_EQ(samples, reported_samples) << "the trace is not what the driver wrote";
  if (!(earlier && *earlier)) {
    ASSERT_GT(samples, static_cast<std::size_t>(seconds * 1000 * 0.9)) << "the trace is short";
  }

  if (counts["message"] > 0) {
    EXPECT_GT(eoffset_limited, 0u) << "motion's note came without motion.eoffset-limited set";
  }
  EXPECT_EQ(nan_values, 0u);
  EXPECT_GT(sensor_nan, 0u) << "no NaN reading was injected";
  EXPECT_EQ(event_mismatch, 0u) << "the two sampler channels are out of step";
  EXPECT_EQ(failures, 0u) << "volkins refused kinematics calls";
  EXPECT_EQ(filter_mismatch, 0u) << "the temperature filter is not what volkins documents";
  EXPECT_EQ(fault_pin_mismatch, 0u) << "volkins.temperature-fault is not raised exactly while a reading is faulty";
  EXPECT_GT(faulty_samples, 100u);
  EXPECT_GT(ramping, 1000u) << "the enable ramp ran too little";
  EXPECT_GE(tool_changes, 5u) << "too few tool length changes (G43, G43.1, G49)";
  for (int j = 0; j < kJoints; ++j) {
    // The homing's move to HOME accelerates at exactly the limit: the second difference adds
    // float noise to it.
    EXPECT_LE(a_peak[j], a_max[j] * (1 + 1e-6)) << "joint " << j << " at sample " << a_at[j];
    EXPECT_LE(a_ramp[j], 0.05 * a_max[j]) << "joint " << j << ": the enable ramp's share";
  }
  EXPECT_EQ(rest_windows, static_cast<std::size_t>(counts["rest_check"])) << "a rest window is missing in the trace";
  EXPECT_GT(rest_samples, 300u * rest_windows);
  EXPECT_EQ(rest_not_still, 0u) << "the machine moved in a rest window";
  EXPECT_LT(rest_worst, 1e-9) << "after a homing, at rest, the joints are not the core's";

  // Memory: VmRSS of rtapi_app after a 10 s warm-up (first programs, first homing done).
  std::vector<std::pair<double, long>> memory;
  {
    std::ifstream in(out / "memory.csv");
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::stringstream s(line);
      std::string t, n, kb;
      std::getline(s, t, ',');
      std::getline(s, n, ',');
      std::getline(s, kb);
      memory.emplace_back(std::stod(t), std::stol(kb));
    }
  }
  ASSERT_GE(memory.size(), 5u);
  long warm = -1, peak = 0, final_kb = memory.back().second;
  for (const auto& [t, kb] : memory) {
    if (t < 10.0) continue;
    if (warm < 0) warm = kb;
    peak = std::max(peak, kb);
  }
  ASSERT_GT(warm, 0);
  const long memory_tolerance_kb = 256;
  EXPECT_LE(peak - warm, memory_tolerance_kb) << "rtapi_app's VmRSS grew";

  // Time of volkins' inverse per servo cycle (volkins.inverse-time, ns) and motion-controller's.
  const auto percentile = [](std::vector<std::int32_t> v, double p) {
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
  };
  ASSERT_GT(inverse_ns.size(), 1000u);
  const std::int32_t inv_median = percentile(inverse_ns, 0.5), inv_p99 = percentile(inverse_ns, 0.99),
                     inv_max = percentile(inverse_ns, 1.0);
  EXPECT_GT(inv_median, 0) << "volkins.inverse-time is not recorded";
  EXPECT_LT(inv_median, 50000) << "the inverse's median takes 5 % of the servo period";

  std::cout << "soak: " << samples << " servo periods (" << samples / 1000.0 << " s), seed "
            << (earlier && *earlier ? std::string("of the earlier run") : std::to_string(seed)) << "\n  events:";
  for (const auto& [kind, n] : counts) std::cout << " " << kind << "=" << n;
  std::cout << "\n  enable toggled while moving " << toggles_moving << ", tool length changes " << tool_changes
            << ", faulty temperature samples " << faulty_samples << " (NaN readings " << sensor_nan
            << "), enable-ramp samples " << ramping << ", samples left out of the acceleration check (motion disabled) "
            << excluded << ", motion.eoffset-limited set in " << eoffset_limited
            << " samples\n  NaN in recorded pins (sensor readings excepted): " << nan_values << "\n";
  for (int j = 0; j < kJoints; ++j)
    std::cout << "  joint " << j << ": max |acceleration| " << a_peak[j] << " (bound " << a_max[j]
              << "), the enable ramp's share " << a_ramp[j] << " (bound " << 0.05 * a_max[j] << ")\n";
  std::cout << "  rest windows after homing: " << rest_windows << " (" << rest_samples
            << " samples), joints against the core max " << rest_worst << "\n  rtapi_app VmRSS: start "
            << memory.front().second << " kB, after warm-up " << warm << " kB, peak after warm-up " << peak
            << " kB, end " << final_kb << " kB (tolerance " << memory_tolerance_kb
            << " kB)\n  volkins.inverse-time: median " << inv_median << " ns, p99 " << inv_p99 << " ns, max " << inv_max
            << " ns; motion-controller.time (ticks): median " << percentile(controller_ticks, 0.5) << ", p99 "
            << percentile(controller_ticks, 0.99) << ", max " << percentile(controller_ticks, 1.0) << "\n";
}

}  // namespace
}  // namespace vc
