#include "vc/machine/load_machine.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "vc/machine/forward.hpp"
#include "vc/machine/toml_file.hpp"
#include "vc/tables/load_table.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/tables/units.hpp"

namespace vc::machine {
namespace {

using Eigen::Vector3d;
namespace fs = std::filesystem;

// As an ostream writes a double (six significant digits), locale-proof.
std::string number(double v) { return significant_text(v, 6); }

// The file's typed getters (where, check_keys, table, text, scalar) are TomlFile's.
class MachineReader : TomlFile {
 public:
  explicit MachineReader(std::string path) : TomlFile(std::move(path)) {}

  Model read() {
    const toml::table& root = this->root();
    model_.path = path();
    check_keys(root, "the machine file",
               {"machine", "measurement", "spindle", "fixture", "correction", "tool_chain", "workpiece_chain",
                "stiffness", "temperatures"});
    read_info(root);
    read_temperatures(root);
    read_spindle(root);
    read_fixture(root);
    read_correction(root);
    read_chain(root, "tool_chain", Chain::Tool);
    read_chain(root, "workpiece_chain", Chain::Workpiece);
    order_joints(root);
    if (model_.tool_axis_coordinate && model_.joint_of(model_.tool_axis_coordinate) >= 0)
      throw LoadError(tool_axis_at_, std::string("tool_axis_coordinate ") + model_.tool_axis_coordinate +
                                         " is an axis of this machine: it must be a coordinate without one");
    for (int j = 0; j < model_.joint_count(); ++j) model_.axes[j].moved_by = 1u << j;
    check_axes_span(root);
    read_stiffness(root);
    for (PendingTables& p : pending_) load_tables(p);
    return std::move(model_);
  }

 private:
  // ---- typed access ----------------------------------------------------------------------
  using TomlFile::scalar;

  double scalar(const toml::table& t, std::string_view key, std::optional<double> fallback,
                const std::string& context) const {
    const toml::node* n = get(t, key, !fallback, context);
    return n ? scalar(*n, key) : *fallback;
  }

  std::vector<double> numbers(const toml::table& t, std::string_view key, std::size_t size, bool required,
                              const std::string& context) const {
    const toml::node* n = get(t, key, required, context);
    if (!n) return std::vector<double>(size, 0.0);
    const toml::array* a = n->as_array();
    if (!a || a->size() != size)
      throw LoadError(where(*n), "'" + std::string(key) + "' must be an array of " + std::to_string(size) + " numbers");
    std::vector<double> out;
    for (const toml::node& e : *a) out.push_back(scalar(e, key));
    return out;
  }

  Vector3d vec3(const toml::table& t, std::string_view key, bool required, const std::string& context) const {
    const auto v = numbers(t, key, 3, required, context);
    return {v[0], v[1], v[2]};
  }

  // Location errors "EC0Y_arcsec = -5" of the line `letter` ('S' for the spindle).
  void read_location(const toml::table* t, char letter, Vector3d& position_mm, Vector3d& orientation_rad) const {
    position_mm.setZero();
    orientation_rad.setZero();
    if (!t) return;
    for (auto&& [key, value] : *t) {
      const std::string k(key.str());
      const std::size_t underscore = k.rfind('_');
      const auto symbol = tables::parse_error_symbol(k.substr(0, underscore));
      const auto unit = underscore == std::string::npos ? std::nullopt : tables::find_unit(k.substr(underscore + 1));
      const std::string expected = std::string("E{X,Y,Z,A,B,C}0") + letter + "_<unit>";
      if (!symbol || !symbol->location || symbol->axis != letter)
        throw LoadError(where(key.source()), "'" + k + "' is not a location error of " + std::string(1, letter) +
                                                 " (expected " + expected + ", e.g. EC0" + letter + "_arcsec)");
      const std::string kind = symbol->quantity() == tables::Quantity::Length ? "a length" : "an angle";
      const std::string units = std::string(tables::unit_names(symbol->quantity()));
      if (underscore == std::string::npos)
        throw LoadError(where(key.source()),
                        "'" + k + "' needs a unit suffix (" + k + "_<unit>, unit one of " + units + ")");
      const std::string unit_name = k.substr(underscore + 1);
      if (!unit)
        throw LoadError(where(key.source()), "unknown unit '" + unit_name + "' in '" + k + "' (use " + units + ")");
      if (unit->quantity != symbol->quantity())
        throw LoadError(where(key.source()), "unit '" + unit_name + "' does not fit " + k.substr(0, underscore) +
                                                 ", which is " + kind + " (use " + units + ")");
      const double v = scalar(value, k) * unit->to_core;
      (symbol->component < 3 ? position_mm[symbol->component] : orientation_rad[symbol->component - 3]) = v;
    }
  }

