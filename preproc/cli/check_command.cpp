// `volcomp check MACHINE`: loads and validates a machine, then summarises it: axes, location
// errors, tables (coverage, slope margin), the largest volumetric error over the travel and
// whether the correction converges everywhere. Exit 0 only if the machine is usable. With
// --ini, the configuration's limits against it, and the checksum of the machine file the INI's
// volkins line names (volkins.checksum shows the active file's: machine_checksum.hpp); MACHINE
// is then that file unless given.
#include <CLI/CLI.hpp>
#include <cctype>
#include <cstdio>
#include <cmath>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/identify/travel_survey.hpp"
#include "vc/init/home_position.hpp"
#include "vc/init/joint_room.hpp"
#include "vc/machine/compensation_types.hpp"
#include "vc/init/volkins_config.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/machine/machine_checksum.hpp"
#include "vc/tables/slope.hpp"

namespace vc::cli {
namespace {

struct CheckArgs {
  std::string machine;
  int samples = 10000;  // random poses over the travel, besides the grid of corners and mids
  std::string ini;      // a LinuxCNC configuration loading this machine: where it homes, or ""
};

using machine::Axis;
using machine::AxisType;
using machine::Joints;
using machine::Model;

constexpr double kRadToUrad = 1e6;
constexpr double kRadToArcsec = 180.0 / M_PI * 3600.0;

std::string unit_of(const Axis& a) { return a.type == AxisType::Linear ? "mm" : "deg"; }

std::string pose_text(const Model& model, const Joints& q) {
  std::string s;
  for (int j = 0; j < model.joint_count(); ++j)
    s += (j ? " " : "") + std::string(1, static_cast<char>(std::tolower(model.axes[j].letter))) + "=" +
         fixed_text(q[j], 3);
  return s;
}

void print_axes(const Model& model, std::ostream& out) {
  out << "axes (joint order " << model.coordinates() << "):\n";
  for (const Axis& a : model.axes) {
    out << "  " << a.letter << "  " << (a.type == AxisType::Linear ? "linear" : "rotary") << ", "
        << (a.chain == machine::Chain::Tool ? "tool chain" : "workpiece chain") << ", travel "
        << number_text(a.travel_min) << " .. " << number_text(a.travel_max) << ' ' << unit_of(a);
    for (int k = 0; k < 3; ++k)
      if (a.location_mm[k] != 0.0)
        out << ", E"
            << "XYZ"[k] << '0' << a.letter << " = " << fixed_text(a.location_mm[k] * 1e3, 2) << " um";
    for (int k = 0; k < 3; ++k)
      if (a.location_rad[k] != 0.0)
        out << ", E"
            << "ABC"[k] << '0' << a.letter << " = " << fixed_text(a.location_rad[k] * kRadToArcsec, 2) << " arcsec";
    out << '\n';
  }
  auto chain = [&](const std::vector<int>& c) {
    std::string s;
    for (int j : c) s += std::string(s.empty() ? "" : " ") + model.axes[j].letter;
    return s.empty() ? std::string("(none)") : s;
  };
  out << "chains: tool " << chain(model.tool_chain) << "; workpiece " << chain(model.workpiece_chain)
      << " (bed outward)\n";
}

// Returns the steepest table slope as a fraction of its limit.
double print_tables(const Model& model, std::ostream& out) {
  out << "tables:\n";
  double worst = 0.0;
  for (const machine::BoundTable& bound : model.tables) {
    const tables::ErrorTable& t = bound.table;
    out << "  " << t.path() << "\n     grid";
    for (const auto& g : t.grid())
      out << ' ' << g.name() << ": " << g.nodes.size() << " nodes " << number_text(g.nodes.front()) << " .. "
          << number_text(g.nodes.back()) << ' ' << g.unit() << (g.periodic ? " (periodic)" : "");
    out << "; " << (t.interpolation() == tables::Interpolation::Cubic ? "cubic" : "linear") << "; columns";
    for (const auto& c : t.columns()) out << ' ' << c.symbol.name();
    const tables::SteepestSlope s = tables::steepest_slope(t);
    worst = std::max(worst, s.fraction);
    out << "\n     steepest slope " << fixed_text(100.0 * s.fraction, 1) << " % of the invertibility limit";
    if (s.column >= 0) out << " (" << t.columns()[s.column].symbol.name() << ")";
    out << '\n';
  }
  if (model.tables.empty()) out << "  (none)\n";
  return worst;
}

// The ISO/TR 16907 Annex A types the file's non-zero terms provide, what provides each, and
// thermal compensation beside them.
void print_compensation_types(const Model& model, std::ostream& out) {
  const machine::CompensationTypes types = machine::compensation_types(model);
  out << "compensation types (ISO/TR 16907 Annex A):\n";
  if (types.types.empty()) out << "  (none: the file has no non-zero error)\n";
  for (const machine::CompensationType& t : types.types) {
    const bool composite = t.code.find("VOL") != std::string::npos;
    out << "  " << t.code << "  " << t.name;
    if (!t.missing.empty()) {
      out << ": partial, has";
      for (std::size_t i = 0; i < t.sources.size(); ++i) out << (i ? ", " : " ") << t.sources[i];
      out << "; lacks";
      for (std::size_t i = 0; i < t.missing.size(); ++i) out << (i ? ", " : " ") << t.missing[i];
    } else if (composite) {
      out << ": complete";
    }
    out << '\n';
    if (!composite)
      for (const std::string& s : t.sources) out << "      " << s << '\n';
  }
  out << "  tool direction (FOR): " << (types.orientation_possible ? "possible, " : "not possible, ")
      << types.orientation_reason << '\n';
  out << "  thermal (not an Annex type):" << (types.thermal.empty() ? " none" : "") << '\n';
  for (const std::string& s : types.thermal) out << "      " << s << '\n';
}

// The configuration's limits against the correction: where it leaves each axis after homing,
// and the room its joint limits leave at the ends of the travel; false if either fails.
bool print_configuration(const Model& model, const std::string& ini_path, std::ostream& out) {
  const init::LinuxcncIni ini = init::LinuxcncIni::read(ini_path);
  const init::VolkinsParameters volkins = init::read_volkins_parameters(ini);
  const init::HomeCheck home = init::check_home_position(ini, model, volkins);
  const init::JointRoomCheck room = init::check_joint_room(ini, model, volkins);
  const auto unit = [&](char letter) {
    return model.axes[model.joint_of(letter)].type == AxisType::Rotary ? " deg" : " mm";
  };
  out << "LinuxCNC configuration " << ini_path
      << (volkins.units.inch() ? " (its inch lengths in mm here; the fixes in inch)" : "") << ":\n";
  if (!volkins.machine.empty()) {
    // As volkins reads it: the file and its tables (compare with `halcmd getp volkins.checksum`).
    // Where the INI's machine= cannot be read from here (a copied INI), a note, not a failure:
    // MACHINE is what is checked.
    try {
      const Model named = volkins.machine == model.path ? model : machine::load_machine(volkins.machine);
      char hex[16];
      std::snprintf(hex, sizeof hex, "0x%08X", machine::machine_checksum(named));
      out << "  checksum " << hex << " (volkins.checksum) of its machine file " << named.path << " and its "
          << machine::checksummed_files(named).size() - 1 << " table files\n";
    } catch (const std::exception& e) {
      out << "  checksum not computed: its machine file does not load here: " << e.what() << '\n';
    }
  }
  out << "  after homing (each joint at its HOME, no tool length offset, world="
      << (home.convention == machine::WorldConvention::Tcp ? "tcp" : "axes") << "):\n";
  for (const init::HomedAxis& a : home.axes)
    out << "    " << a.letter << "  HOME " << number_text(a.home) << " -> world " << fixed_text(a.world, 4)
        << unit(a.letter) << ", axis limits " << number_text(a.min_limit) << " .. " << number_text(a.max_limit) << '\n';
  out << "  the joints over the axes' limits, corrected (" << room.poses
      << " poses, L = " << number_text(room.tool_lengths_mm[0]) << " and " << number_text(room.tool_lengths_mm[1])
      << " mm):\n";
  for (const init::JointRoom& j : room.joints)
    out << "    joint " << j.joint << " (" << j.letter << ")  " << fixed_text(j.lowest, 4) << " .. "
        << fixed_text(j.highest, 4) << unit(j.letter) << ", joint limits " << number_text(j.min_limit) << " .. "
        << number_text(j.max_limit) << '\n';
  for (const std::string& p : home.problems) out << "  error: " << p << '\n';
  for (const std::string& p : room.problems) out << "  error: " << p << '\n';
  return home.problems.empty() && room.problems.empty();
}

int run_check(const CheckArgs& args, std::ostream& out) {
  std::string path = args.machine;
  if (path.empty() && !args.ini.empty())
    path = init::read_volkins_parameters(init::LinuxcncIni::read(args.ini)).machine;
  if (path.empty()) throw std::runtime_error("error: check needs MACHINE, or --ini with a volkins machine= line");
  const Model model = machine::load_machine(path);
  out << "machine " << model.info.name;
  if (!model.info.serial.empty()) out << " (" << model.info.serial << ")";
  out << "\n  file " << model.path
      << "\n  measured: " << (model.info.measured_on.empty() ? "date not given" : model.info.measured_on) << ", "
      << fixed_text(model.info.temperature_C, 1) << " C";
  if (!model.info.instrument.empty()) out << ", " << model.info.instrument;
  out << "\n  tool length L = " << number_text(model.tool_length_mm)
      << " mm (checked here); in use L = " << number_text(model.tool_length_reference_mm)
      << " mm + the G43 tool length offset; pole fade " << number_text(model.fade.start_rad * 180.0 / M_PI) << " .. "
      << number_text(model.fade.full_rad * 180.0 / M_PI) << " deg\n";
  if (model.tool_axis_coordinate)
    out << "  tool-axis coordinate " << model.tool_axis_coordinate << ": moves the tool along its own axis (volkins: "
        << "the nominal TCP tool is L + " << static_cast<char>(std::tolower(model.tool_axis_coordinate))
        << " long; its joint is passed through)\n";
  print_axes(model, out);
  if (!model.temperatures.empty()) {  // the survey below is at their references
    out << "temperature inputs (degC; surveyed at the reference):";
    for (const machine::TemperatureInput& t : model.temperatures)
      out << ' ' << t.name << ' ' << number_text(t.reference_degC) << " (" << number_text(t.min_degC) << " .. "
          << number_text(t.max_degC) << ')';
    out << '\n';
  }
  const double steepest = print_tables(model, out);
  print_compensation_types(model, out);
  for (const Warning& w : model.warnings) out << w.to_string() << '\n';

  const identify::TravelSurvey s = identify::survey_travel(model, args.samples);
  out << "volumetric error over the travel (" << s.poses << " poses, L = " << number_text(model.tool_length_mm)
      << " mm):\n  largest position error " << fixed_text(s.max_position_mm * 1e3, 2) << " um at "
      << pose_text(model, s.worst_position) << '\n';
  if (model.rotary_count() > 0 || s.max_direction_rad > 0.0)
    out << "  largest tool-direction error " << fixed_text(s.max_direction_rad * kRadToUrad, 2) << " urad at "
        << pose_text(model, s.worst_direction) << '\n';
  out << "invertibility margin: steepest table slope " << fixed_text(100.0 * steepest, 1) << " % of the limit\n";
  out << "correction: ";
  if (s.failures == 0) {
    out << "converged at all " << s.poses << " poses, at most " << s.max_iterations
        << " Newton steps, largest residual " << number_text(s.max_residual_mm) << " mm\n";
  } else {
    out << "FAILED at " << s.failures << " of " << s.poses << " poses, first at " << pose_text(model, s.first_failure)
        << '\n';
  }
  bool usable = s.failures == 0;
  if (!args.ini.empty()) usable = print_configuration(model, args.ini, out) && usable;
  out << (usable ? "usable\n" : "NOT usable\n");
  return usable ? 0 : 1;
}

}  // namespace

void add_check_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "check", "Validate a machine file and its tables; summarise axes, tables, error and invertibility");
  cmd->add_option("MACHINE", args->machine, "machine description file (.toml); with --ini, the INI's machine= by default");
  cmd->add_option("--samples", args->samples, "random poses sampled over the travel")->capture_default_str();
  cmd->add_option("--ini", args->ini,
                  "a LinuxCNC configuration that loads this machine with volkins: is every axis inside its "
                  "limits after homing? Prints the checksum of its machine file (volkins.checksum)")
      ->check(CLI::ExistingFile);
  cmd->callback([args, &exit_code] { exit_code = run_check(*args, std::cout); });
}

}  // namespace vc::cli
