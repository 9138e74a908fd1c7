#include "vc/acceptance/work_volume.hpp"

#include <sstream>
#include <stdexcept>
#include <vector>

#include "vc/tables/number_text.hpp"

namespace vc::acceptance {

LinearJoints linear_joints(const machine::Model& model) {
  LinearJoints j;
  int* slots[3] = {&j.x, &j.y, &j.z};
  for (int i = 0; i < 3; ++i) {
    const char letter = "XYZ"[i];
    const int joint = model.joint_of(letter);
    if (joint < 0 || model.axes[static_cast<std::size_t>(joint)].type != machine::AxisType::Linear)
      throw std::runtime_error(model.info.name + " has no linear " + std::string(1, letter) +
                               " axis: the diagonal tests need linear X, Y and Z axes");
    *slots[i] = joint;
  }
  return j;
}

WorkVolume default_volume(const machine::Model& model, double shrink) {
  const LinearJoints j = linear_joints(model);
  WorkVolume v;
  for (int i = 0; i < 3; ++i) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j[i])];
    const double margin = shrink * (a.travel_max - a.travel_min);
    v.low_mm[i] = a.travel_min + margin;
    v.high_mm[i] = a.travel_max - margin;
  }
  return v;
}

WorkVolume parse_volume(const machine::Model& model, const std::string& text) {
  const LinearJoints j = linear_joints(model);
  std::vector<std::string> parts;
  std::stringstream list(text);
  for (std::string part; std::getline(list, part, ',');) parts.push_back(part);
  if (parts.size() != 3) throw std::runtime_error("--volume " + text + ": x0:x1,y0:y1,z0:z1 (mm), three ranges");
  WorkVolume v;
  for (int i = 0; i < 3; ++i) {
    const std::string& p = parts[static_cast<std::size_t>(i)];
    const auto colon = p.find(':');
    const std::string axis(1, "XYZ"[i]);
    double lo = 0, hi = 0;
    try {
      std::size_t used_lo = 0, used_hi = 0;
      lo = std::stod(p.substr(0, colon), &used_lo);
      hi = std::stod(p.substr(colon + 1), &used_hi);
      if (colon == std::string::npos || used_lo != colon || used_hi != p.size() - colon - 1) throw std::invalid_argument(p);
    } catch (const std::exception&) {
      throw std::runtime_error("--volume " + text + ": '" + p + "' is not LOW:HIGH in mm (" + axis + ")");
    }
    if (!(lo < hi)) throw std::runtime_error("--volume " + text + ": " + axis + " needs low < high");
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j[i])];
    if (lo < a.travel_min || hi > a.travel_max)
      throw std::runtime_error("--volume " + text + ": " + axis + " " + p + " leaves the travel " +
                               number_text(a.travel_min) + ":" + number_text(a.travel_max) + " mm");
    v.low_mm[i] = lo;
    v.high_mm[i] = hi;
  }
  return v;
}

}  // namespace vc::acceptance