  // ---- sections --------------------------------------------------------------------------
  void read_info(const toml::table& root) {
    const toml::table& m = *table(root, "machine", true, "the machine file");
    check_keys(m, "[machine]", {"name", "serial", "description"});
    model_.info.name = text(m, "name", true, "[machine]");
    if (model_.info.name.empty()) throw LoadError(where(*m.get("name")), "the machine name must not be empty");
    model_.info.serial = text(m, "serial", false, "[machine]");
    model_.info.description = text(m, "description", false, "[machine]");
    if (const toml::table* s = table(root, "measurement", false, "")) {
      check_keys(*s, "[measurement]", {"date", "by", "instrument", "temperature_C", "notes"});
      model_.info.measured_on = text(*s, "date", false, "");
      model_.info.measured_by = text(*s, "by", false, "");
      model_.info.instrument = text(*s, "instrument", false, "");
      model_.info.temperature_C = scalar(*s, "temperature_C", 20.0, "");
    }
  }

  // [temperatures]: name = { reference_degC = 20, min_degC = 10, max_degC = 45 }
  void read_temperatures(const toml::table& root) {
    const toml::table* temps = table(root, "temperatures", false, "");
    if (!temps) return;
    for (auto&& [key, value] : *temps) {
      const std::string name(key.str());
      const toml::table* t = value.as_table();
      if (!t)
        throw LoadError(where(key.source()),
                        "temperature input '" + name + "' = { reference_degC = 20.0, min_degC = ..., max_degC = ... }");
      const std::string context = "temperature input '" + name + "'";
      check_keys(*t, context, {"reference_degC", "min_degC", "max_degC"});
      TemperatureInput in;
      in.name = name;
      in.reference_degC = scalar(*t, "reference_degC", 20.0, context);
      in.min_degC = scalar(*t, "min_degC", 0.0, context);
      in.max_degC = scalar(*t, "max_degC", 50.0, context);
      if (!(in.min_degC <= in.reference_degC && in.reference_degC <= in.max_degC) || in.min_degC < -50 ||
          in.max_degC > 150)
        throw LoadError(where(*t), context + ": needs -50 <= min_degC <= reference_degC <= max_degC <= 150");
      if (model_.temperatures.size() == static_cast<std::size_t>(kMaxTemperatureInputs))
        throw LoadError(where(*t), "more than " + std::to_string(kMaxTemperatureInputs) +
                                       " temperature inputs (the model takes " + std::to_string(kMaxTemperatureInputs) +
                                       ")");
      model_.temperatures.push_back(in);
    }
  }

  // thermal = { input = "x_screw", expansion_um_per_m_K = 11.5, reference_mm = 0 } (linear axes)
  void read_thermal(const toml::table& axis_table, Axis& axis, const std::string& context) {
    const toml::node* n = axis_table.get("thermal");
    if (!n) return;
    const toml::table* t = n->as_table();
    if (!t) throw LoadError(where(*n), "thermal = { input = \"name\", expansion_um_per_m_K = 11.5, reference_mm = 0 }");
    if (axis.type != AxisType::Linear || (axis.letter != 'X' && axis.letter != 'Y' && axis.letter != 'Z'))
      throw LoadError(
          where(*n),
          "thermal expansion is for the linear axes X, Y, Z (a rotary axis's thermal drift goes in a table)");
    const std::string where_text = context + " thermal";
    check_keys(*t, where_text, {"input", "expansion_um_per_m_K", "reference_mm"});
    const std::string input = text(*t, "input", true, where_text);
    axis.thermal.input = model_.temperature_of(input);
    if (axis.thermal.input < 0)
      throw LoadError(where(*t->get("input")), "no temperature input '" + input + "' in [temperatures]");
    const double um_per_m_K = scalar(*t, "expansion_um_per_m_K", std::nullopt, where_text);
    if (std::abs(um_per_m_K) > 50)
      throw LoadError(where(*t->get("expansion_um_per_m_K")),
                      "expansion_um_per_m_K must be within +-50 (steel 11.5, "
                      "cast iron 10.5, glass scales 0-8)");
    axis.thermal.expansion_per_K = um_per_m_K * 1e-6;
    axis.thermal.reference_mm = scalar(*t, "reference_mm", 0.0, where_text);
  }

