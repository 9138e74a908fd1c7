#include "vc/init/joint_room.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>

#include "vc/init/number.hpp"
#include "vc/machine/correct.hpp"

namespace vc::init {
namespace {

constexpr int kLevels = 5;  // sample positions per joint over its axis's limits

// A value rounded for a message (6 decimals, no "-0").
std::string rounded(double v) { return format_number(std::round(v * 1e6) / 1e6); }

}  // namespace

JointRoomCheck check_joint_room(const LinuxcncIni& ini, const machine::Model& model, const VolkinsParameters& volkins) {
  const int n = model.joint_count();
  const auto rotary = [&](int j) { return model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Rotary; };
  // The INI's length in mm (the rotary axes' deg as they are).
  const auto to_mm = [&](int j, double v) { return rotary(j) || no_limit(v) ? v : volkins.units.to_mm(v); };
  JointRoomCheck check;
  std::vector<int> model_joint;  // of each JointRoom
  const std::string coordinates = volkins.coordinates.empty() ? model.coordinates() : volkins.coordinates;
  for (std::size_t i = 0; i < coordinates.size(); ++i) {
    const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(coordinates[i])));
    const int j = model.joint_of(letter);
    if (j < 0) continue;  // a tool-axis coordinate (5axiskins' W): passed through
    JointRoom r;
    r.letter = letter;
    r.joint = static_cast<int>(i);
    const std::string section = "JOINT_" + std::to_string(i);
    r.min_limit = to_mm(j, ini_number(ini, section, "MIN_LIMIT", r.min_limit));
    r.max_limit = to_mm(j, ini_number(ini, section, "MAX_LIMIT", r.max_limit));
    r.lowest = std::numeric_limits<double>::infinity();
    r.highest = -r.lowest;
    check.joints.push_back(r);
    model_joint.push_back(j);
  }

  // Each axis's limits (mm or deg), and the nominal positions sampled: over the limits, but not
  // beyond its principal joint's, where LinuxCNC takes no axis with or without the correction (the
  // xyzbc-trt sample's B at +-36000 over a joint of -100 .. 50 is sampled over -100 .. 50).
  std::vector<std::array<double, 2>> axis_limits(static_cast<std::size_t>(n));
  std::vector<std::array<double, kLevels>> levels(static_cast<std::size_t>(n));
  std::vector<std::string> axis_sections(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
    const std::string section =
        std::string("AXIS_") + static_cast<char>(std::toupper(static_cast<unsigned char>(a.letter)));
    axis_sections[static_cast<std::size_t>(j)] = section;
    // The axis's limits, else the machine file's travel; without either (LinuxCNC's +-1e99), a
    // continuous rotary axis is sampled over a turn.
    double lo = to_mm(j, ini_number(ini, section, "MIN_LIMIT", -kNoLimit));
    double hi = to_mm(j, ini_number(ini, section, "MAX_LIMIT", kNoLimit));
    if (no_limit(lo)) lo = a.travel_min;
    if (no_limit(hi)) hi = a.travel_max;
    if (rotary(j) && (no_limit(lo) || no_limit(hi))) lo = 0.0, hi = 360.0;
    axis_limits[static_cast<std::size_t>(j)] = {lo, hi};
    const auto principal = std::find(model_joint.begin(), model_joint.end(), j);
    if (principal != model_joint.end()) {
      const JointRoom& r = check.joints[static_cast<std::size_t>(principal - model_joint.begin())];
      if (std::max(lo, r.min_limit) < std::min(hi, r.max_limit))
        lo = std::max(lo, r.min_limit), hi = std::min(hi, r.max_limit);
    }
    for (int k = 0; k < kLevels; ++k) levels[static_cast<std::size_t>(j)][k] = lo + (hi - lo) * k / (kLevels - 1);
  }

  check.tool_lengths_mm = {model.correction_length(0.0), std::max(model.tool_length_mm, model.correction_length(0.0))};
  long combinations = 1;
  for (int j = 0; j < n; ++j) combinations *= kLevels;
  machine::Joints nominal(n);
  for (long index = 0; index < combinations; ++index) {
    long rest = index;
    for (int j = 0; j < n; ++j, rest /= kLevels) nominal[j] = levels[static_cast<std::size_t>(j)][rest % kLevels];
    for (const double L : check.tool_lengths_mm) {
      const machine::Correction c = machine::correct(model, nominal, L);
      ++check.poses;
      if (c.status != machine::Status::Ok) continue;  // volcomp check's survey reports those
      for (std::size_t r = 0; r < check.joints.size(); ++r) {
        const double q = c.joints[model_joint[r]];
        check.joints[r].lowest = std::min(check.joints[r].lowest, q);
        check.joints[r].highest = std::max(check.joints[r].highest, q);
      }
    }
  }

  const std::string unit = volkins.units.inch() ? "inch" : "mm";
  for (std::size_t r = 0; r < check.joints.size(); ++r) {
    const JointRoom& room = check.joints[r];
    const int j = model_joint[r];
    const bool is_rotary = rotary(j);
    // Back to the INI's units, for the values the user writes there.
    const double per_unit = is_rotary ? 1.0 : volkins.units.mm_per_unit;
    const double step = limit_step(volkins, is_rotary);
    const std::string joint_section = "JOINT_" + std::to_string(room.joint);
    const std::string& axis_section = axis_sections[static_cast<std::size_t>(j)];
    for (const bool above : {true, false}) {
      const char* key = above ? "MAX_LIMIT" : "MIN_LIMIT";
      const double joint_limit = above ? room.max_limit : room.min_limit;
      if (no_limit(joint_limit)) continue;  // a joint without limits (a continuous table) needs no room
      const double reached = above ? room.highest : room.lowest;
      const double beyond = above ? reached - joint_limit : joint_limit - reached;
      // An axis limit beyond its joint's is one LinuxCNC cannot keep with or without the
      // correction (the room is measured at the joint's limit then): always a finding.
      const double axis_end = axis_limits[static_cast<std::size_t>(j)][above ? 1 : 0];
      const bool axis_beyond = above ? axis_end > joint_limit + kLimitNoise : axis_end < joint_limit - kLimitNoise;
      if (beyond <= kLimitNoise && !axis_beyond) continue;
      const IniEntry* limit = ini.find(joint_section, key);
      const IniEntry* axis_limit = ini.find(axis_section, key);
      // How far the correction takes the joint beyond the axis's limit there, and the axis limit
      // that leaves it that much room inside the joint's: the cause is the axis limit, which lies
      // within the correction of the joint's (or beyond it).
      const double sampled_end = levels[static_cast<std::size_t>(j)][above ? kLevels - 1 : 0];
      const double excursion = std::max(0.0, above ? reached - sampled_end : sampled_end - reached);
      const double narrowed_mm = above ? joint_limit - excursion : joint_limit + excursion;
      const double narrowed = step * (above ? std::floor(narrowed_mm / per_unit / step - 1e-9)
                                            : std::ceil(narrowed_mm / per_unit / step + 1e-9));
      const double widened =
          step * (above ? std::ceil(reached / per_unit / step + 1e-9) : std::floor(reached / per_unit / step - 1e-9));
      const std::string letter(1, room.letter);
      const std::string joint_text = "joint " + std::to_string(room.joint) + " (" + letter + ")";
      const std::string joint_limit_text = std::string(key) + (limit ? " (" + ini.cite(*limit) + ")" : "");
      const std::string axis_limit_text =
          axis_limit
              ? "[" + axis_section + "]" + key + " (" + ini.cite(*axis_limit) + ")"
              : "[" + axis_section + "] without " + key + " (LinuxCNC's default: none; the machine file's travel)";
      const std::string refused = "LinuxCNC refuses a move that ends there (\"would exceed joint " +
                                  std::to_string(room.joint) + "'s " + (above ? "positive" : "negative") + " limit\")";
      std::string p =
          axis_beyond
              // The axis's own limit lies beyond the joint's: refused with or without the correction.
              ? joint_text + ": " + letter + "'s own limit, " + axis_limit_text + ", lies beyond its joint's " +
                    joint_limit_text + ": " + refused + ", with or without the correction" +
                    (excursion >= 5e-6 ? " (which adds " + um_or_mdeg(excursion, is_rotary) + " there)" : "")
              : joint_text + ": the correction takes it to " + rounded(reached / per_unit) + " at the " +
                    (above ? "upper" : "lower") + " end of " + letter + "'s travel, " + um_or_mdeg(beyond, is_rotary) +
                    " beyond its " + joint_limit_text + ": " + refused + ". The cause is " + letter + "'s own limit, " +
                    axis_limit_text + ", which leaves the joint less room than the correction (" +
                    um_or_mdeg(excursion, is_rotary) + ")";
      p += ": narrow " + letter + "'s travel: [" + axis_section + "]" + key + " = " + rounded(narrowed) +
           (is_rotary || per_unit == 1.0 ? "" : " " + unit);
      if (is_rotary)
        p += " (a rotary axis with stops: its joint limits are where the stops are, not to be widened)";
      else
        p += ". That is the safe fix; widening the joint's limit instead ([" + joint_section + "]" + key + " = " +
             rounded(widened) + ") is only right if the machine has that travel before its limit switch";
      check.problems.push_back(p);
    }
  }
  return check;
}

}  // namespace vc::init
