#include "vc/init/home_position.hpp"

#include <cctype>
#include <cmath>

#include "vc/init/number.hpp"

namespace vc::init {
namespace {

// The suggested HOME is this far inside the limit (mm or deg), or a multiple of it.
constexpr double kHomeStep = 0.1;

}  // namespace

HomeCheck check_home_position(const LinuxcncIni& ini, const machine::Model& model, const VolkinsParameters& volkins) {
  using machine::Joints;
  using machine::WorldConvention;
  const int n = model.joint_count();
  HomeCheck check;
  check.convention = volkins.world;
  Joints home = Joints::Zero(n);
  for (int j = 0; j < n; ++j) {
    HomedAxis a;
    a.letter = static_cast<char>(std::toupper(static_cast<unsigned char>(model.axes[j].letter)));
    a.joint = linuxcnc_joint(volkins, model, j);
    const std::string joint_section = "JOINT_" + std::to_string(a.joint);
    a.home_from = "[" + joint_section + "] gives no HOME (LinuxCNC homes it to 0)";
    a.home = ini_number(ini, joint_section, "HOME", 0.0, &a.home_from);
    const std::string axis_section = std::string("AXIS_") + a.letter;
    a.min_limit = ini_number(ini, axis_section, "MIN_LIMIT", a.min_limit);
    a.max_limit = ini_number(ini, axis_section, "MAX_LIMIT", a.max_limit);
    home[j] = a.home;
    check.axes.push_back(a);
  }

  Joints world;
  const machine::Status status =
      machine::world_from_joints(model, volkins.world, home, model.correction_length(0.0), world);
  if (status != machine::Status::Ok) {
    check.problems.push_back(std::string("at the joints' HOME the forward kinematics fails: ") +
                             machine::describe(status));
    return check;
  }

  for (int j = 0; j < n; ++j) {
    HomedAxis& a = check.axes[j];
    a.world = world[j];
    const bool rotary = model.axes[j].type == machine::AxisType::Rotary;
    for (const bool above : {true, false}) {
      const double limit = above ? a.max_limit : a.min_limit;
      const double beyond = above ? a.world - limit : limit - a.world;
      const IniEntry* limit_entry = ini.find(std::string("AXIS_") + a.letter, above ? "MAX_LIMIT" : "MIN_LIMIT");
      if (beyond <= kLimitNoise || !limit_entry) continue;  // LinuxCNC's default limits are +-1e99
      // The correction shifts the world from the joints by about the same near the home: a HOME
      // inside the limit by more than that shift, in whole steps of 0.1 mm (deg).
      const double shift = above ? a.world - a.home : a.home - a.world;
      const double inside = kHomeStep * std::max(1.0, std::ceil((shift + kLimitNoise) / kHomeStep));
      const double suggested = above ? limit - inside : limit + inside;
      check.problems.push_back(
          std::string(1, a.letter) + " homes " + um_or_mdeg(beyond, rotary) + " beyond its " +
          (above ? "MAX_LIMIT" : "MIN_LIMIT") + " (" + ini.cite(*limit_entry) + "): " + a.home_from +
          " puts the corrected world " + a.letter + " at " + format_number(std::round(a.world * 1e6) / 1e6) +
          ". LinuxCNC then refuses every move that leaves " + a.letter + " there (\"would exceed " + a.letter + "'s " +
          (above ? "positive" : "negative") + " limit\") and notes a soft limit at each machine-on. Home " +
          "inside: [JOINT_" + std::to_string(a.joint) + "]HOME = " + format_number(std::round(suggested * 1e6) / 1e6));
    }
  }
  return check;
}

}  // namespace vc::init
