#include "vc/init/home_position.hpp"

#include <cctype>
#include <cmath>
#include <sstream>

#include "vc/init/number.hpp"

namespace vc::init {
namespace {

// Beyond a limit by less than this is float noise of the forward (its tolerance is 1e-10 mm).
constexpr double kNoise = 1e-9;
// The suggested HOME is this far inside the limit (mm or deg), or a multiple of it.
constexpr double kHomeStep = 0.1;

double number_of(const IniEntry& entry) {
  double v = 0.0;
  if (!parse_number(entry.value, v)) throw LoadError(entry.where(), entry.key + " = " + entry.value + " is not a number");
  return v;
}

std::string um_or_mdeg(double v, bool rotary) {
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << v * 1e3 << (rotary ? " mdeg" : " um");
  return s.str();
}

}  // namespace

VolkinsParameters read_volkins_parameters(const LinuxcncIni& ini) {
  const IniEntry* kins = ini.find("KINS", "KINEMATICS");
  std::istringstream words(kins ? kins->value : "");
  std::string word;
  if (!(words >> word) || word != "volkins")
    throw LoadError(kins ? kins->where() : ini.where_missing("KINS"), "[KINS]KINEMATICS does not load volkins");
  VolkinsParameters p;
  while (words >> word) {
    if (word.rfind("coordinates=", 0) == 0) p.coordinates = word.substr(12);
    if (word == "world=tcp") p.world = machine::WorldConvention::Tcp;
  }
  return p;
}

HomeCheck check_home_position(const LinuxcncIni& ini, const machine::Model& model, const VolkinsParameters& volkins) {
  using machine::Joints;
  using machine::WorldConvention;
  const int n = model.joint_count();
  const std::string& coordinates = volkins.coordinates;
  HomeCheck check;
  check.convention = volkins.world;
  Joints home = Joints::Zero(n);
  for (int j = 0; j < n; ++j) {
    HomedAxis a;
    a.letter = static_cast<char>(std::toupper(static_cast<unsigned char>(model.axes[j].letter)));
    a.joint = j;
    if (!coordinates.empty()) {
      const std::size_t at = coordinates.find(static_cast<char>(std::tolower(static_cast<unsigned char>(a.letter))));
      const std::size_t at_upper = coordinates.find(a.letter);
      if (std::min(at, at_upper) != std::string::npos) a.joint = static_cast<int>(std::min(at, at_upper));
    }
    const std::string joint_section = "JOINT_" + std::to_string(a.joint);
    if (const IniEntry* e = ini.find(joint_section, "HOME")) {
      a.home = number_of(*e);
      a.home_from = ini.cite(*e);
    } else {
      a.home_from = "[" + joint_section + "] gives no HOME (LinuxCNC homes it to 0)";
    }
    const std::string axis_section = std::string("AXIS_") + a.letter;
    if (const IniEntry* e = ini.find(axis_section, "MIN_LIMIT")) a.min_limit = number_of(*e);
    if (const IniEntry* e = ini.find(axis_section, "MAX_LIMIT")) a.max_limit = number_of(*e);
    home[j] = a.home;
    check.axes.push_back(a);
  }

  Joints world;
  const machine::Status status =
      machine::world_from_joints(model, volkins.world, home, model.correction_length(0.0), world);
  if (status != machine::Status::Ok) {
    check.problems.push_back(std::string("at the joints' HOME the forward kinematics fails: ") + machine::describe(status));
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
      if (beyond <= kNoise || !limit_entry) continue;  // LinuxCNC's default limits are +-1e99
      // The correction shifts the world from the joints by about the same near the home: a HOME
      // inside the limit by more than that shift, in whole steps of 0.1 mm (deg).
      const double shift = above ? a.world - a.home : a.home - a.world;
      const double inside = kHomeStep * std::max(1.0, std::ceil((shift + kNoise) / kHomeStep));
      const double suggested = above ? limit - inside : limit + inside;
      check.problems.push_back(
          std::string(1, a.letter) + " homes " + um_or_mdeg(beyond, rotary) + " beyond its " +
          (above ? "MAX_LIMIT" : "MIN_LIMIT") + " (" + ini.cite(*limit_entry) + "): " + a.home_from +
          " puts the corrected world " + a.letter + " at " + format_number(std::round(a.world * 1e6) / 1e6) +
          ". LinuxCNC then refuses every move that leaves " + a.letter + " there (\"would exceed " + a.letter +
          "'s " + (above ? "positive" : "negative") + " limit\") and notes a soft limit at each machine-on. Home " +
          "inside: [JOINT_" + std::to_string(a.joint) + "]HOME = " + format_number(std::round(suggested * 1e6) / 1e6));
    }
  }
  return check;
}

}  // namespace vc::init
