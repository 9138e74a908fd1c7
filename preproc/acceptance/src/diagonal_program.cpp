#include "vc/acceptance/diagonal_program.hpp"

#include <sstream>

#include "vc/machine/forward.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::acceptance {
namespace {

// 6 decimals: the commanded points lie on the line within 0.5 nm (LinuxCNC reads them so).
std::string xyz(const Eigen::Vector3d& p) {
  return "X" + fixed_text(p[0], 6) + " Y" + fixed_text(p[1], 6) + " Z" + fixed_text(p[2], 6);
}

// The rotary axes (every joint but X, Y, Z) at their rest positions: "B0 C0".
std::string rotary_words(const Plan& plan, const machine::Model& model) {
  std::string words;
  for (int k = 0; k < model.joint_count(); ++k) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(k)];
    if (a.type == machine::AxisType::Rotary) words += std::string(" ") + a.letter + number_text(plan.rest[k]);
  }
  return words;
}

std::string rotary_text(const Plan& plan, const machine::Model& model) {
  std::string text;
  for (int k = 0; k < model.joint_count(); ++k) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(k)];
    if (a.type == machine::AxisType::Rotary)
      text += std::string(text.empty() ? "" : ", ") + a.letter + " = " + number_text(plan.rest[k]) + " deg";
  }
  return text.empty() ? "none (no rotary axes)" : text + " (held there for every line)";
}

// The direction of the tool's motion against the part, in the part frame, on the ideal machine.
Eigen::Vector3d part_frame_direction(const Plan& plan, const Diagonal& d, const machine::Model& model) {
  const double L = plan.settings.tool_length_mm;
  const auto tip = [&](const Eigen::Vector3d& p) {
    return machine::tool_pose(model, machine::Machine::Ideal, joints_at(model, plan.rest, p), L).tip_mm;
  };
  return (tip(d.end_mm) - tip(d.start_mm)).normalized();
}

std::string triple(const Eigen::Vector3d& u) {
  return fixed_text(u[0], 6) + ", " + fixed_text(u[1], 6) + ", " + fixed_text(u[2], 6);
}

}  // namespace

std::string diagonal_program(const Plan& plan, const Diagonal& d, const machine::Model& model) {
  const DiagonalSettings& s = plan.settings;
  // Program coordinates: joints minus the tool length offset on Z (axes world).
  const Eigen::Vector3d offset(0, 0, plan.tool_offset_mm);
  const auto point = [&](double distance) { return xyz(d.at(distance) - offset); };
  const double last = d.targets_mm.back();
  std::ostringstream g;
  g << "(volcomp acceptance plan: "
    << (d.axis_run() ? "ISO 230-2 positioning run " : "ISO 230-6 " + d.kind + " diagonal ") << d.name
    << " of " << model.info.name << ")\n"
    << "(laser along the line from X Y Z " << triple(d.start_mm) << " to " << triple(d.end_mm)
    << " mm [joints], the setup sheet " << d.name << ".md)\n"
    << "(" << d.targets_mm.size() << " targets, " << s.runs << " bidirectional runs, dwell " << number_text(s.dwell_s)
    << " s at each target, overrun " << number_text(s.overrun_mm) << " mm before each reversal)\n"
    << "G21 G90 G94 G17 G40 G80\n"
    << "G43.1 Z" << fixed_text(plan.tool_offset_mm, 6) << " (the optic's L " << number_text(s.tool_length_mm)
    << " mm minus tool_length_reference_mm)\n";
  const std::string rotary = rotary_words(plan, model);
  if (!rotary.empty()) g << "G0" << rotary << " (rotary axes at rest for the whole test)\n";
  g << "G0 " << point(-s.overrun_mm) << " (the overrun before the start)\n"
    << "F" << number_text(s.feed_mm_per_min) << "\n";
  for (int run = 1; run <= s.runs; ++run) {
    g << "(run " << run << " +)\n";
    for (std::size_t i = 0; i < d.targets_mm.size(); ++i)
      g << "G1 " << point(d.targets_mm[i]) << " (target " << i + 1 << ")\nG4 P" << number_text(s.dwell_s) << "\n";
    g << "G1 " << point(last + s.overrun_mm) << " (overrun)\n";
    g << "(run " << run << " -)\n";
    for (std::size_t i = d.targets_mm.size(); i-- > 0;)
      g << "G1 " << point(d.targets_mm[i]) << " (target " << i + 1 << ")\nG4 P" << number_text(s.dwell_s) << "\n";
    g << "G1 " << point(-s.overrun_mm) << " (overrun)\n";
  }
  g << "G49\nM2\n";
  return g.str();
}