  void read_spindle(const toml::table& root) {
    const toml::table& s = *table(root, "spindle", true, "the machine file");
    check_keys(s, "[spindle]",
               {"gauge_point_mm", "tool_length_mm", "tool_length_reference_mm", "tool_axis_coordinate", "location"});
    Spindle& spindle = model_.spindle;
    spindle.gauge_point_mm = vec3(s, "gauge_point_mm", false, "[spindle]");
    model_.tool_length_mm = scalar(s, "tool_length_mm", 0.0, "[spindle]");
    model_.tool_length_reference_mm = scalar(s, "tool_length_reference_mm", 0.0, "[spindle]");
    const std::string tool_axis = text(s, "tool_axis_coordinate", false, "[spindle]");
    if (s.get("tool_axis_coordinate")) {
      if (tool_axis.size() != 1 || std::string_view("UVW").find(tool_axis[0]) == std::string_view::npos)
        throw LoadError(where(*s.get("tool_axis_coordinate")),
                        "tool_axis_coordinate '" + tool_axis +
                            "' must be one of U, V, W (the LinuxCNC coordinate "
                            "that moves the tool along its own axis, e.g. 5axiskins' W)");
      model_.tool_axis_coordinate = tool_axis[0];
      tool_axis_at_ = where(*s.get("tool_axis_coordinate"));
    }
    read_location(table(s, "location", false, ""), 'S', spindle.location_mm, spindle.location_rad);
    spindle.real = line_placement(spindle.gauge_point_mm, spindle.location_mm, spindle.location_rad);
    spindle.ideal = line_placement(spindle.gauge_point_mm, Vector3d::Zero(), Vector3d::Zero());
  }

  void read_fixture(const toml::table& root) {
    const toml::table* f = table(root, "fixture", false, "");
    model_.fixture = Eigen::Isometry3d::Identity();
    if (!f) return;
    check_keys(*f, "[fixture]", {"origin_mm", "rotation_deg"});
    model_.fixture = line_placement(vec3(*f, "origin_mm", false, "[fixture]"), Vector3d::Zero(),
                                    vec3(*f, "rotation_deg", false, "[fixture]") * tables::kDegToRad);
  }

  void read_correction(const toml::table& root) {
    model_.fade = {2.0 * tables::kDegToRad, 10.0 * tables::kDegToRad};
    const toml::table* c = table(root, "correction", false, "");
    if (!c) return;
    check_keys(*c, "[correction]", {"pole_fade_deg", "max_iterations"});
    if (c->get("pole_fade_deg")) {
      const auto fade = numbers(*c, "pole_fade_deg", 2, true, "[correction]");
      if (!(fade[0] >= 0.0 && fade[1] > fade[0] && fade[1] <= 90.0))
        throw LoadError(where(*c->get("pole_fade_deg")), "pole_fade_deg = [start, full] needs 0 <= start < full <= 90");
      model_.fade = {fade[0] * tables::kDegToRad, fade[1] * tables::kDegToRad};
    }
    if (const toml::node* n = c->get("max_iterations")) {
      const auto v = n->value<int64_t>();
      if (!v || *v < 1 || *v > 100) throw LoadError(where(*n), "max_iterations must be an integer from 1 to 100");
      model_.solver.max_iterations = static_cast<int>(*v);
    }
  }

