#include "vc/init/machine_layout.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <sstream>

#include "vc/init/linuxcnc_units.hpp"
#include "vc/init/number.hpp"

namespace vc::init {
namespace {

constexpr const char* kLetters = "XYZABCUVW";
constexpr int kMaxJoints = 16;     // EMCMOT_MAX_JOINTS
constexpr double kNoLimit = 1e98;  // LinuxCNC's "no limit" is 1e99 (inijoint.cc's defaults)

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

char upper(char c) { return static_cast<char>(std::toupper(static_cast<unsigned char>(c))); }

bool is_rotary(char letter) { return letter == 'A' || letter == 'B' || letter == 'C'; }

void check_angular_units(const LinuxcncIni& ini) {
  const IniEntry* angular = ini.find("TRAJ", "ANGULAR_UNITS");
  if (!angular) return;
  const std::string u = lower(angular->value);
  double per_deg = 0.0;
  if (!(u == "deg" || u == "degree" || (parse_number(u, per_deg) && per_deg == 1.0)))
    throw LoadError(angular->where(), "ANGULAR_UNITS = " + angular->value + " is not deg: volkins works in degrees");
}

// motmod's num_extrajoints= in [EMCMOT]EMCMOT: joints after the kinematics' ones.
int extra_joints(const LinuxcncIni& ini) {
  const IniEntry* motmod = ini.find("EMCMOT", "EMCMOT");
  if (!motmod) return 0;
  std::istringstream words(motmod->value);
  int extra = 0;
  for (std::string w; words >> w;) {
    double n = 0.0;
    if (w.rfind("num_extrajoints=", 0) == 0 && parse_number(w.substr(16), n)) extra = static_cast<int>(n);
  }
  return extra;
}

int whole_number(const IniEntry& entry, int low, int high) {
  double n = 0.0;
  if (!parse_number(entry.value, n) || n != std::floor(n) || n < low || n > high)
    throw LoadError(entry.where(), entry.key + " = " + entry.value + " is not a whole number from " +
                                       std::to_string(low) + " to " + std::to_string(high));
  return static_cast<int>(n);
}

double limit(const IniEntry& entry) {
  double v = 0.0;
  if (!parse_number(entry.value, v))
    throw LoadError(entry.where(), entry.key + " = " + entry.value + " is not a number");
  return v;
}

// The letters a switchkins module requires, in its default order (its coordinates= without
// the parameter); "" for trivkins.
std::string required_coordinates(StockModule kind) {
  switch (kind) {
    case StockModule::XyzbcTrt:
      return "xyzbc";
    case StockModule::XyzacTrt:
      return "xyzac";
    case StockModule::XyzabTdr:  // joints 0-4, fixed (no coordinates=)
      return "xyzab";
    case StockModule::FiveAxis:
      return "xyzbcw";
    case StockModule::Trivkins:
      break;
  }
  return "";
}

// The coordinates the module maps its joints with, checked letter by letter; the number of
// kinematics joints is needed for trivkins without coordinates= (its default is XYZABCUVW:
// joint n is the n-th letter).
void read_coordinates(const KinematicsLine& k, const LinuxcncIni& ini, int kinematics_joints, MachineLayout& layout) {
  const std::string line = ini.cite(*k.entry);
  const std::string required = required_coordinates(k.kind);
  if (const std::string* given = k.parameter("coordinates")) {
    layout.coordinates = *given;
    layout.coordinates_from = k.module + " coordinates=" + *given + " (" + line + ")";
  } else if (k.kind == StockModule::Trivkins) {
    if (kinematics_joints > 9)
      throw LoadError(k.entry->where(),
                      "trivkins without coordinates= maps at most 9 joints (XYZABCUVW), but [KINS]JOINTS "
                      "asks for " +
                          std::to_string(kinematics_joints));
    layout.coordinates = lower(std::string(kLetters).substr(0, static_cast<std::size_t>(kinematics_joints)));
    layout.coordinates_from = "trivkins with its default coordinates=" + layout.coordinates +
                              " (XYZABCUVW, as many as [KINS]JOINTS has joints) (" + line + ")";
  } else {
    layout.coordinates = required;
    layout.coordinates_from = k.module + " with its default coordinates=" + layout.coordinates + " (" + line + ")";
  }
  for (char c : layout.coordinates)
    if (!std::strchr(kLetters, upper(c)))
      throw LoadError(k.entry->where(), "coordinates=" + layout.coordinates + ": '" + std::string(1, c) +
                                            "' is not an axis letter (XYZABCUVW)");
  if (layout.coordinates.empty()) throw LoadError(k.entry->where(), "coordinates= names no axis");
  for (char r : required)
    if (std::none_of(layout.coordinates.begin(), layout.coordinates.end(),
                     [&](char c) { return upper(c) == upper(r); }))
      throw LoadError(k.entry->where(), "coordinates=" + layout.coordinates + " lacks " + std::string(1, upper(r)) +
                                            ", which " + k.module + " requires (it needs " + required + ")");
  if (k.kind != StockModule::FiveAxis) return;
  // 5axiskins maps A, U and V one-to-one to their joints (5axiskins.c); volkins' joints are the
  // machine file's axes and its tool-axis coordinate only.
  for (char c : layout.coordinates)
    if (std::strchr("AUV", upper(c)))
      throw LoadError(k.entry->where(),
                      layout.coordinates_from + " has " + std::string(1, upper(c)) +
                          ", which 5axiskins passes through " +
                          "to its joint one-to-one: volkins does not pass it through (its joints are the machine "
                          "file's axes X Y Z B C and the tool-axis coordinate W); remove the joint");
  layout.tool_axis = 'W';
  layout.tool_axis_joint = static_cast<int>(layout.coordinates.find_first_of("Ww"));
}

// The axes (as a set of letters) of a coordinates string.
std::string letter_set(const std::string& coordinates) {
  std::string set;
  for (const char* l = kLetters; *l; ++l)
    if (std::any_of(coordinates.begin(), coordinates.end(), [&](char c) { return upper(c) == *l; })) set += *l;
  return set;
}

void check_traj_coordinates(const LinuxcncIni& ini, const MachineLayout& layout) {
  const IniEntry* traj = ini.find("TRAJ", "COORDINATES");
  const std::string planner = traj ? letter_set(traj->value) : "XYZ";  // LinuxCNC's default: XYZ
  const std::string kinematics = letter_set(layout.coordinates);
  if (planner == kinematics) return;
  const std::string traj_text =
      traj ? "[TRAJ]COORDINATES = " + traj->value : "[TRAJ] without COORDINATES (LinuxCNC takes XYZ)";
  std::string why;
  for (char l : kinematics)
    if (planner.find(l) == std::string::npos) {
      const std::size_t joint =
          std::find_if(layout.coordinates.begin(), layout.coordinates.end(), [&](char c) { return upper(c) == l; }) -
          layout.coordinates.begin();
      why = "the kinematics makes joint " + std::to_string(joint) + " the axis " + std::string(1, l) +
            ", which the trajectory planner does not have";
      break;
    }
  if (why.empty())
    for (char l : planner)
      if (kinematics.find(l) == std::string::npos) {
        why = std::string(1, l) + " is an axis of the trajectory planner that no joint of the kinematics moves";
        break;
      }
  throw LoadError(traj ? traj->where() : ini.where_missing("TRAJ"),
                  traj_text + " and " + layout.coordinates_from + " do not name the same axes: " + why +
                      "; volkins needs every joint to be an axis of the machine (remove the joint or add the axis)");
}

// The model: exactly three linear axes X Y Z, at most two rotary ones (and the tool-axis
// coordinate, no axis of its own).
void check_model_axes(const KinematicsLine& k, const MachineLayout& layout) {
  std::string axes = letter_set(layout.coordinates);
  if (layout.tool_axis) axes.erase(axes.find(layout.tool_axis), 1);
  const std::string& named = layout.coordinates_from;
  for (char l : std::string("UVW"))
    if (axes.find(l) != std::string::npos)
      throw LoadError(k.entry->where(),
                      named + " has " + std::string(1, l) +
                          ": the model has exactly three linear axes X Y Z (U, V, W are further linear "
                          "axes)");
  for (char l : std::string("XYZ"))
    if (axes.find(l) == std::string::npos)
      throw LoadError(k.entry->where(),
                      named + " has no " + std::string(1, l) + ": the model has exactly three linear axes X Y Z");
  if (axes.size() > 5)
    throw LoadError(k.entry->where(), named + " has three rotary axes A, B, C: the model has at most two");
}

LayoutAxis read_axis(const LinuxcncIni& ini, const IniEntry& joints_entry, const LinearUnits& units, char letter,
                     int joint) {
  LayoutAxis axis;
  axis.letter = letter;
  axis.joint = joint;
  axis.rotary = is_rotary(letter);
  const std::string name = "JOINT_" + std::to_string(joint);
  const IniSection* section = ini.section(name);
  if (!section)
    throw LoadError(joints_entry.where(), "joint " + std::to_string(joint) + " (" + std::string(1, letter) +
                                              ") has no [" + name +
                                              "] section: its MIN_LIMIT and MAX_LIMIT are the axis's travel");
  if (const IniEntry* type = ini.find(name, "TYPE")) {
    const std::string t = lower(type->value);
    if (t != "linear" && t != "angular")
      throw LoadError(type->where(), "TYPE = " + type->value + " is neither LINEAR nor ANGULAR");
    if ((t == "angular") != axis.rotary)
      throw LoadError(type->where(), "TYPE = " + type->value + ", but joint " + std::to_string(joint) + " is " +
                                         std::string(1, letter) + ", a " + (axis.rotary ? "rotary" : "linear") +
                                         " axis (TYPE = " + (axis.rotary ? "ANGULAR" : "LINEAR") + ")");
    axis.type_from = "[" + name + "] " + ini.cite(*type);
  } else {
    axis.type_from = "[" + name + "] gives no TYPE";
  }
  const IniEntry* low = ini.find(name, "MIN_LIMIT");
  const IniEntry* high = ini.find(name, "MAX_LIMIT");
  // A rotary joint without limits (LinuxCNC's default, +-1e99) turns without end: a rotary
  // table, continuous. The machine file's travel is then one turn: its tables are periodic
  // over it, and volkins corrects the axis at any angle.
  const auto no_limit = [](const IniEntry* e, double sign) {
    double v = 0.0;
    return !e || (parse_number(e->value, v) && v * sign >= kNoLimit);
  };
  if (axis.rotary && no_limit(low, -1.0) && no_limit(high, 1.0)) {
    axis.continuous = true;
    axis.travel_min = 0.0;
    axis.travel_max = 360.0;
    axis.travel_from = "[" + name + "] " + (low || high ? "limits beyond +-1e98" : "gives no MIN_LIMIT, MAX_LIMIT") +
                       ": a rotary table without stops (LinuxCNC's default limits +-1e99); the travel is one turn";
    return axis;
  }
  for (const auto& [entry, key] : {std::pair{low, "MIN_LIMIT"}, std::pair{high, "MAX_LIMIT"}})
    if (!entry)
      throw LoadError({section->path, section->line},
                      "[" + name + "] has no " + key + ": the limits of joint " + std::to_string(joint) + " (" +
                          std::string(1, letter) + ") are the axis's travel in the machine file" +
                          (axis.rotary ? " (a rotary table without stops: give neither limit)" : ""));
  axis.travel_min = limit(*low);
  axis.travel_max = limit(*high);
  if (!(axis.travel_min < axis.travel_max))
    throw LoadError(low->where(), "MIN_LIMIT = " + low->value + " is not below MAX_LIMIT = " + high->value + " (" +
                                      ini.cite(*high) + ")");
  axis.travel_from = "[" + name + "] " + ini.cite(*low) + ", " + ini.cite(*high);
  if (!axis.rotary && units.inch()) {
    axis.travel_min = units.to_mm(axis.travel_min);
    axis.travel_max = units.to_mm(axis.travel_max);
    axis.travel_from += " (inch, x 25.4)";
  }
  return axis;
}

}  // namespace

const LayoutAxis* MachineLayout::axis(char letter) const {
  for (const LayoutAxis& a : axes)
    if (a.letter == letter) return &a;
  return nullptr;
}

MachineLayout read_layout(const LinuxcncIni& ini, const KinematicsLine& k) {
  MachineLayout layout;
  layout.units = read_linear_units(ini);
  const IniEntry* joints = ini.find("KINS", "JOINTS");
  if (!joints)
    throw LoadError(ini.where_missing("KINS"),
                    "no [KINS]JOINTS: LinuxCNC needs the number of joints, init the joint of each axis");
  const int joint_count = whole_number(*joints, 1, kMaxJoints);
  const int extra = extra_joints(ini);
  read_coordinates(k, ini, joint_count - extra, layout);
  const int mapped = static_cast<int>(layout.coordinates.size());
  if (mapped + extra != joint_count)
    throw LoadError(joints->where(),
                    "JOINTS = " + joints->value + ", but " + layout.coordinates_from + " maps " +
                        std::to_string(mapped) + " joints" +
                        (extra ? " and [EMCMOT]EMCMOT adds " + std::to_string(extra) + " extra joints" : "") +
                        ": they must agree");
  check_traj_coordinates(ini, layout);
  check_model_axes(k, layout);
  for (const char* l = kLetters; *l; ++l) {
    if (*l == layout.tool_axis) continue;  // no axis of the model: its joint's limits are LinuxCNC's
    const std::size_t first = layout.coordinates.find_first_of(std::string{*l, static_cast<char>(std::tolower(*l))});
    if (first != std::string::npos)
      layout.axes.push_back(read_axis(ini, *joints, layout.units, *l, static_cast<int>(first)));
  }
  if (std::any_of(layout.axes.begin(), layout.axes.end(), [](const LayoutAxis& a) { return a.rotary; }))
    check_angular_units(ini);
  return layout;
}

}  // namespace vc::init
