#include "module_settings.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "vc/machine/load_machine.hpp"

namespace vc::kins {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

[[noreturn]] void refuse(const std::string& message) { throw std::runtime_error("error: " + message); }

}  // namespace

ModuleSettings settings_from_parameters(const char* machine, const char* coordinates, const char* world,
                                        const char* sparm, const char* units) {
  if (!machine || !*machine) refuse("no machine file: load it as `loadrt volkins machine=/path/to/machine.toml`");
  ModuleSettings s;
  // A relative path is taken from rtapi_app's working directory (LinuxCNC starts it in the
  // configuration's directory); made absolute here so every message names the file tried.
  s.model = machine::load_machine(std::filesystem::absolute(machine).lexically_normal().string());
  // Temperature inputs become HAL pins volkins.temperature.<name>.
  // (at most machine::kMaxTemperatureInputs: the loader refuses more)
  for (const machine::TemperatureInput& t : s.model.temperatures)
    if (t.name.empty() || t.name.size() > 24 || !std::all_of(t.name.begin(), t.name.end(), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
        }))
      refuse("temperature input '" + t.name + "' of " + s.model.path +
             ": a HAL pin name needs 1-24 letters, digits, '_' or '-'");

  static constexpr const char* kPoseOrder = "xyzabcuvw";
  const auto field_of = [](char letter) { return static_cast<int>(std::strchr(kPoseOrder, letter) - kPoseOrder); };
  const std::string axes = s.model.coordinates();
  const char tool_axis = static_cast<char>(std::tolower(static_cast<unsigned char>(s.model.tool_axis_coordinate)));
  const std::string given = coordinates && *coordinates ? lower(coordinates) : axes;
  const auto mismatch = [&](const std::string& why) {
    refuse("coordinates=" + std::string(coordinates) + " does not match the machine file " + s.model.path + ": " + why +
           " (its axes are \"" + axes + "\"" +
           (tool_axis ? std::string(" and its tool_axis_coordinate ") + s.model.tool_axis_coordinate : std::string()) +
           ": each axis at least once, a letter twice drives two joints alike, e.g. a gantry's two Y motors)");
  };
  if (given.size() > static_cast<std::size_t>(kMaxJoints))
    mismatch("more than " + std::to_string(kMaxJoints) + " joints");
  s.joint_count = static_cast<int>(given.size());
  s.principal_joint.fill(-1);
  for (int k = 0; k < s.joint_count; ++k) {
    if (tool_axis && given[k] == tool_axis) {
      s.model_joint[k] = -1;
      if (s.tool_axis_joint < 0) s.tool_axis_joint = k;
      continue;
    }
    const std::size_t axis = axes.find(given[k]);
    if (axis == std::string::npos)
      mismatch("joint " + std::to_string(k) + "'s axis " + static_cast<char>(std::toupper(given[k])) + " is not in it");
    s.model_joint[k] = static_cast<int>(axis);
    if (s.principal_joint[axis] < 0) s.principal_joint[axis] = k;
  }
  for (std::size_t axis = 0; axis < axes.size(); ++axis)
    if (s.principal_joint[axis] < 0)
      mismatch(std::string("no joint drives its axis ") + static_cast<char>(std::toupper(axes[axis])));
  if (tool_axis) s.tool_axis_field = field_of(tool_axis);

  // Type 0's world: world=, else sparm=identityfirst (identity), else identity.
  const std::string convention = world && *world ? lower(world) : "";
  const std::string switchkins = sparm && *sparm ? lower(sparm) : "";
  if (!switchkins.empty() && switchkins != "identityfirst")
    refuse("sparm=" + std::string(sparm) +
           " is not a volkins parameter: sparm=identityfirst (kinematics type 0 is "
           "the identity, as with LinuxCNC's trt modules) or none; world=tcp makes type 0 the TCP kinematics");
  if (convention == "axes" || convention.empty())
    s.kinematics_types = {machine::WorldConvention::Axes, machine::WorldConvention::Tcp};
  else if (convention == "tcp")
    s.kinematics_types = {machine::WorldConvention::Tcp, machine::WorldConvention::Axes};
  else
    refuse("world=" + std::string(world) + " is not a world convention: use world=axes or world=tcp");
  if (convention == "tcp" && !switchkins.empty())
    refuse(
        "world=tcp and sparm=identityfirst contradict each other: kinematics type 0 is either TCP (world=tcp) or "
        "the identity (sparm=identityfirst or world=axes)");

  s.z_joint = s.model.joint_of('Z');
  if (s.kinematics_types[0] == machine::WorldConvention::Tcp && s.z_joint < 0)
    refuse("world=tcp needs a Z axis (the tool length is taken along it); " + s.model.path + " has none");

  const std::string unit = units && *units ? lower(units) : "mm";
  if (unit != "mm" && unit != "inch")
    refuse("units=" + std::string(units) +
           " is not a length unit of LinuxCNC: units=mm (default) or units=inch, "
           "as [TRAJ]LINEAR_UNITS");
  s.mm_per_unit = unit == "inch" ? 25.4 : 1.0;
  for (int j = 0; j < s.model.joint_count(); ++j) {
    s.pose_field[j] = field_of(axes[j]);
    s.linear_scale[j] = s.model.axes[j].type == machine::AxisType::Linear ? s.mm_per_unit : 1.0;
  }
  s.contraction.emplace(s.model, std::vector<double>(kBoundToolLengthsMm.begin(), kBoundToolLengthsMm.end()), true);
  return s;
}

}  // namespace vc::kins
