#include "vc/acceptance/plan_file.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "vc/machine/toml_file.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::acceptance {
namespace {

std::string list(const Eigen::Vector3d& v) {
  return "[" + number_text(v[0]) + ", " + number_text(v[1]) + ", " + number_text(v[2]) + "]";
}

// A TOML string, quoted and escaped as toml++ writes one (a path may hold \ or ").
std::string quoted(const std::string& text) {
  std::ostringstream out;
  out << toml::value<std::string>(text);
  return out.str();
}

std::vector<double> numbers(const machine::TomlFile& file, const toml::table& t, std::string_view key,
                            const std::string& context, std::size_t size = 0) {
  const toml::node* n = file.get(t, key, true, context);
  const toml::array* a = n->as_array();
  if (!a) throw LoadError(file.where(*n), "'" + std::string(key) + "' must be an array of numbers");
  if (size && a->size() != size)
    throw LoadError(file.where(*n), "'" + std::string(key) + "' needs " + std::to_string(size) + " numbers");
  std::vector<double> out;
  for (const toml::node& x : *a) out.push_back(file.scalar(x, key));
  return out;
}

Eigen::Vector3d vector3(const machine::TomlFile& file, const toml::table& t, std::string_view key,
                        const std::string& context) {
  const std::vector<double> v = numbers(file, t, key, context, 3);
  return {v[0], v[1], v[2]};
}

// The laser lines of the array `name` ([[diagonal]] or [[axis_run]]), each checked.
std::vector<Diagonal> lines(const machine::TomlFile& file, const std::string& name) {
  std::vector<Diagonal> out;
  const std::string table = "[[" + name + "]]";
  if (const toml::node* n = file.root().get(name)) {
    const toml::array* a = n->as_array();
    if (!a) throw LoadError(file.where(*n), "'" + name + "' must be an array of tables, " + table);
    for (const toml::node& item : *a) {
      const toml::table* t = item.as_table();
      if (!t) throw LoadError(file.where(item), "'" + name + "' must be an array of tables, " + table);
      file.check_keys(*t, table,
                      {"name", "kind", "start_mm", "end_mm", "targets_mm", "program", "sheet", "measurements"});
      Diagonal d;
      d.name = file.text(*t, "name", true, table);
      d.kind = file.text(*t, "kind", true, table);
      if (d.axis_run() != (name == "axis_run"))
        throw LoadError(file.where(*t->get("kind")), d.name + ": kind '" + d.kind + "' in " + table +
                                                         (name == "axis_run" ? ": 'axis X', 'axis Y' or 'axis Z'"
                                                                             : ": an axis run belongs in [[axis_run]]"));
      d.start_mm = vector3(file, *t, "start_mm", table);
      d.end_mm = vector3(file, *t, "end_mm", table);
      d.targets_mm = numbers(file, *t, "targets_mm", table);
      if (d.targets_mm.size() < 5)
        throw LoadError(file.where(*t), d.name + ": fewer than 5 targets (ISO 230-2 asks for at least 5)");
      if (!(d.length_mm() > 0)) throw LoadError(file.where(*t), d.name + ": start and end are the same point");
      // Distances from the start, increasing, on the line (the last may round past its end by 0.5 um).
      const toml::node& targets = *t->get("targets_mm");
      for (std::size_t i = 0; i < d.targets_mm.size(); ++i)
        if (d.targets_mm[i] < 0 || d.targets_mm[i] > d.length_mm() + 1e-3 || (i && !(d.targets_mm[i] > d.targets_mm[i - 1])))
          throw LoadError(file.where(targets), d.name + ": target " + std::to_string(i + 1) + " (" +
                                                   number_text(d.targets_mm[i]) +
                                                   " mm) is not an increasing distance from 0 to the length " +
                                                   fixed_text(d.length_mm(), 3) + " mm");
      out.push_back(d);
    }
  }
  return out;
}

}  // namespace

std::string program_path(const Diagonal& d) { return (d.axis_run() ? "axes/" : "diagonals/") + d.name + ".ngc"; }
std::string sheet_path(const Diagonal& d) { return (d.axis_run() ? "axes/" : "diagonals/") + d.name + ".md"; }
std::string measurements_name(const Diagonal& d) { return d.name + ".csv"; }
std::string program_path(const Circle& c) { return "circles/" + c.name + ".ngc"; }
std::string sheet_path(const Circle& c) { return "circles/" + c.name + ".md"; }
std::string measurements_name(const Circle& c) { return c.name + ".csv"; }

