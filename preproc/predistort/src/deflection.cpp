#include "vc/predistort/deflection.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "vc/machine/toml_file.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::predistort {
namespace {

// The file's typed getters (where, get) are TomlFile's.
class ProcessReader : machine::TomlFile {
 public:
  explicit ProcessReader(const std::string& path) : TomlFile(path) {}

  double number(const toml::table& t, const char* key, std::optional<double> fallback, bool positive) const {
    const toml::node* n = get(t, key, !fallback, "[[tool]]");
    if (!n) return *fallback;
    const auto v = n->value<double>();
    if (!v || !std::isfinite(*v) || (positive ? *v <= 0 : *v < 0))
      throw LoadError(where(*n),
                      std::string("'") + key + "' must be a " + (positive ? "positive" : "non-negative") + " number");
    return *v;
  }

  CuttingProcess read(const interpreter::ToolTable* tool_table) const {
    const toml::table& root = this->root();
    CuttingProcess process;
    process.path = path();
    for (const auto& [key, node] : root)
      if (key.str() != "tool")
        throw LoadError(where(node), "unknown key '" + std::string(key.str()) + "' (only [[tool]] tables)");
    const toml::array* tools = root["tool"].as_array();
    if (!tools) throw LoadError({path(), 1, 1}, "no [[tool]] tables");
    for (const toml::node& node : *tools) {
      const toml::table* t = node.as_table();
      if (!t) throw LoadError(where(node), "[[tool]] must be a table");
      static const char* kKeys[] = {"number",        "diameter_mm",     "teeth",           "specific_force_N_per_mm2",
                                    "chip_exponent", "depth_of_cut_mm", "width_of_cut_mm", "radial_ratio",
                                    "material_side"};
      for (const auto& [key, value] : *t)
        if (std::find_if(std::begin(kKeys), std::end(kKeys), [&](const char* k) { return key.str() == k; }) ==
            std::end(kKeys))
          throw LoadError(where(value), "unknown key '" + std::string(key.str()) + "' in [[tool]]");
      ToolProcess p;
      const double number_value = number(*t, "number", std::nullopt, false);
      if (number_value != std::floor(number_value))
        throw LoadError(where(*t->get("number")), "'number' must be a whole number");
      p.tool = static_cast<int>(number_value);
      std::optional<double> table_diameter;
      if (tool_table)
        if (const auto it = tool_table->find(p.tool); it != tool_table->end() && it->second.diameter > 0)
          table_diameter = it->second.diameter;
      p.diameter_mm = number(*t, "diameter_mm", table_diameter, true);
      const double teeth = number(*t, "teeth", std::nullopt, true);
      if (teeth != std::floor(teeth)) throw LoadError(where(*t->get("teeth")), "'teeth' must be a whole number");
      p.teeth = static_cast<int>(teeth);
      p.specific_force_N_per_mm2 = number(*t, "specific_force_N_per_mm2", std::nullopt, true);
      p.chip_exponent = number(*t, "chip_exponent", 0.25, false);
      p.depth_of_cut_mm = number(*t, "depth_of_cut_mm", std::nullopt, true);
      p.width_of_cut_mm = number(*t, "width_of_cut_mm", std::nullopt, true);
      if (p.width_of_cut_mm > p.diameter_mm)
        throw LoadError(where(*t->get("width_of_cut_mm")), "width_of_cut_mm cannot exceed the tool diameter");
      p.radial_ratio = number(*t, "radial_ratio", 0.0, false);
      if (const toml::node* side = t->get("material_side")) {
        const auto s = side->value<std::string>();
        if (!s || (*s != "left" && *s != "right" && *s != "none"))
          throw LoadError(where(*side), "material_side must be \"left\", \"right\" or \"none\"");
        p.material_side = *s == "left" ? 1 : *s == "right" ? -1 : 0;
      }
      if (!process.tools.emplace(p.tool, p).second)
        throw LoadError(where(node), "tool " + std::to_string(p.tool) + " is listed twice");
    }
    return process;
  }
};

}  // namespace

CuttingProcess load_process(const std::string& path, const interpreter::ToolTable* tools) {
  return ProcessReader(path).read(tools);
}

Deflection::Deflection(const machine::Model& model, CuttingProcess process)
    : model_(model), process_(std::move(process)) {}

Eigen::Vector3d Deflection::force(const interpreter::Move& move, const Eigen::Vector3d& feed,
                                  const Eigen::Vector3d& tool_axis, double path_length_mm) const {
  const auto it = process_.tools.find(move.tool);
  if (it == process_.tools.end() || move.kind == interpreter::MoveKind::Rapid || !move.spindle_on ||
      move.spindle_rpm <= 0)
    return Eigen::Vector3d::Zero();
  const ToolProcess& p = it->second;
  // Feed across the tool axis (a plunge along the axis has no radial engagement here).
  const Eigen::Vector3d across = feed - feed.dot(tool_axis) * tool_axis;
  if (across.norm() < 1e-9) return Eigen::Vector3d::Zero();
  const double feed_mm_per_min = (move.inverse_time ? move.feed * path_length_mm : move.feed) * across.norm();
  const double n = move.spindle_rpm;
  const double fz = feed_mm_per_min / (p.teeth * n);
  const double hm = fz * std::sqrt(p.width_of_cut_mm / p.diameter_mm);
  if (hm <= 0) return Eigen::Vector3d::Zero();
  const double kc = p.specific_force_N_per_mm2 * std::pow(hm, -p.chip_exponent);
  const double fc = kc * p.depth_of_cut_mm * p.width_of_cut_mm * feed_mm_per_min / (M_PI * p.diameter_mm * n);
  const Eigen::Vector3d t = across.normalized();
  const Eigen::Vector3d left = tool_axis.cross(t);  // seen from the spindle
  return -fc * t - p.material_side * p.radial_ratio * fc * left;
}

void Deflection::at(const machine::Joints& nominal, double tool_length_mm, const Eigen::Vector3d& force,
                    machine::Joints& shift, Eigen::Vector3d& deflection_mm) const {
  shift = machine::Joints::Zero(nominal.size());
  deflection_mm.setZero();
  machine::PoseDerivatives d;
  machine::tool_pose(model_, machine::Machine::Ideal, nominal, tool_length_mm, d);
  for (int j = 0; j < model_.joint_count(); ++j) {
    const auto& c = model_.compliance[static_cast<std::size_t>(j)];
    if (c.mm_per_N.empty()) continue;
    const Eigen::Vector3d direction = d.tip.col(j).normalized();
    const double component = c.at(nominal[j]) * force.dot(direction);
    shift[j] = component * d.tip.col(j).norm() / d.tip.col(j).squaredNorm();  // mm of joint per mm of tip
    deflection_mm += component * direction;
  }
}

}  // namespace vc::predistort