  // [stiffness]: X = { compliance_um_per_N = 0.02 } or, position-dependent,
  // Z = { position_mm = [-300, 0], compliance_um_per_N = [0.05, 0.03] }.
  void read_stiffness(const toml::table& root) {
    model_.compliance.assign(static_cast<std::size_t>(model_.joint_count()), AxisCompliance{});
    const toml::table* t = table(root, "stiffness", false, "");
    if (!t) return;
    for (const auto& [key, node] : *t) {
      const std::string letter(key.str());
      const int j = letter.size() == 1 ? model_.joint_of(letter[0]) : -1;
      if (j < 0 || model_.axes[static_cast<std::size_t>(j)].type != AxisType::Linear)
        throw LoadError(where(key.source()), "'" + letter + "' in [stiffness] is not a linear axis of this machine (" +
                                                 model_.coordinates() + ")");
      const toml::table* axis = node.as_table();
      if (!axis) throw LoadError(where(node), "[stiffness] " + letter + " must be a table");
      const std::string context = "[stiffness] " + letter;
      check_keys(*axis, context, {"position_mm", "compliance_um_per_N"});
      AxisCompliance& c = model_.compliance[static_cast<std::size_t>(j)];
      const toml::node* values = axis->get("compliance_um_per_N");
      if (!values) throw LoadError(where(*axis), context + " needs 'compliance_um_per_N'");
      if (values->is_array()) {
        const toml::node* positions = axis->get("position_mm");
        const std::size_t n = values->as_array()->size();
        if (!positions) throw LoadError(where(*values), "a list of compliances needs 'position_mm' of the same length");
        c.position_mm = numbers(*axis, "position_mm", n, true, context);
        c.mm_per_N = numbers(*axis, "compliance_um_per_N", n, true, context);
        for (std::size_t i = 1; i < n; ++i)
          if (!(c.position_mm[i] > c.position_mm[i - 1]))
            throw LoadError(where(*positions), "position_mm must increase");
      } else {
        if (axis->get("position_mm"))
          throw LoadError(where(*axis->get("position_mm")), "position_mm needs a list of compliances");
        c.mm_per_N = {scalar(*values, "compliance_um_per_N")};
      }
      for (double& v : c.mm_per_N) {
        if (v < 0) throw LoadError(where(*values), "a compliance cannot be negative");
        v *= 1e-3;  // um/N -> mm/N
      }
    }
  }

  struct PendingTables {
    int axis_order;  // position in axes_read_ (before joint ordering)
    const toml::array* tables;
  };

  void read_chain(const toml::table& root, std::string_view key, Chain chain) {
    const toml::node* n = root.get(key);
    if (!n) return;
    const toml::array* list = n->as_array();
    if (!list || !list->is_array_of_tables())
      throw LoadError(where(*n),
                      std::string("'") + std::string(key) + "' must be a list of axes: [[" + std::string(key) + "]]");
    std::vector<int>& chain_list = chain == Chain::Tool ? tool_order_ : part_order_;
    for (const toml::node& item : *list) {
      const toml::table& t = *item.as_table();
      const std::string context = "[[" + std::string(key) + "]]";
      check_keys(t, context,
                 {"axis", "type", "direction", "pole_mm", "travel_mm", "travel_deg", "location", "tables", "thermal"});
      Axis axis{};
      const std::string letter = text(t, "axis", true, context);
      if (letter.size() != 1 || tables::kAxisLetters.find(letter[0]) == std::string_view::npos)
        throw LoadError(where(*t.get("axis")), "axis '" + letter + "' must be one upper-case letter of XYZABCUVW");
      axis.letter = letter[0];
      for (const Axis& other : model_.axes)
        if (other.letter == axis.letter) throw LoadError(where(*t.get("axis")), "axis " + letter + " appears twice");
      const std::string type = text(t, "type", true, context);
      if (type != "linear" && type != "rotary")
        throw LoadError(where(*t.get("type")), "type must be \"linear\" or \"rotary\"");
      axis.type = type == "linear" ? AxisType::Linear : AxisType::Rotary;
      axis.chain = chain;
      const Vector3d dir = vec3(t, "direction", true, context);
      if (!(dir.norm() > 1e-9)) throw LoadError(where(*t.get("direction")), "direction must not be zero");
      axis.direction = dir.normalized();
      axis.pole_mm = vec3(t, "pole_mm", true, context);
      const char* travel_key = axis.type == AxisType::Linear ? "travel_mm" : "travel_deg";
      const char* wrong_key = axis.type == AxisType::Linear ? "travel_deg" : "travel_mm";
      if (t.get(wrong_key))
        throw LoadError(where(*t.get(wrong_key)), std::string("a ") + type + " axis gives its travel as " + travel_key);
      const auto travel = numbers(t, travel_key, 2, true, context);
      if (!(travel[0] < travel[1]))
        throw LoadError(where(*t.get(travel_key)), std::string(travel_key) + " = [min, max] needs min < max");
      axis.travel_min = travel[0];
      axis.travel_max = travel[1];
      read_location(table(t, "location", false, ""), axis.letter, axis.location_mm, axis.location_rad);
      axis.real_base = line_placement(axis.pole_mm, axis.location_mm, axis.location_rad);
      read_thermal(t, axis, context);
      const toml::node* tl = t.get("tables");
      if (tl && !(tl->is_array() && tl->as_array()->is_array_of_tables()))
        throw LoadError(where(*tl), "'tables' must be a list: [[" + std::string(key) + ".tables]]");
      chain_list.push_back(static_cast<int>(model_.axes.size()));
      pending_.push_back({static_cast<int>(model_.axes.size()), tl ? tl->as_array() : nullptr});
      axis_source_.push_back(where(t));
      model_.axes.push_back(axis);
    }
  }

