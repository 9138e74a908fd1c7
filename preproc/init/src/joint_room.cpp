#include "vc/init/joint_room.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <limits>

#include "vc/init/number.hpp"
#include "vc/machine/correct.hpp"

namespace vc::init {
namespace {

constexpr int kLevels = 5;          // sample positions per joint over its axis's limits
constexpr double kLimitStep = 0.1;  // a suggested limit is a multiple of this (mm or deg)

}  // namespace

JointRoomCheck check_joint_room(const LinuxcncIni& ini, const machine::Model& model, const VolkinsParameters& volkins) {
  const int n = model.joint_count();
  std::vector<std::array<double, kLevels>> levels(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
    const std::string section =
        std::string("AXIS_") + static_cast<char>(std::toupper(static_cast<unsigned char>(a.letter)));
    const double lo = ini_number(ini, section, "MIN_LIMIT", a.travel_min);
    const double hi = ini_number(ini, section, "MAX_LIMIT", a.travel_max);
    for (int k = 0; k < kLevels; ++k) levels[static_cast<std::size_t>(j)][k] = lo + (hi - lo) * k / (kLevels - 1);
  }

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
    r.min_limit = ini_number(ini, section, "MIN_LIMIT", r.min_limit);
    r.max_limit = ini_number(ini, section, "MAX_LIMIT", r.max_limit);
    r.lowest = std::numeric_limits<double>::infinity();
    r.highest = -r.lowest;
    check.joints.push_back(r);
    model_joint.push_back(j);
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

  for (std::size_t r = 0; r < check.joints.size(); ++r) {
    const JointRoom& room = check.joints[r];
    const bool rotary = model.axes[static_cast<std::size_t>(model_joint[r])].type == machine::AxisType::Rotary;
    const std::string section = "JOINT_" + std::to_string(room.joint);
    for (const bool above : {true, false}) {
      const double beyond = above ? room.highest - room.max_limit : room.min_limit - room.lowest;
      if (beyond <= kLimitNoise) continue;
      const IniEntry* limit = ini.find(section, above ? "MAX_LIMIT" : "MIN_LIMIT");
      const double reached = above ? room.highest : room.lowest;
      const double suggested =
          kLimitStep * (above ? std::ceil(reached / kLimitStep + 1e-9) : std::floor(reached / kLimitStep - 1e-9));
      check.problems.push_back(
          "joint " + std::to_string(room.joint) + " (" + room.letter + "): the correction takes it to " +
          format_number(std::round(reached * 1e6) / 1e6) + " at the " + (above ? "upper" : "lower") + " end of " +
          room.letter + "'s travel, " + um_or_mdeg(beyond, rotary) + " beyond its " +
          (above ? "MAX_LIMIT" : "MIN_LIMIT") + (limit ? " (" + ini.cite(*limit) + ")" : "") +
          ": LinuxCNC refuses a move that ends there (\"would exceed joint " + std::to_string(room.joint) + "'s " +
          (above ? "positive" : "negative") + " limit\"). Room for the correction: [" + section + "]" +
          (above ? "MAX_LIMIT" : "MIN_LIMIT") + " = " + format_number(std::round(suggested * 1e6) / 1e6));
    }
  }
  return check;
}

}  // namespace vc::init
