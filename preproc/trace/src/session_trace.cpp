#include "vc/trace/session_trace.hpp"

#include <cctype>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "vc/tables/csv.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::trace {
namespace {

using machine::Joints;

// Two joints of one letter differ by more than this (mm, deg): not driven alike. LinuxCNC
// interpolates both from the same command with the same cubic: they are equal to the bit.
constexpr double kTwinJointTolerance = 1e-9;

// The world position LinuxCNC commanded, as the core's world (TCP: without G43's tool length).
Joints core_world(const machine::Model& model, machine::WorldConvention convention, Joints world, double L) {
  if (convention == machine::WorldConvention::Tcp) world[model.joint_of('Z')] -= L;
  return world;
}

}  // namespace

TraceLayout trace_layout(const machine::Model& model, const std::string& coordinates, double mm_per_unit) {
  TraceLayout layout;
  layout.mm_per_unit = mm_per_unit;
  layout.joints.resize(static_cast<std::size_t>(model.joint_count()));
  const std::string letters = coordinates.empty() ? model.coordinates() : coordinates;
  for (std::size_t k = 0; k < letters.size(); ++k) {
    const int j = model.joint_of(static_cast<char>(std::toupper(static_cast<unsigned char>(letters[k]))));
    if (j >= 0) layout.joints[static_cast<std::size_t>(j)].push_back(static_cast<int>(k));  // else a tool-axis joint
  }
  for (int j = 0; j < model.joint_count(); ++j)
    if (layout.joints[static_cast<std::size_t>(j)].empty())
      throw std::invalid_argument("coordinates=" + letters + " has no joint for the machine's axis " +
                                  model.axes[static_cast<std::size_t>(j)].letter);
  return layout;
}

