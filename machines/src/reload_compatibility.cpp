#include "vc/machine/reload_compatibility.hpp"

#include <cmath>
#include <sstream>

namespace vc::machine {
namespace {

const char* type_name(AxisType t) { return t == AxisType::Linear ? "linear" : "rotary"; }
const char* chain_name(Chain c) { return c == Chain::Tool ? "tool" : "workpiece"; }

template <class A, class B>
bool near(const A& a, const B& b) {
  return ((a - b).array().abs() <= kReloadNominalTolerance).all();
}

std::string vector_text(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out.precision(17);
  out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return out.str();
}

std::string chain_text(const Model& m, const std::vector<int>& chain) {
  std::string s;
  for (int j : chain) s += m.axes[j].letter;
  return s.empty() ? "none" : s;
}

}  // namespace

std::string reload_incompatibility(const Model& running, const Model& candidate) {
  const std::string unchanged = " (the nominal kinematics must not change under a homed machine)";
  if (candidate.coordinates() != running.coordinates())
    return "its axes are \"" + candidate.coordinates() + "\", the running file's \"" + running.coordinates() + "\"";
  for (int j = 0; j < running.joint_count(); ++j) {
    const Axis &a = running.axes[j], &b = candidate.axes[j];
    const std::string axis = std::string("axis ") + a.letter;
    if (a.type != b.type)
      return axis + " is " + type_name(b.type) + ", in the running file " + type_name(a.type);
    if (a.chain != b.chain)
      return axis + " is in the " + chain_name(b.chain) + " chain, in the running file in the " + chain_name(a.chain) + " chain";
    if (!near(a.direction, b.direction))
      return axis + "'s direction is " + vector_text(b.direction) + ", in the running file " +
             vector_text(a.direction) + unchanged;
    if (!near(a.pole_mm, b.pole_mm))
      return axis + "'s pole is " + vector_text(b.pole_mm) + " mm, in the running file " + vector_text(a.pole_mm) +
             " mm" + unchanged;
  }
  if (candidate.tool_chain != running.tool_chain || candidate.workpiece_chain != running.workpiece_chain)
    return "its chains are tool " + chain_text(candidate, candidate.tool_chain) + ", workpiece " +
           chain_text(candidate, candidate.workpiece_chain) + "; the running file's tool " +
           chain_text(running, running.tool_chain) + ", workpiece " + chain_text(running, running.workpiece_chain);
  if (candidate.tool_axis_coordinate != running.tool_axis_coordinate)
    return "its tool_axis_coordinate differs from the running file's";
  if (!near(candidate.spindle.gauge_point_mm, running.spindle.gauge_point_mm))
    return "the spindle's gauge point is " + vector_text(candidate.spindle.gauge_point_mm) +
           " mm, in the running file " + vector_text(running.spindle.gauge_point_mm) + " mm" + unchanged;
  if (!near(candidate.fixture.matrix(), running.fixture.matrix()))
    return "its fixture differs from the running file's" + unchanged;
  if (!(std::abs(candidate.tool_length_reference_mm - running.tool_length_reference_mm) <= kReloadNominalTolerance)) {
    std::ostringstream out;
    out.precision(17);
    out << "its tool_length_reference_mm is " << candidate.tool_length_reference_mm << ", in the running file "
        << running.tool_length_reference_mm << unchanged;
    return out.str();
  }
  std::string names, running_names;
  for (const TemperatureInput& t : candidate.temperatures) names += (names.empty() ? "" : ", ") + t.name;
  for (const TemperatureInput& t : running.temperatures) running_names += (running_names.empty() ? "" : ", ") + t.name;
  if (names != running_names)
    return "its temperature inputs are [" + names + "], the running file's [" + running_names +
           "] (their HAL pins volkins.temperature.<name> exist already)";
  return {};
}

}  // namespace vc::machine