std::vector<const Diagonal*> laser_lines(const Plan& plan) {
  std::vector<const Diagonal*> lines;
  for (const Diagonal& d : plan.diagonals) lines.push_back(&d);
  for (const Diagonal& d : plan.axis_runs) lines.push_back(&d);
  return lines;
}

std::string plan_toml(const Plan& p) {
  const DiagonalSettings& s = p.settings;
  std::ostringstream out;
  out << "# volcomp acceptance plan: the tests of " << p.machine << " (lengths mm, angles deg, feed mm/min, dwell s)\n"
      << "# X, Y, Z are the machine's joints (LinuxCNC's axes world); distances along a line from its start.\n"
      << "[plan]\n"
      << "machine = " << quoted(p.machine) << "\n"
      << "coordinates = " << quoted(p.coordinates) << "\n"
      << "tool_length_mm = " << number_text(s.tool_length_mm) << "  # the tool-side optic below the gauge point\n"
      << "tool_offset_mm = " << number_text(p.tool_offset_mm) << "  # the programs' G43.1 Z\n"
      << "rest = [";
  for (int k = 0; k < p.rest.size(); ++k) out << (k ? ", " : "") << number_text(p.rest[k]);
  out << "]  # every joint in the machine's order; X, Y, Z move along the lines\n"
      << "volume_mm = [";
  for (int i = 0; i < 3; ++i)
    out << (i ? ", " : "") << "[" << number_text(s.volume.low_mm[i]) << ", " << number_text(s.volume.high_mm[i]) << "]";
  out << "]\n"
      << "feed_mm_per_min = " << number_text(s.feed_mm_per_min) << "\n"
      << "dwell_s = " << number_text(s.dwell_s) << "\n"
      << "overrun_mm = " << number_text(s.overrun_mm) << "\n"
      << "runs = " << s.runs << "\n"
      << "targets = " << s.targets << "\n"
      << "seed = " << s.seed << "\n";
  for (const Diagonal* line : laser_lines(p)) {
    const Diagonal& d = *line;
    out << (d.axis_run() ? "\n[[axis_run]]  # ISO 230-2\n" : "\n[[diagonal]]  # ISO 230-6\n")
        << "name = " << quoted(d.name) << "\n"
        << "kind = " << quoted(d.kind) << "\n"
        << "start_mm = " << list(d.start_mm) << "\n"
        << "end_mm = " << list(d.end_mm) << "\n"
        << "targets_mm = [";
    for (std::size_t i = 0; i < d.targets_mm.size(); ++i) out << (i ? ", " : "") << number_text(d.targets_mm[i]);
    out << "]\n"
        << "program = \"" << program_path(d) << "\"\n"
        << "sheet = \"" << sheet_path(d) << "\"\n"
        << "measurements = \"" << measurements_name(d) << "\"\n";
  }
  if (!p.rtest.empty()) {
    const auto joints = [](const std::vector<machine::Joints>& poses) {
      std::string text = "[";
      for (std::size_t k = 0; k < poses.size(); ++k) {
        text += k ? ", [" : "[";
        for (int j = 0; j < poses[k].size(); ++j) text += (j ? ", " : "") + number_text(poses[k][j]);
        text += "]";
      }
      return text + "]";
    };
    out << "\n[rtest]  # ISO 10791-6\n"
        << "sphere_joints_mm = " << list(p.rtest.sphere_joints_mm) << "\n"
        << "sphere_mm = " << list(p.rtest.sphere_mm) << "\n"
        << "program = \"" << kRTestProgram << "\"\nsheet = \"" << kRTestSheet << "\"\nmeasurements = \""
        << kRTestMeasurements << "\"\n";
    for (const RTestSequence& q : p.rtest.sequences)
      out << "\n[[rtest.sequence]]\nname = " << quoted(q.name) << "\nleft_out = " << q.left_out
          << "\nposes = " << joints(q.poses) << "\nretracts = " << joints(q.retracts) << "\n";
  }
  for (const Circle& c : p.circles)
    out << "\n[[circle]]  # ISO 230-4\n"
        << "name = " << quoted(c.name) << "\n"
        << "plane = " << quoted(c.plane) << "\n"
        << "centre_mm = " << list(c.centre_mm) << "\n"
        << "radius_mm = " << number_text(c.radius_mm) << "\n"
        << "program = \"" << program_path(c) << "\"\n"
        << "sheet = \"" << sheet_path(c) << "\"\n"
        << "measurements = \"" << measurements_name(c) << "\"\n";
  return out.str();
}

