// volcomp trace: the tool-tip error of a recorded LinuxCNC session, and whether volkins did
// exactly what the core computes (see vc/trace/session_trace.hpp for the comparison).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <stdexcept>

#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "program_files.hpp"
#include "types_option.hpp"
#include "vc/fit_tables/comp_file.hpp"
#include "vc/fit_tables/comp_file_replay.hpp"
#include "vc/init/kinematics_line.hpp"
#include "vc/init/linuxcnc_ini.hpp"
#include "vc/init/linuxcnc_units.hpp"
#include "vc/init/number.hpp"
#include "vc/init/volkins_config.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/atomic_file.hpp"
#include "vc/trace/session_trace.hpp"

namespace vc::cli {
namespace {

struct TraceArgs {
  std::string machine;
  std::string trace;              // CSV recorded by kins/configs/common/headless_driver.py
  std::string world;              // the module's world convention: axes or tcp ("": --ini's, else axes)
  std::string output;             // per-sample errors CSV (optional)
  double servo_period_s = 0.001;  // for the time column
  std::string comp_files;         // a folder of fit-tables' COMP_FILEs to replay on the trace (optional)
  std::string ini;                // the configuration's INI: joints, world, units; the joints' limits for the replay
  std::string replay_output;      // the replay's per-sample errors CSV (t_s,e_um; optional)
  TypesOption types;              // the compensation types volkins corrected with (its type pins)
};

// The COMP_FILEs of args.comp_files replayed on the session (fit_tables::replay_comp_files):
// the tool-tip error it would have had with them loaded.
void print_comp_file_replay(const TraceArgs& args, const machine::Model& model, const trace::SessionTrace& session,
                            const trace::TraceSummary& summary, std::ostream& out) {
  namespace fs = std::filesystem;
  if (args.ini.empty())
    throw std::runtime_error("--comp-files needs --ini: the joints' limits, which LinuxCNC's ramp uses");
  if (!fs::is_directory(args.comp_files)) throw std::runtime_error(args.comp_files + ": no such folder");
  const init::LinuxcncIni ini = init::LinuxcncIni::read(args.ini);
  std::vector<fit_tables::LinuxcncComp> comps;
  std::vector<fit_tables::JointLimits> limits;
  std::string with, without;
  for (int j = 0; j < model.joint_count(); ++j) {
    const std::string section = "JOINT_" + std::to_string(j);
    double limit[2] = {0.0, 0.0};
    const char* keys[2] = {"MAX_VELOCITY", "MAX_ACCELERATION"};
    for (int k = 0; k < 2; ++k) {
      const init::IniEntry* entry = ini.find(section, keys[k]);
      if (!entry) throw LoadError(ini.where_missing(section), "[" + section + "]" + keys[k] + " is missing");
      if (!init::parse_number(entry->value, limit[k]) || limit[k] <= 0)
        throw LoadError(entry->where(), "[" + section + "]" + keys[k] + " is not a number > 0");
    }
    // The homing's move from HOME_OFFSET to HOME (LinuxCNC's defaults 0).
    const double home = init::ini_number(ini, section, "HOME", 0.0);
    const double offset = init::ini_number(ini, section, "HOME_OFFSET", 0.0);
    limits.push_back({limit[0], limit[1], home > offset ? 1 : home < offset ? -1 : 0});
    const fs::path file = fs::path(args.comp_files) / fit_tables::linuxcnc_comp_file_name(model, j);
    if (!fs::exists(file)) {
      comps.emplace_back();
      without += " " + std::string(1, model.axes[static_cast<std::size_t>(j)].letter);
      continue;
    }
    std::ifstream in(file, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    try {
      comps.push_back(fit_tables::read_linuxcnc_comp(text, 1));
    } catch (const std::invalid_argument& e) {
      throw LoadError({file.string()}, e.what());
    }
    with += " " + file.filename().string();
  }
  const fit_tables::CompReplay replay =
      fit_tables::replay_comp_files(model, session, summary, comps, limits, args.servo_period_s);
  if (!args.replay_output.empty())
    tables::write_atomically(args.replay_output, [&](std::ostream& csv) {
      csv << "t_s,e_um\n";
      for (std::size_t k = 0; k < replay.tip_error_um.size(); ++k)
        csv << fixed_text(static_cast<double>(summary.samples[k].sample) * args.servo_period_s, 3) << ','
            << number_text(replay.tip_error_um[k]) << '\n';
    });
  double max_um = 0, sum_sq = 0;
  for (const double e : replay.tip_error_um) max_um = std::max(max_um, e), sum_sq += e * e;
  const double rms_um = std::sqrt(sum_sq / static_cast<double>(std::max<std::size_t>(1, replay.tip_error_um.size())));
  out << "with the COMP_FILEs of " << args.comp_files << " replayed as LinuxCNC applies them (" << with.substr(1)
      << (without.empty() ? "" : "; none on" + without) << "): tool tip error: max " << fixed_text(max_um, 3)
      << " um, RMS " << fixed_text(rms_um, 3) << " um\n";
}

// How the configuration that recorded the trace maps it onto the machine file.
struct RecordedBy {
  trace::TraceLayout layout;
  machine::WorldConvention convention = machine::WorldConvention::Axes;
};

// From the INI (volkins' [KINS]KINEMATICS line: coordinates=, world=, units=; a stock module's:
// its coordinates= and [TRAJ]LINEAR_UNITS, the world as --world says), or, without --ini, the
// machine file's own joint order in mm and --world.
RecordedBy recorded_by(const TraceArgs& args, const machine::Model& model) {
  RecordedBy r;
  r.convention = world_convention(args.world.empty() ? "axes" : args.world);
  if (args.ini.empty()) return r;
  const init::LinuxcncIni ini = init::LinuxcncIni::read(args.ini);
  const init::IniEntry* kins = ini.find("KINS", "KINEMATICS");
  std::string coordinates;
  double mm_per_unit = 1.0;
  if (kins && kins->value.rfind("volkins", 0) == 0) {
    const init::VolkinsParameters volkins = init::read_volkins_parameters(ini);
    if (!args.world.empty() && r.convention != volkins.world)
      throw LoadError(kins->where(), "--world " + args.world +
                                         " contradicts the configuration: volkins is loaded with " +
                                         (volkins.world == machine::WorldConvention::Tcp ? "world=tcp" : "world=axes") +
                                         " (leave --world out with --ini)");
    r.convention = volkins.world;
    coordinates = volkins.coordinates;
    mm_per_unit = volkins.units.mm_per_unit;
  } else {  // a session with LinuxCNC's own module (--comp-files' replay)
    const init::KinematicsLine line = init::read_kinematics_line(ini);
    if (const std::string* c = line.parameter("coordinates")) coordinates = *c;
    mm_per_unit = init::read_linear_units(ini).mm_per_unit;
  }
  try {
    r.layout = trace::trace_layout(model, coordinates, mm_per_unit);
  } catch (const std::invalid_argument& e) {
    throw LoadError(kins->where(), std::string(e.what()) + " (" + model.path + ")");
  }
  return r;
}

int run_trace(const TraceArgs& args, std::ostream& out) {
  const machine::TypeSelection types = args.types.selection();
  if (args.comp_files.empty() && !args.replay_output.empty())
    throw std::runtime_error("--replay-output goes with --comp-files");
  const machine::Model model = machine::load_machine(args.machine);
  const RecordedBy recorded = recorded_by(args, model);
  const machine::WorldConvention convention = recorded.convention;
  const trace::SessionTrace session = trace::read_session_trace(args.trace, model, recorded.layout);
  if (!types.is_all() && !session.with_volkins)
    throw std::runtime_error("--types " + args.types.list + ": " + args.trace +
                             " is a session without volkins (no gain column): no compensation types to switch");
  const trace::TraceSummary summary = trace::check_trace(model, convention, session, types);
  if (summary.samples.empty()) throw std::runtime_error(args.trace + ": fewer than 4 usable samples");

  double max_tip = 0, sum_sq = 0, max_dir = 0, max_mismatch = 0, max_pose_mm = 0, max_pose_rad = 0;
  double max_dir_corrected = 0;                  // where volkins corrects the tool direction too
  double max_selected = 0, sum_sq_selected = 0;  // of the selected types' errors (--types)
  std::size_t corrected = 0;
  for (const trace::SampleCheck& s : summary.samples) {
    const double e = s.tip_error_mm.norm();
    max_tip = std::max(max_tip, e);
    sum_sq += e * e;
    max_dir = std::max(max_dir, s.direction_error_rad);
    max_mismatch = std::max(max_mismatch, s.module_mismatch);
    const double e_selected = s.selected_tip_error_mm.norm();
    max_selected = std::max(max_selected, e_selected);
    sum_sq_selected += e_selected * e_selected;
    if (s.full_correction) {
      ++corrected;
      max_dir_corrected = std::max(max_dir_corrected, s.direction_error_rad);
      max_pose_mm = std::max(max_pose_mm, s.command_pose_mm);
      max_pose_rad = std::max(max_pose_rad, s.command_pose_rad);
    }
  }
  const double rms = std::sqrt(sum_sq / static_cast<double>(summary.samples.size()));

  if (!args.output.empty())
    tables::write_atomically(args.output, [&](std::ostream& csv) {
      csv << "t_s,ex_um,ey_um,ez_um,e_um,ek_urad,gain\n";
      for (const trace::SampleCheck& s : summary.samples) {
        csv << fixed_text(static_cast<double>(s.sample) * args.servo_period_s, 3);
        // Full precision: with compensation on, the errors are nanometres.
        for (int k = 0; k < 3; ++k) csv << ',' << number_text(s.tip_error_mm[k] * 1e3);
        csv << ',' << number_text(s.tip_error_mm.norm() * 1e3) << ',' << number_text(s.direction_error_rad * 1e6) << ','
            << number_text(session.gain[s.sample]) << '\n';
      }
    });
  out << "trace: " << args.trace << " (" << summary.samples.size() << " samples checked, " << summary.skipped
      << " skipped at tool changes)\n"
      << "tool tip error: max " << fixed_text(max_tip * 1e3, 3) << " um, RMS " << fixed_text(rms * 1e3, 3)
      << " um; tool direction error: max " << fixed_text(max_dir * 1e6, 2) << " urad\n";
  if (corrected > 0 && corrected < summary.samples.size())
    // Near the pole (the tool along the C axis) C cannot turn the tool: volkins fades the
    // direction correction out there and corrects the tip only (model.md, pole fade).
    out << "  where the tool direction is corrected too (gain 1, beyond the pole fade band: "
        << fixed_text(100.0 * static_cast<double>(corrected) / static_cast<double>(summary.samples.size()), 1)
        << " % of the samples): tool direction error max " << fixed_text(max_dir_corrected * 1e6, 2)
        << " urad; elsewhere the tip only\n";
  if (!types.is_all())
    // The machine keeps the errors of the types switched off: the tip error above has them.
    out << "  of the compensation types corrected (" << types.to_string() << "; the others' errors left out): "
        << "tool tip error max " << fixed_text(max_selected * 1e3, 3) << " um, RMS "
        << fixed_text(std::sqrt(sum_sq_selected / static_cast<double>(summary.samples.size())) * 1e3, 3) << " um\n";
  if (!args.comp_files.empty()) {
    // LinuxCNC's COMP_FILEs act on the joints; the replay takes them to be the commanded axes.
    if (convention != machine::WorldConvention::Axes)
      throw std::runtime_error("--comp-files replays a session in the axes world (the joints are the commanded axes)");
    if (recorded.layout.mm_per_unit != 1.0)
      throw std::runtime_error("--comp-files replays the COMP_FILEs of a configuration in mm; " + args.ini +
                               " runs in inch");
    print_comp_file_replay(args, model, session, summary, out);
  }
  if (!session.with_volkins) {
    // LinuxCNC's own kinematics: what moves the joints off them is the joints' COMP_FILEs.
    out << "joints beyond the nominal kinematics' (COMP_FILE corrections; mm or deg): max " << number_text(max_mismatch)
        << '\n';
    return 0;
  }
  out << "module against the core (joints, mm or deg"
      << (types.is_all() ? std::string() : "; the core with the types " + types.to_string()) << "): max "
      << number_text(max_mismatch) << '\n'
      << "commanded pose residual where fully corrected: max " << number_text(max_pose_mm) << " mm, "
      << number_text(max_pose_rad) << " rad\n";
  return 0;
}

}  // namespace

void add_trace_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<TraceArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "trace", "Tool-tip error along a recorded LinuxCNC session, and volkins checked against the core");
  cmd->add_option("MACHINE", args->machine, "machine description file (.toml)")->required();
  cmd->add_option("TRACE", args->trace, "trace CSV written by the headless driver")->required();
  cmd->add_option("--world", args->world,
                  "the module's world convention: axes (the default) or tcp; with --ini the configuration's");
  cmd->add_option("-o,--output", args->output, "write t_s,ex_um,ey_um,ez_um,e_um,ek_urad,gain per sample to this CSV");
  cmd->add_option("--comp-files", args->comp_files,
                  "a session without correction: also its tool-tip error with these COMP_FILEs (fit-tables' "
                  "joint_N_<axis>.comp) replayed as LinuxCNC applies them");
  cmd->add_option("--replay-output", args->replay_output,
                  "with --comp-files: write t_s,e_um per sample of the "
                  "replay to this CSV");
  cmd->add_option("--ini", args->ini,
                  "the configuration's INI that recorded the trace: volkins' coordinates= (which joint "
                  "column drives each axis; a gantry's other motors checked equal), world= and units=; "
                  "with --comp-files also [JOINT_n] MAX_VELOCITY, MAX_ACCELERATION (LinuxCNC's ramp of "
                  "the correction)")
      ->check(CLI::ExistingFile);
  add_types_option(*cmd, args->types,
                   "the compensation types volkins corrected with (its type pins): the module is checked against "
                   "the core with these, and the tip error of these types' errors is reported too");
  cmd->callback([args, &exit_code] { exit_code = run_trace(*args, std::cout); });
}

}  // namespace vc::cli