std::string diagonal_sheet(const Plan& plan, const Diagonal& d, const machine::Model& model) {
  const DiagonalSettings& s = plan.settings;
  std::ostringstream m;
  const Eigen::Vector3d u = d.direction();
  const Eigen::Vector3d w = part_frame_direction(plan, d, model);
  m << (d.axis_run() ? "# ISO 230-2 linear positioning test " : "# ISO 230-6 diagonal displacement test ") << d.name
    << " (" << d.kind << "), " << model.info.name << "\n\n"
    << "Machine file `" << plan.machine << "`. Program `" << d.name << ".ngc` (in this folder), run in LinuxCNC "
    << "with the compensation as it will be used (ISO/TR 16907 11.3: all compensations active by default).\n\n"
    << "| | |\n|---|---|\n"
    << "| line | from X Y Z = " << triple(d.start_mm) << " mm to " << triple(d.end_mm) << " mm (joints), "
    << fixed_text(d.length_mm(), 3) << " mm long |\n"
    << "| direction cosines (X, Y, Z axes) | " << triple(u) << " |\n"
    << "| direction cosines (part frame: the tool's motion against the part, ideal machine) | " << triple(w) << " |\n"
    << "| rotary axes | " << rotary_text(plan, model) << " |\n"
    << "| tool-side optic | on the spindle axis, L = " << number_text(s.tool_length_mm)
    << " mm below the spindle gauge point (tool point (0, 0, -" << number_text(s.tool_length_mm)
    << ") mm in the spindle frame); the effective tool-side offset of ISO/TR 16907 11.3 a) |\n"
    << "| tool length to declare | the program declares it: G43.1 Z" << number_text(plan.tool_offset_mm)
    << " (L minus the machine file's tool_length_reference_mm), so volkins corrects for the optic; "
       "volkins.tool-offset must be netted to motion.tooloffset.z |\n"
    << "| feed | " << number_text(s.feed_mm_per_min) << " mm/min (G1) |\n"
    << "| dwell | " << number_text(s.dwell_s) << " s at each target (G4): take the reading in it |\n"
    << "| runs | " << s.runs << " bidirectional (+: away from the start, -: back), overrun "
    << number_text(s.overrun_mm) << " mm past the end targets before each reversal |\n\n"
    << "## Setup\n\n"
    << "1. The laser on the table (the part side), its beam along the line above: through the start point and "
       "the end point of the optic's path (the cosines above); the reflector (tool-side optic) in the spindle at L.\n"
    << "2. Align the beam over the whole line (the program's first move goes to the overrun before the start; "
       "jog along the line to align).\n"
    << "3. Zero the laser at target 1 (the start point, distance 0) after the first approach in run 1 +.\n"
    << "4. Run the program; at each dwell record the displacement.\n"
    << "5. Export the runs as `" << measurements_name(d)
    << "` in the measurements folder, one reading per row (units in the header):\n\n"
    << "       target[mm],run,direction,deviation[um]\n\n"
    << "   target: the distance below; run 1.." << s.runs << "; direction + or -; deviation = the laser's displacement "
       "minus the target (actual - nominal, ISO 230-2's positional deviation).\n\n"
    << "## Targets\n\n| target | distance [mm] | X [mm] | Y [mm] | Z [mm] (joints) |\n|---:|---:|---:|---:|---:|\n";
  for (std::size_t i = 0; i < d.targets_mm.size(); ++i) {
    const Eigen::Vector3d p = d.at(d.targets_mm[i]);
    m << "| " << i + 1 << " | " << fixed_text(d.targets_mm[i], 3) << " | " << fixed_text(p[0], 3) << " | "
      << fixed_text(p[1], 3) << " | " << fixed_text(p[2], 3) << " |\n";
  }
  m << "\nThe inner targets are off the even spacing by a pseudo-random offset (up to a quarter of it) so that they "
       "fall off the compensation tables' nodes (ISO/TR 16907 11.3: other sampling points than the compensation's).\n";
  return m.str();
}

std::string plan_index(const Plan& plan, const machine::Model& model) {
  const DiagonalSettings& s = plan.settings;
  std::ostringstream m;
  m << "# Acceptance tests of " << model.info.name << " (`" << plan.machine << "`)\n\n"
    << "Written by `volcomp acceptance plan`. `plan.toml` is the machine-readable plan (`volcomp acceptance "
       "simulate` and `evaluate` read it); each test has a G-code program and a setup sheet in the folder of its kind.\n\n"
    << "Work volume (joints): X " << number_text(s.volume.low_mm[0]) << ":" << number_text(s.volume.high_mm[0])
    << ", Y " << number_text(s.volume.low_mm[1]) << ":" << number_text(s.volume.high_mm[1]) << ", Z "
    << number_text(s.volume.low_mm[2]) << ":" << number_text(s.volume.high_mm[2]) << " mm. Rotary axes: "
    << rotary_text(plan, model) << ".\n\n";
  if (!plan.diagonals.empty())
    m << "## ISO 230-6 diagonal displacement tests (`diagonals/`)\n\n"
      << "| test | kind | length [mm] | program | sheet | measurements file |\n|---|---|---:|---|---|---|\n";
  const auto lines_table = [&](const std::vector<Diagonal>& lines) {
    for (const Diagonal& d : lines)
      m << "| " << d.name << " | " << d.kind << " | " << fixed_text(d.length_mm(), 3) << " | `" << program_path(d)
        << "` | `" << sheet_path(d) << "` | `" << measurements_name(d) << "` |\n";
  };
  lines_table(plan.diagonals);
  if (!plan.axis_runs.empty()) {
    m << "\n## ISO 230-2 linear positioning tests (`axes/`)\n\n"
      << "| test | kind | length [mm] | program | sheet | measurements file |\n|---|---|---:|---|---|---|\n";
    lines_table(plan.axis_runs);
  }
  if (!plan.circles.empty()) {
    m << "\n## ISO 230-4 circular tests (`circles/`)\n\n"
      << "| test | plane | radius [mm] | program | sheet | measurements file |\n|---|---|---:|---|---|---|\n";
    for (const Circle& c : plan.circles)
      m << "| " << c.name << " | " << c.plane << " | " << number_text(c.radius_mm) << " | `" << program_path(c) << "` | `"
        << sheet_path(c) << "` | `" << measurements_name(c) << "` |\n";
  }
  m << "\nThen: `volcomp acceptance evaluate DIR --measurements FOLDER [--tolerances T.toml]`.\n";
  return m.str();
}

}  // namespace vc::acceptance