  // Puts axes in LinuxCNC's coordinate order (XYZABCUVW) and checks the machine's shape.
  void order_joints(const toml::table& root) {
    const int n = static_cast<int>(model_.axes.size());
    std::vector<int> order(n);
    for (int i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return tables::kAxisLetters.find(model_.axes[a].letter) < tables::kAxisLetters.find(model_.axes[b].letter);
    });
    std::vector<int> joint_of_read(n);
    std::vector<Axis> axes;
    for (int j = 0; j < n; ++j) {
      joint_of_read[order[j]] = j;
      axes.push_back(model_.axes[order[j]]);
    }
    model_.axes = axes;
    for (int i : tool_order_) model_.tool_chain.push_back(joint_of_read[i]);
    for (int i : part_order_) model_.workpiece_chain.push_back(joint_of_read[i]);
    for (PendingTables& p : pending_) p.axis_order = joint_of_read[p.axis_order];
    std::vector<SourceLocation> sources(n);
    for (int i = 0; i < n; ++i) sources[joint_of_read[i]] = axis_source_[i];
    axis_source_ = sources;

    int linear = 0;
    for (const Axis& a : model_.axes) linear += a.type == AxisType::Linear;
    if (linear != 3)
      throw LoadError(where(root),
                      "the machine has " + std::to_string(linear) + " linear axes; the model needs exactly 3");
    if (model_.rotary_count() > 2)
      throw LoadError(where(root), "the machine has " + std::to_string(model_.rotary_count()) +
                                       " rotary axes; the correction handles at most 2");
  }

  // The three linear axes must span space, or no correction can be solved.
  void check_axes_span(const toml::table& root) const {
    Joints mid(model_.joint_count());
    for (int j = 0; j < model_.joint_count(); ++j)
      mid[j] = 0.5 * (model_.axes[j].travel_min + model_.axes[j].travel_max);
    PoseDerivatives d;
    tool_pose(model_, Machine::Ideal, mid, model_.tool_length_mm, d);
    Eigen::Matrix3d j3;
    int c = 0;
    for (int j = 0; j < model_.joint_count(); ++j)
      if (model_.axes[j].type == AxisType::Linear) j3.col(c++) = d.tip.col(j);
    if (std::abs(j3.determinant()) < 1e-6)
      throw LoadError(where(root), "the directions of the linear axes do not span space");
  }