SessionTrace read_session_trace(const std::string& path, const machine::Model& model, const TraceLayout& layout) {
  const std::vector<tables::CsvRow> rows = tables::read_csv_rows(path, "session trace");
  if (rows.empty()) throw LoadError({path, 1, 1}, "the trace is empty");
  const int n = model.joint_count();
  const std::string axes = model.coordinates();
  // The LinuxCNC joints of each model joint, the principal one first.
  std::vector<std::vector<int>> joints_of = layout.joints;
  if (joints_of.empty())
    for (int j = 0; j < n; ++j) joints_of.push_back({j});
  if (joints_of.size() != static_cast<std::size_t>(n))
    throw std::invalid_argument("the trace layout has " + std::to_string(joints_of.size()) + " joints, the machine " +
                                std::to_string(n));
  std::vector<std::string> wanted;
  for (char a : axes) wanted.emplace_back(1, a);
  for (int j = 0; j < n; ++j) wanted.push_back("j" + std::to_string(joints_of[static_cast<std::size_t>(j)].front()));
  for (const char* extra : {"tool_offset", "controller_time"}) wanted.emplace_back(extra);
  // The other joints of a letter (a gantry's second motor): (model joint, column name).
  std::vector<std::pair<int, std::string>> twins;
  for (int j = 0; j < n; ++j)
    for (std::size_t k = 1; k < joints_of[static_cast<std::size_t>(j)].size(); ++k)
      twins.emplace_back(j, "j" + std::to_string(joints_of[static_cast<std::size_t>(j)][k]));
  for (const auto& twin : twins) wanted.push_back(twin.second);
  // LinuxCNC's units to mm: the linear axes (the rotary ones are deg either way).
  std::vector<double> to_mm(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j)
    to_mm[static_cast<std::size_t>(j)] =
        model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Linear ? layout.mm_per_unit : 1.0;

  std::vector<int> column(wanted.size(), -1);
  const tables::CsvRow& header = rows.front();
  for (std::size_t c = 0; c < header.cells.size(); ++c)
    for (std::size_t w = 0; w < wanted.size(); ++w)
      if (header.cells[c].text == wanted[w]) column[w] = static_cast<int>(c);
  // The tool length offset's column under its former name (traces recorded before the pin
  // volkins.tool-length became volkins.tool-offset), for one release.
  const std::size_t offset_column = 2 * static_cast<std::size_t>(n);
  for (std::size_t c = 0; c < header.cells.size() && column[offset_column] < 0; ++c)
    if (header.cells[c].text == "tool_length") column[offset_column] = static_cast<int>(c);
  for (std::size_t w = 0; w < wanted.size(); ++w)
    if (column[w] < 0)
      throw LoadError({path, header.line, 1},
                      "no column '" + wanted[w] + "' (the machine's axes are " + axes +
                          (w >= static_cast<std::size_t>(n) && w < 2 * static_cast<std::size_t>(n)
                               ? "; " + wanted[w] + " is LinuxCNC's joint of " + axes[w - n]
                               : std::string()) +
                          ")");

  int gain = -1;               // optional: a session without volkins (stock kinematics) has none
  int correction_length = -1;  // optional: traces recorded before volkins slewed the tool length
  int tcp = -1;                // optional: the kinematics type's world, per sample
  int tool_axis = -1;          // optional: the tool-axis coordinate (5axiskins' W)
  const std::string tool_axis_name(1, static_cast<char>(std::tolower(model.tool_axis_coordinate)));
  for (std::size_t c = 0; c < header.cells.size(); ++c) {
    if (header.cells[c].text == "gain") gain = static_cast<int>(c);
    if (header.cells[c].text == "correction_length") correction_length = static_cast<int>(c);
    if (header.cells[c].text == "tcp") tcp = static_cast<int>(c);
    if (model.tool_axis_coordinate && header.cells[c].text == tool_axis_name) tool_axis = static_cast<int>(c);
  }

  // Optional: the filtered temperature each input had (the trace of a machine with [temperatures]).
  std::vector<int> temperature_column(model.temperatures.size(), -1);
  for (std::size_t c = 0; c < header.cells.size(); ++c)
    for (std::size_t i = 0; i < model.temperatures.size(); ++i)
      if (header.cells[c].text == "temperature_" + model.temperatures[i].name)
        temperature_column[i] = static_cast<int>(c);

  SessionTrace t;
  t.path = path;
  t.with_volkins = gain >= 0;
  t.temperature_degC.resize(model.temperatures.size());
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const tables::CsvRow& row = rows[r];
    if (row.cells.size() != header.cells.size())
      throw LoadError({path, row.line, 1}, std::to_string(row.cells.size()) + " cells, the header has " +
                                               std::to_string(header.cells.size()));
    auto value = [&](std::size_t w) { return tables::csv_number(path, row.line, row.cells[column[w]]); };
    Joints world(n), joints(n);
    for (int j = 0; j < n; ++j) {
      world[j] = value(j) * to_mm[static_cast<std::size_t>(j)];
      joints[j] = value(n + j) * to_mm[static_cast<std::size_t>(j)];
    }
    // A gantry's motors are driven alike (volkins gives every joint of a letter its principal's
    // command, as LinuxCNC's identity kinematics do): one that is not is not this configuration.
    for (std::size_t k = 0; k < twins.size(); ++k) {
      const int j = twins[k].first;
      const std::string letter(1, static_cast<char>(std::toupper(static_cast<unsigned char>(axes[j]))));
      const double twin = value(2 * n + 2 + k) * to_mm[static_cast<std::size_t>(j)];
      if (std::abs(twin - joints[j]) > kTwinJointTolerance)
        throw LoadError({path, row.line, row.cells[column[2 * n + 2 + k]].column},
                        twins[k].second + " = " + row.cells[column[2 * n + 2 + k]].text + " differs from " +
                            wanted[n + j] + " = " + row.cells[column[n + j]].text + ", the principal joint of " +
                            letter + ": both drive " + letter + " (coordinates=)");
    }
    t.world.push_back(world);
    t.joints.push_back(joints);
    t.gain.push_back(gain >= 0 ? tables::csv_number(path, row.line, row.cells[gain]) : 0.0);
    t.tool_offset_mm.push_back(value(2 * n) * layout.mm_per_unit);
    t.controller_ticks.push_back(value(2 * n + 1));
    if (correction_length >= 0)  // volkins.correction-length: the core's L, in LinuxCNC's unit as its other pins
      t.correction_length_mm.push_back(tables::csv_number(path, row.line, row.cells[correction_length]) *
                                       layout.mm_per_unit);
    if (tool_axis >= 0)
      t.tool_axis_mm.push_back(tables::csv_number(path, row.line, row.cells[tool_axis]) * layout.mm_per_unit);
    if (tcp >= 0)
      t.convention.push_back(tables::csv_number(path, row.line, row.cells[tcp]) != 0.0
                                 ? machine::WorldConvention::Tcp
                                 : machine::WorldConvention::Axes);
    for (std::size_t i = 0; i < temperature_column.size(); ++i)
      if (temperature_column[i] >= 0)
        t.temperature_degC[i].push_back(tables::csv_number(path, row.line, row.cells[temperature_column[i]]));
  }
  return t;
}

Joints interpolated(const std::vector<Joints>& p, std::size_t n) {
  return (p[n - 3] + 4.0 * p[n - 2] + p[n - 1]) / 6.0;
}