Plan read_plan(const std::string& dir) { return read_plan_file((std::filesystem::path(dir) / "plan.toml").string()); }

Plan read_plan_file(const std::string& path) {
  const machine::TomlFile file(path);
  Plan p;
  const toml::table& plan = *file.table(file.root(), "plan", true, "an acceptance plan");
  file.check_keys(plan, "[plan]",
                  {"machine", "coordinates", "tool_length_mm", "tool_offset_mm", "rest", "volume_mm",
                   "feed_mm_per_min", "dwell_s", "overrun_mm", "runs", "targets", "seed"});
  p.machine = file.text(plan, "machine", true, "[plan]");
  p.coordinates = file.text(plan, "coordinates", true, "[plan]");
  DiagonalSettings& s = p.settings;
  s.tool_length_mm = file.scalar(*file.get(plan, "tool_length_mm", true, "[plan]"), "tool_length_mm");
  p.tool_offset_mm = file.scalar(*file.get(plan, "tool_offset_mm", true, "[plan]"), "tool_offset_mm");
  const std::vector<double> rest = numbers(file, plan, "rest", "[plan]", p.coordinates.size());
  p.rest.resize(static_cast<Eigen::Index>(rest.size()));
  for (std::size_t k = 0; k < rest.size(); ++k) p.rest[static_cast<Eigen::Index>(k)] = rest[k];
  const toml::node* volume = file.get(plan, "volume_mm", true, "[plan]");
  const toml::array* ranges = volume->as_array();
  if (!ranges || ranges->size() != 3) throw LoadError(file.where(*volume), "'volume_mm' is [[x0, x1], [y0, y1], [z0, z1]]");
  for (std::size_t i = 0; i < 3; ++i) {
    const toml::array* r = (*ranges)[i].as_array();
    if (!r || r->size() != 2) throw LoadError(file.where(*volume), "'volume_mm' is [[x0, x1], [y0, y1], [z0, z1]]");
    s.volume.low_mm[static_cast<int>(i)] = file.scalar((*r)[0], "volume_mm");
    s.volume.high_mm[static_cast<int>(i)] = file.scalar((*r)[1], "volume_mm");
  }
  s.feed_mm_per_min = file.scalar(*file.get(plan, "feed_mm_per_min", true, "[plan]"), "feed_mm_per_min");
  s.dwell_s = file.scalar(*file.get(plan, "dwell_s", true, "[plan]"), "dwell_s");
  s.overrun_mm = file.scalar(*file.get(plan, "overrun_mm", true, "[plan]"), "overrun_mm");
  // A whole number in [low, high], checked before the cast (a double out of int's range is undefined).
  const auto whole = [&](std::string_view key, double low, double high) {
    const toml::node* n = file.get(plan, key, true, "[plan]");
    const double v = file.scalar(*n, key);
    if (v != std::floor(v) || v < low || v > high)
      throw LoadError(file.where(*n), "'" + std::string(key) + "' must be a whole number from " + number_text(low) +
                                          " to " + number_text(high));
    return v;
  };
  s.runs = static_cast<int>(whole("runs", 2, 1000));
  s.targets = static_cast<int>(whole("targets", 5, 100000));
  s.seed = static_cast<unsigned>(whole("seed", 0, 4294967295.0));

  p.diagonals = lines(file, "diagonal");
  p.axis_runs = lines(file, "axis_run");
  if (const toml::node* n = file.root().get("circle")) {
    const toml::array* a = n->as_array();
    if (!a) throw LoadError(file.where(*n), "'circle' must be an array of tables, [[circle]]");
    for (const toml::node& item : *a) {
      const toml::table* t = item.as_table();
      if (!t) throw LoadError(file.where(item), "'circle' must be an array of tables, [[circle]]");
      file.check_keys(*t, "[[circle]]", {"name", "plane", "centre_mm", "radius_mm", "program", "sheet", "measurements"});
      Circle c;
      c.name = file.text(*t, "name", true, "[[circle]]");
      c.plane = file.text(*t, "plane", true, "[[circle]]");
      if (c.plane != "XY" && c.plane != "YZ" && c.plane != "ZX")
        throw LoadError(file.where(*t->get("plane")), c.name + ": the plane is XY, YZ or ZX, not '" + c.plane + "'");
      c.centre_mm = vector3(file, *t, "centre_mm", "[[circle]]");
      const toml::node* r = file.get(*t, "radius_mm", true, "[[circle]]");
      c.radius_mm = file.scalar(*r, "radius_mm");
      if (!(c.radius_mm > 0)) throw LoadError(file.where(*r), c.name + ": the radius must be > 0 mm");
      p.circles.push_back(c);
    }
  }
  if (const toml::table* r = file.table(file.root(), "rtest", false, "")) {
    file.check_keys(*r, "[rtest]", {"sphere_joints_mm", "sphere_mm", "program", "sheet", "measurements", "sequence"});
    p.rtest.sphere_joints_mm = vector3(file, *r, "sphere_joints_mm", "[rtest]");
    p.rtest.sphere_mm = vector3(file, *r, "sphere_mm", "[rtest]");
    const toml::node* n = file.get(*r, "sequence", true, "[rtest]");
    const toml::array* a = n->as_array();
    if (!a || a->empty()) throw LoadError(file.where(*n), "'sequence' must be an array of tables, [[rtest.sequence]]");
    // An array of poses, each every joint of the plan's machine.
    const auto poses = [&](const toml::table& t, std::string_view key) {
      const toml::node* list = file.get(t, key, true, "[[rtest.sequence]]");
      const toml::array* rows = list->as_array();
      if (!rows || rows->empty()) throw LoadError(file.where(*list), "'" + std::string(key) + "' must be [[joints...], ...]");
      std::vector<machine::Joints> out;
      for (const toml::node& row : *rows) {
        const toml::array* values = row.as_array();
        if (!values || values->size() != p.coordinates.size())
          throw LoadError(file.where(row), "'" + std::string(key) + "': each pose has " +
                                               std::to_string(p.coordinates.size()) + " joints (" + p.coordinates + ")");
        machine::Joints q(static_cast<Eigen::Index>(values->size()));
        for (std::size_t j = 0; j < values->size(); ++j) q[static_cast<Eigen::Index>(j)] = file.scalar((*values)[j], key);
        out.push_back(q);
      }
      return out;
    };
    for (const toml::node& item : *a) {
      const toml::table* t = item.as_table();
      if (!t) throw LoadError(file.where(item), "'sequence' must be an array of tables, [[rtest.sequence]]");
      file.check_keys(*t, "[[rtest.sequence]]", {"name", "left_out", "poses", "retracts"});
      RTestSequence q;
      q.name = file.text(*t, "name", true, "[[rtest.sequence]]");
      const toml::node* left = file.get(*t, "left_out", true, "[[rtest.sequence]]");
      const double left_out = file.scalar(*left, "left_out");
      if (left_out != std::floor(left_out) || left_out < 0 || left_out > 1000)  // checked before the cast
        throw LoadError(file.where(*left), "'left_out' must be a whole number from 0 to 1000");
      q.left_out = static_cast<int>(left_out);
      q.poses = poses(*t, "poses");
      q.retracts = poses(*t, "retracts");
      if (q.poses.size() != q.retracts.size())
        throw LoadError(file.where(*t), q.name + ": " + std::to_string(q.poses.size()) + " poses but " +
                                            std::to_string(q.retracts.size()) + " retracts");
      p.rtest.sequences.push_back(q);
    }
  }
  if (p.diagonals.empty() && p.axis_runs.empty() && p.circles.empty() && p.rtest.empty())
    throw LoadError({file.path()}, "no test in the plan: no [[diagonal]], [[axis_run]], [[circle]] or [rtest]");
  return p;
}

}  // namespace vc::acceptance