  // ---- error tables ----------------------------------------------------------------------
  void load_tables(const PendingTables& pending) {
    if (!pending.tables) return;
    const int joint = pending.axis_order;
    Axis& axis = model_.axes[joint];
    const fs::path base = fs::path(path()).parent_path();
    std::vector<std::string> listed;
    for (const toml::node& item : *pending.tables) {
      const toml::table& t = *item.as_table();
      const std::string context = std::string("a table of axis ") + axis.letter;
      check_keys(t, context, {"file", "interpolation", "scale", "measured_at_mm"});
      const std::string file = text(t, "file", true, context);
      tables::TableOptions options;
      const std::string interp = text(t, "interpolation", false, context);
      if (t.get("interpolation") && interp != "linear" && interp != "cubic")
        throw LoadError(where(*t.get("interpolation")), "interpolation must be \"linear\" or \"cubic\"");
      options.interpolation = interp == "cubic" ? tables::Interpolation::Cubic : tables::Interpolation::Linear;
      const toml::table* scale = table(t, "scale", false, "");
      if (scale)
        for (auto&& [key, value] : *scale) options.scale[std::string(key.str())] = scalar(value, key.str());
      const std::string table_path = (base / file).lexically_normal().string();
      if (std::find(listed.begin(), listed.end(), table_path) != listed.end())
        throw LoadError(where(*t.get("file")), "table file '" + file + "' is listed twice under axis " +
                                                   std::string(1, axis.letter) + ": its errors would count twice");
      listed.push_back(table_path);
      if (!fs::is_regular_file(table_path))
        throw LoadError(where(*t.get("file")), "table file '" + file + "' not found (looked for " + table_path + ")");
      BoundTable bound(tables::load_table(table_path, options));
      bind(bound, axis, where(*t.get("file")));
      bound.file_line = where(*t.get("file")).line;
      if (scale)
        for (auto&& [key, value] : *scale) {
          bool found = false;
          for (const auto& c : bound.table.columns()) found |= c.symbol.name() == key.str();
          if (!found)
            throw LoadError(where(key.source()),
                            "scale names " + std::string(key.str()) + ", which is not a column of " + table_path);
        }
      if (const toml::node* m = t.get("measured_at_mm"))
        rereference(bound, axis, vec3(t, "measured_at_mm", true, context), where(*m));
      warn_if_short(bound);
      for (std::size_t v = 0; v < bound.table.grid().size(); ++v)
        if (bound.joint[v] >= 0) axis.moved_by |= 1u << bound.joint[v];
      axis.tables.push_back(static_cast<int>(model_.tables.size()));
      model_.tables.push_back(std::move(bound));
    }
  }

  // Ties the table's grid variables to joints. Problems are reported in the CSV file, where
  // they are, naming the machine-file line that lists the table.
  void bind(BoundTable& bound, const Axis& axis, const SourceLocation& listed_at) const {
    const std::string listed = " (table listed at " + listed_at.to_string() + ")";
    const auto& grid = bound.table.grid();
    for (std::size_t v = 0; v < grid.size(); ++v) {
      if (grid[v].is_temperature()) {
        bound.joint[v] = -1;
        bound.input[v] = bind_temperature(grid[v], listed);
        continue;
      }
      const int j = model_.joint_of(grid[v].axis);
      if (j < 0)
        throw LoadError(grid[v].where, std::string("grid variable ") + static_cast<char>(std::tolower(grid[v].axis)) +
                                           " is not an axis of this machine (" + model_.coordinates() + ")" + listed);
      if (grid[v].rotary != (model_.axes[j].type == AxisType::Rotary))
        throw LoadError(grid[v].where,
                        std::string("axis ") + grid[v].axis + " is " +
                            (grid[v].rotary ? "linear: its positions are in mm" : "rotary: its positions are in deg") +
                            listed);
      bound.joint[v] = j;
    }
    for (const auto& c : bound.table.columns())
      if (c.symbol.axis != axis.letter)
        throw LoadError(c.where, c.symbol.name() + " is an error of axis " + c.symbol.axis +
                                     ", but this table is listed under axis " + axis.letter + listed);
  }