TraceSummary check_trace(const machine::Model& machine_model, machine::WorldConvention loaded_convention,
                         const SessionTrace& trace, const machine::TypeSelection& types) {
  using machine::Machine;
  TraceSummary out;
  const std::size_t count = trace.size();
  // The machine at each sample's temperatures (as the module filtered them; the reference where
  // the trace has no column).
  const machine::Model& model = machine_model;
  // `conditions`: the real machine; `selected`: what volkins corrected, the same with only the
  // selected types (set after the temperatures: without thermal they are at their references).
  machine::Conditions conditions = model.reference_conditions();
  machine::Conditions selected = conditions;
  const auto at_temperatures_of = [&](std::size_t k) {
    for (std::size_t i = 0; i < trace.temperature_degC.size(); ++i)
      if (trace.temperature_degC[i].size() == count) conditions.temperature_degC[i] = trace.temperature_degC[i][k];
    selected = conditions;
    machine::apply_selection(model, types, selected);
  };
  // Kinematics outputs per sample. Cycle k's inverse ran with that cycle's gain and L (volkins.update
  // runs first) and the tool length of cycle k-1 (motion writes tooloffset.z at its end).
  const bool recorded_L = trace.correction_length_mm.size() == count;
  auto correction_length = [&](std::size_t k) {
    return recorded_L ? trace.correction_length_mm[k]
                      : model.correction_length(trace.tool_offset_mm[k == 0 ? 0 : k - 1]);
  };
  std::vector<Joints> nominal(count), expected(count);
  std::vector<machine::Correction> corrections(count);
  for (std::size_t k = 0; k < count; ++k) {
    const machine::WorldConvention convention =
        trace.convention.size() == count ? trace.convention[k] : loaded_convention;
    const double offset = trace.tool_offset_mm[k == 0 ? 0 : k - 1];
    const double L = correction_length(k);  // the tool-length rule (slewed)
    const Joints world = core_world(model, convention, trace.world[k], offset);
    at_temperatures_of(k);
    // The nominal (TCP) kinematics take the offset at once, the correction its slewed L; the
    // tool-axis coordinate lengthens the nominal tool only.
    machine::Applied applied{trace.gain[k], nullptr};
    applied.conditions = &selected;
    applied.nominal_tool_length_mm =
        model.correction_length(offset) + (trace.tool_axis_mm.size() == count ? trace.tool_axis_mm[k] : 0.0);
    machine::nominal_inverse(model, convention, world, applied.nominal_tool_length_mm, nominal[k]);
    machine::joints_from_world(model, convention, world, L, applied, expected[k], &corrections[k]);
  }
  // Left out of the tool-tip claims: the samples while L differs from the tool's (the tool length
  // slews after a G43: the tip is off by angular error x difference of L meanwhile), and the
  // interpolation's window after it.
  std::size_t last_tool_change = 0;
  for (std::size_t n = 1; n < count; ++n) {
    const double tool_L = model.correction_length(trace.tool_offset_mm[n - 1]);
    if (trace.tool_offset_mm[n] != trace.tool_offset_mm[n - 1] || (recorded_L && correction_length(n) != tool_L))
      last_tool_change = n;
    if (n < 3 || (last_tool_change > 0 && n <= last_tool_change + 4)) {
      out.skipped += n >= 3;
      continue;
    }
    const double L = correction_length(n);
    at_temperatures_of(n);
    SampleCheck s;
    s.sample = n;
    const machine::ToolPose real = machine::tool_pose(model, conditions, Machine::Real, trace.joints[n], L);
    const machine::ToolPose ideal = machine::tool_pose(model, Machine::Ideal, interpolated(nominal, n), L);
    s.tip_error_mm = real.tip_mm - ideal.tip_mm;
    s.selected_tip_error_mm =
        machine::tool_pose(model, selected, Machine::Real, trace.joints[n], L).tip_mm - ideal.tip_mm;
    s.direction_error_rad = ideal.direction.cross(real.direction).norm();
    s.module_mismatch = (trace.joints[n] - interpolated(expected, n)).cwiseAbs().maxCoeff();

    const machine::ToolPose commanded = machine::tool_pose(model, Machine::Ideal, nominal[n], L);
    const machine::ToolPose achieved = machine::tool_pose(model, selected, Machine::Real, expected[n], L);
    s.command_pose_mm = (achieved.tip_mm - commanded.tip_mm).norm();
    s.command_pose_rad = commanded.direction.cross(achieved.direction).norm();
    s.full_correction =
        trace.gain[n] == 1.0 && corrections[n].fade == 1.0 && types.orientation && model.rotary_count() == 2;
    out.samples.push_back(s);
  }
  return out;
}

}  // namespace vc::trace
