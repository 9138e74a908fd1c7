#include "vc/init/home_position.hpp"

#include <cctype>
#include <cmath>

#include "vc/init/number.hpp"

namespace vc::init {

HomeCheck check_home_position(const LinuxcncIni& ini, const machine::Model& model, const VolkinsParameters& volkins) {
  using machine::Joints;
  using machine::WorldConvention;
  const int n = model.joint_count();
  HomeCheck check;
  check.convention = volkins.world;
  Joints home = Joints::Zero(n);
  // The INI's lengths are in LinuxCNC's units (the rotary axes' deg as they are).
  const auto per_unit = [&](int j) {
    return model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Rotary ? 1.0 : volkins.units.mm_per_unit;
  };
  const auto to_mm = [&](int j, double v) { return no_limit(v) ? v : v * per_unit(j); };
  for (int j = 0; j < n; ++j) {
    HomedAxis a;
    a.letter = static_cast<char>(std::toupper(static_cast<unsigned char>(model.axes[j].letter)));
    a.joint = linuxcnc_joint(volkins, model, j);
    const std::string joint_section = "JOINT_" + std::to_string(a.joint);
    a.home_from = "[" + joint_section + "] gives no HOME (LinuxCNC homes it to 0)";
    a.home = to_mm(j, ini_number(ini, joint_section, "HOME", 0.0, &a.home_from));
    const std::string axis_section = std::string("AXIS_") + a.letter;
    a.min_limit = to_mm(j, ini_number(ini, axis_section, "MIN_LIMIT", a.min_limit));
    a.max_limit = to_mm(j, ini_number(ini, axis_section, "MAX_LIMIT", a.max_limit));
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
      // inside the limit by more than that shift, in whole steps (0.1 mm or deg, 0.01 inch) of
      // the INI's units, in which it is given back.
      const double unit = per_unit(j);
      const double step = limit_step(volkins, rotary);
      const double shift = (above ? a.world - a.home : a.home - a.world) / unit;
      const double inside = step * std::max(1.0, std::ceil((shift + kLimitNoise) / step));
      const double suggested = above ? limit / unit - inside : limit / unit + inside;
      check.problems.push_back(std::string(1, a.letter) + " homes " + um_or_mdeg(beyond, rotary) + " beyond its " +
                               (above ? "MAX_LIMIT" : "MIN_LIMIT") + " (" + ini.cite(*limit_entry) +
                               "): " + a.home_from + " puts the corrected world " + a.letter + " at " +
                               format_number(std::round(a.world / unit * 1e6) / 1e6) + (unit == 1.0 ? "" : " inch") +
                               ". LinuxCNC then refuses every move that leaves " + a.letter +
                               " there (\"would exceed " + a.letter + "'s " + (above ? "positive" : "negative") +
                               " limit\") and notes a soft limit at each machine-on. Home " + "inside: [JOINT_" +
                               std::to_string(a.joint) + "]HOME = " + format_number(std::round(suggested * 1e6) / 1e6));
    }
  }
  return check;
}

}  // namespace vc::init