  // A temperature grid variable names an input of [temperatures], and its grid covers the
  // input's range: the model must hold wherever the input may be (volkins holds the last good
  // value outside it), and a table does not extrapolate (it would hold its end value).
  int bind_temperature(const tables::GridVariable& g, const std::string& listed) const {
    const int i = model_.temperature_of(g.temperature);
    if (i < 0) {
      std::string names;
      for (const TemperatureInput& t : model_.temperatures) names += (names.empty() ? "" : ", ") + t.name;
      throw LoadError(g.where, "temperature '" + g.temperature +
                                   "' is not an input of the machine file's [temperatures] (" +
                                   (names.empty() ? "it has none" : "it has: " + names) + ")" + listed);
    }
    const TemperatureInput& t = model_.temperatures[static_cast<std::size_t>(i)];
    if (g.nodes.front() > t.min_degC || g.nodes.back() < t.max_degC)
      throw LoadError(g.where, "the table covers " + g.temperature + " = " + number(g.nodes.front()) + " .. " +
                                   number(g.nodes.back()) + " degC but the input's range is " + number(t.min_degC) +
                                   " .. " + number(t.max_degC) +
                                   " degC: a temperature grid must cover min_degC .. max_degC (extend the table or "
                                   "narrow the range)" +
                                   listed);
    return i;
  }

  // A table measured at p_meas instead of the pole, node by node (model.md, exact):
  //     delta_pole = delta_meas - (R(eps) - I) * (p_meas - p_pole)
  // eps is the table's own angular columns at the same node.
  void rereference(BoundTable& bound, const Axis& axis, const Vector3d& offset, const SourceLocation& at) const {
    tables::ErrorTable& table = bound.table;
    if (table.grid().size() != 1 || table.grid()[0].axis != axis.letter)
      throw LoadError(at, std::string("measured_at_mm applies to a table over the axis's own position (") +
                              static_cast<char>(std::tolower(axis.letter)) + ") only");
    const auto& columns = table.columns();
    bool has_angles = false;
    for (const auto& c : columns) has_angles |= c.symbol.component >= 3;
    if (!has_angles)
      throw LoadError(at, std::string("measured_at_mm needs the angular errors (EA") + axis.letter + ", EB" +
                              axis.letter + ", EC" + axis.letter +
                              ") in the same table, to move its translations to the pole");
    for (int node = 0; node < table.node_count(); ++node) {
      Vector3d eps = Vector3d::Zero();
      for (std::size_t c = 0; c < columns.size(); ++c)
        if (columns[c].symbol.component >= 3) eps[columns[c].symbol.component - 3] = table.value(node, c);
      const Vector3d shift = (rotation_xyz(eps) - Eigen::Matrix3d::Identity()) * offset;
      for (std::size_t c = 0; c < columns.size(); ++c)
        if (columns[c].symbol.component < 3)
          table.set_value(node, static_cast<int>(c), table.value(node, c) - shift[columns[c].symbol.component]);
    }
    // Translation columns missing from the file get no correction: say so rather than guess.
    for (int k = 0; k < 3; ++k) {
      bool present = false;
      for (const auto& c : columns) present |= c.symbol.component == k;
      if (!present && std::abs(offset[(k + 1) % 3]) + std::abs(offset[(k + 2) % 3]) > 0.0)
        throw LoadError(at, "measured_at_mm moves " + tables::ErrorSymbol{k, axis.letter, false}.name() +
                                ", which the table does not have: add the column (zeros if not measured)");
    }
  }

  void warn_if_short(const BoundTable& bound) {
    const auto& grid = bound.table.grid();
    for (std::size_t v = 0; v < grid.size(); ++v) {
      if (grid[v].periodic || bound.joint[v] < 0) continue;  // (a temperature grid covers its range: bind_temperature)
      const Axis& a = model_.axes[bound.joint[v]];
      const double lo = grid[v].nodes.front(), hi = grid[v].nodes.back();
      if (a.travel_min < lo - 1e-9 || a.travel_max > hi + 1e-9) {
        const char* unit = grid[v].rotary ? " deg" : " mm";
        model_.warnings.push_back(
            {grid[v].where, std::string("the table covers ") + static_cast<char>(std::tolower(a.letter)) + " = " +
                                number(lo) + " .. " + number(hi) + unit + " but the travel is " + number(a.travel_min) +
                                " .. " + number(a.travel_max) + unit + ": end values are held outside the table"});
      }
    }
  }

  Model model_;
  std::vector<int> tool_order_, part_order_;
  std::vector<PendingTables> pending_;
  std::vector<SourceLocation> axis_source_;
  SourceLocation tool_axis_at_;  // [spindle] tool_axis_coordinate, where given
};

}  // namespace

Model load_machine(const std::string& path) { return MachineReader(path).read(); }

}  // namespace vc::machine
