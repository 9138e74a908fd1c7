#include "vc/fit_tables/table_set.hpp"

#include <cmath>
#include <stdexcept>

#include "vc/fit_tables/interpolation.hpp"

namespace vc::fit_tables {
namespace {

constexpr double kArcsecToRad = M_PI / (180.0 * 3600.0);

std::string letter(const machine::Model& model, int joint) {
  return std::string(1, model.axes[static_cast<std::size_t>(joint)].letter);
}

bool is_rotary(const machine::Model& model, int joint) {
  return model.axes[static_cast<std::size_t>(joint)].type == machine::AxisType::Rotary;
}

// The ISO 230-1 component letter of a direction or rotation named by an axis letter (X Y Z A B
// C), or 0 for the others (U V W have no symbols of their own in the model).
char component(char axis_letter) {
  return std::string("XYZABC").find(axis_letter) != std::string::npos ? axis_letter : 0;
}

// The rotation about the direction perpendicular to two of X Y Z: XY -> C, YZ -> A, XZ -> B.
char rotation_between(char a, char b) {
  const std::string xyz = "XYZ";
  if (xyz.find(a) == std::string::npos || xyz.find(b) == std::string::npos) return 0;
  for (char p : xyz)
    if (p != a && p != b) return static_cast<char>('A' + (p - 'X'));
  return 0;
}

std::vector<std::string> own_deviations(const machine::Model& model, const Table& t) {
  const char in = model.axes[static_cast<std::size_t>(t.input)].letter;
  const char out = model.axes[static_cast<std::size_t>(t.output)].letter;
  switch (t.kind) {
    case TableKind::Positioning:
      if (component(in)) return {std::string("E") + in + in};
      return {};
    case TableKind::Cross:
      if (component(in) && component(out)) return {std::string("E") + out + in};
      return {};
    case TableKind::Squareness: {
      const char r = rotation_between(in, out);
      if (!r) return {};
      return {std::string("E") + r + "0" + in, std::string("E") + r + "0" + out};
    }
  }
  return {};
}

bool same_table(const Table& a, const Table& b) {
  return a.kind == b.kind && a.input == b.input && a.output == b.output;
}

}  // namespace

std::string TableSet::name(const machine::Model& model, const Table& t) const {
  switch (t.kind) {
    case TableKind::Positioning:
      return letter(model, t.input);
    case TableKind::Cross:
      return letter(model, t.input) + "->" + letter(model, t.output);
    case TableKind::Squareness:
      return "sq " + letter(model, t.input) + "->" + letter(model, t.output);
  }
  return "?";
}

TableSet resolve_tables(const Controller& controller, const machine::Model& model, std::optional<int> nodes) {
  TableSet set;
  auto add = [&](const TableSpec& spec, int input, int output) {
    Table t;
    t.kind = spec.kind;
    t.input = input;
    t.output = output;
    t.direction_dependent = spec.direction_dependent;
    const std::string what = std::string(kind_name(spec.kind)) + " table " + letter(model, input) +
                             (spec.kind == TableKind::Positioning ? "" : "->" + letter(model, output));
    for (const Table& other : set.tables)
      if (same_table(other, t)) {
        set.notes.push_back(spec.where.to_string() + ": the " + what + " is listed twice: used once");
        return;
      }
    if (spec.kind == TableKind::Squareness) {
      if (is_rotary(model, input) || is_rotary(model, output)) {
        set.notes.push_back(spec.where.to_string() + ": " + what + " skipped: a squareness joins two linear axes");
        return;
      }
      t.resolution = spec.resolution_arcsec * kArcsecToRad;
    } else {
      const int count = nodes.value_or(spec.default_nodes);
      if (count < 2 || count > spec.max_nodes)
        throw std::invalid_argument("--nodes " + std::to_string(count) + ": the " + what + " of " + controller.name +
                                    " takes 2 .. " + std::to_string(spec.max_nodes) + " nodes");
      const machine::Axis& axis = model.axes[static_cast<std::size_t>(input)];
      const double span = axis.travel_max - axis.travel_min;
      t.modulo = spec.modulo && axis.type == machine::AxisType::Rotary && std::abs(span - 360.0) < 1e-9;
      if (t.modulo && count < 3)
        throw std::invalid_argument("--nodes " + std::to_string(count) + ": the modulo " + what +
                                    " needs at least 3 nodes (its first and last are one)");
      t.nodes = equally_spaced(axis.travel_min, axis.travel_max, count);
      t.resolution = is_rotary(model, output) ? spec.resolution_deg : spec.resolution_um * 1e-3;
    }
    t.own_deviations = own_deviations(model, t);
    t.first_unknown = set.unknowns;
    set.unknowns += t.unknowns();
    set.tables.push_back(std::move(t));
  };

  for (const TableSpec& spec : controller.tables) {
    if (spec.kind == TableKind::Positioning) {
      if (spec.input == "all") {
        for (int j = 0; j < model.joint_count(); ++j) add(spec, j, j);
        continue;
      }
      const int j = model.joint_of(spec.input[0]);
      if (j < 0) {
        set.notes.push_back(spec.where.to_string() + ": positioning table " + spec.input +
                            " skipped: " + model.info.name + " has no axis " + spec.input);
        continue;
      }
      add(spec, j, j);
      continue;
    }
    const int in = model.joint_of(spec.input[0]), out = model.joint_of(spec.output[0]);
    if (in < 0 || out < 0) {
      set.notes.push_back(spec.where.to_string() + ": " + kind_name(spec.kind) + " table " + spec.input + "->" +
                          spec.output + " skipped: " + model.info.name + " has no axis " +
                          (in < 0 ? spec.input : spec.output));
      continue;
    }
    add(spec, in, out);
  }
  return set;
}

void contributions(const TableSet& set, const machine::Joints& q, std::vector<Contribution>& out) {
  out.clear();
  for (const Table& t : set.tables) {
    const double at = q[t.input];
    if (t.kind == TableKind::Squareness) {
      out.push_back({t.first_unknown, t.output, at});
      continue;
    }
    const NodeWeights w = node_weights(t.nodes, t.modulo, at);
    out.push_back({t.unknown_of_node(w.low), t.output, w.w_low});
    if (w.w_high != 0.0) out.push_back({t.unknown_of_node(w.high), t.output, w.w_high});
  }
}

machine::Joints compensated(const TableSet& set, const Eigen::VectorXd& x, const machine::Joints& q) {
  std::vector<Contribution> c;
  contributions(set, q, c);
  machine::Joints out = q;
  for (const Contribution& k : c) out[k.joint] += k.weight * x[k.unknown];
  return out;
}

Eigen::VectorXd rounded(const TableSet& set, const Eigen::VectorXd& x) {
  Eigen::VectorXd out = x;
  for (const Table& t : set.tables) {
    if (t.resolution <= 0) continue;
    for (int k = 0; k < t.unknowns(); ++k) {
      double& v = out[t.first_unknown + k];
      v = std::round(v / t.resolution) * t.resolution;
    }
  }
  return out;
}

}  // namespace vc::fit_tables
