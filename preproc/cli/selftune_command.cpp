// volcomp selftune: the program of the next part from the measured deviations of this one
// (seeds/000 ch. I fig. 1.12: P1 = P0, part i machined with Pi and measured (Ri), P(i+1)
// derived from Pi and Ri). Local strategy: Pi's path shifted against the deviations. Model
// strategy: the machine's tables tuned from the deviations (written as a new table set),
// and the original program pre-distorted with them.
#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "vc/tables/atomic_file.hpp"
#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "program_files.hpp"
#include "types_option.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/missing_tool_offset.hpp"
#include "vc/predistort/predistort.hpp"
#include "vc/predistort/tool_lengths.hpp"
#include "vc/shop/first_part.hpp"
#include "vc/shop/model_fit_advice.hpp"
#include "vc/shop/selftune_local.hpp"
#include "vc/shop/selftune_model.hpp"
#include "vc/tables/source_error.hpp"
#include "vc/tables/symbols.hpp"

namespace vc::cli {
namespace {

struct SelftuneArgs {
  std::string machine;             // the model (machine file) the program was made for
  std::string input;               // program Pi that machined the measured part
  std::string report;              // CMM report Ri
  std::string report_unit;         // for a CMM export whose file states no unit: mm, um or inch
  std::string deviation_sign;      // of a CMM export's deviation column: actual-minus-nominal or nominal-minus-actual
  bool decimal_comma = false;      // a CMM export writes 12,5
  std::string output;              // program P(i+1)
  std::string strategy = "local";  // local or model
  std::string var_file, tool_table, world = "axes";
  std::string machine_units = "mm";
  bool compensated = false;  // Pi ran with volkins correcting with MACHINE
  // The types volkins corrected Pi with (--compensated), and the types the model strategy's
  // next program is pre-distorted for (or volkins corrects it with): the same shop setting.
  TypesOption types;
  std::vector<int> ball_end_tools;
  double flute_length_mm = 30.0;
  double cutoff_mm = 10.0, outlier_sigmas = 4.0;
  // local
  double gain = 1.0, radius_mm = 40.0, angle_deg = 20.0, step_mm = 1.0, tolerance_mm = 0.0005;
  bool no_tilt = false;      // keep the program's tool axis (tip shifted only)
  double min_support = 6.0;  // local: widen the window where fewer points carry a shift
  // model
  std::string tables_out;                 // folder of the updated machine file and tables
  std::string nominal;                    // the original program P0 (default: PROGRAM)
  std::string next_program, next_points;  // model: another part (program, CMM plan): the noise carried there
  std::vector<std::string> deviations;
  int nodes = 5;
  double regularisation = 1e-3, smoothness = 1e-2;
};

std::ifstream open_program(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw LoadError({path}, "cannot open the program");
  return in;
}

std::string um(double mm) { return fixed_text(mm * 1e3, 3) + " um"; }

void print_first_part(const shop::FirstPart& part, std::ostream& report) {
  report << "volcomp selftune: " << part.points.size() << " points matched to the program's cuts; points differ from "
         << "their neighbours by " << um(part.robust_sigma_mm) << " (robust sigma: noise and short waves); "
         << part.outliers << " outliers left out; short-wave part below the cut-off RMS " << um(part.short_wave_rms_mm)
         << "\n";
  if (!part.left_out.empty())
    report << "  " << part.left_out.size() << " points left out, on no surface the program cuts:\n";
  for (const shop::LeftOutPoint& p : part.left_out)
    report << "  left out " << p.point.id << " (report line " << p.point.line << "): " << p.reason << "\n";
  for (const shop::MatchedPoint& m : part.points)
    if (m.outlier)
      report << "  outlier " << m.point.id << " (report line " << m.point.line << "): deviation "
             << um(*m.point.deviation_mm) << ", its face around it " << um(m.filtered_mm) << "\n";
}

// What the local strategy did with the tool axis, and where it could not see it.
void print_tilt(const shop::TiltSummary& t, std::ostream& report) {
  if (!t.asked) {
    report << "  tool axis: kept as programmed (--no-tilt)\n";
    return;
  }
  if (!t.machine_tilts) {
    report << "  tool axis: not corrected: the machine has no rotary axis (a tilt error is left; a 3-axis path "
              "cannot turn the tool)\n";
    return;
  }
  report << "  tool axis: turned on " << t.tilted << " pieces of 5-axis moves (largest "
         << fixed_text(t.largest_rad * 1e6, 2) << " urad)";
  if (t.unseen > 0)
    report << "; not estimated on " << t.unseen
           << " (the points near them lie at one height along the tool: a tilt cannot be told from a shift of the tip)";
  if (t.below_noise > 0)
    report << "; not turned on " << t.below_noise
           << " (the tilt the points tell is within one standard error of zero: noise; elsewhere it is shrunk by "
              "its noise)";
  if (t.singular > 0) report << "; not turned on " << t.singular << " (the rotary axes cannot give it there: a pole)";
  if (t.rotary_held > 0)
    report
        << "; " << t.rotary_held
        << " pieces of moves that hold the rotary axes (3+2; pre-distorted: turned by less than 0.01 deg) keep their "
           "tool axis (tip shifted only)";
  report << "\n";
}

// The tool lengths a program's path was simulated (and corrected) for, and where they came from.
predistort::ToolLengthLog tool_lengths_of(const std::string& program, const interpreter::Setup& setup) {
  std::ifstream in = open_program(program);
  return predistort::read_tool_lengths(in, setup);
}

// What a refusal adds about L: the path lies where a tool of that length cuts; a part cut
// with a longer tool and no G43 lies its length below it, outside the region the path cuts.
std::string tool_length_cause(const predistort::ToolLengthLog& log, const machine::Model& model,
                              const ProgramFiles& files, const std::string& program, const std::string& tool_table) {
  std::string text = "\n  the path was simulated for the program's " + log.describe(model, program, tool_table);
  const auto first = log.first_without_offset();
  if (!first) return text;
  const auto tool = predistort::likely_tool(model, files.tools ? &*files.tools : nullptr, first->tool);
  if (!tool || tool->length_mm == model.correction_length(0.0)) return text;
  const std::string reference = number_text(model.tool_length_reference_mm) + " mm";
  text += "\n  corrected for L = " + reference + " (no G43 in " + program + " from line " +
          std::to_string(first->line) + "); if the part was cut with a " + number_text(tool->length_mm) + " mm tool (" +
          (tool->tool >= 0 ? "tool " + std::to_string(tool->tool) + " in the tool table"
                           : std::string("the machine file's tool_length_mm")) +
          "), add G43" + (tool->tool >= 0 ? " H" + std::to_string(tool->tool) : std::string()) +
          " or set tool_length_reference_mm";
  return text;
}

int run_selftune(const SelftuneArgs& args, std::ostream& report) {
  const machine::TypeSelection types = args.types.selection();
  if (!types.is_all() && !args.compensated && args.strategy != "model")
    throw std::runtime_error("--types " + args.types.list +
                             " changes nothing here: Pi was pre-distorted (the types are in its numbers) and the local "
                             "strategy shifts it; give --compensated if volkins corrected Pi with these types");
  if (args.strategy != "local" && args.strategy != "model")
    throw std::runtime_error("--strategy must be local or model, not " + args.strategy);
  if (args.strategy == "model" && args.tables_out.empty())
    throw std::runtime_error("--strategy model needs --tables-out FOLDER for the updated tables");
  if (args.output.empty() && !(args.strategy == "model" && args.compensated))
    throw std::runtime_error("-o/--output is required (the program of the next part)");
  if (!(args.gain > 0 && args.gain <= 1.5)) throw std::runtime_error("--gain must be in (0, 1.5]");
  if (!(args.radius_mm > 0) || !(args.step_mm > 0) || !(args.cutoff_mm > 0) || !(args.angle_deg > 0))
    throw std::runtime_error("--radius, --angle, --step and --cutoff must be positive");
  if (!(args.min_support >= 0)) throw std::runtime_error("--min-support must be 0 or more");
  if (args.next_program.empty() != args.next_points.empty())
    throw std::runtime_error("--next-program and --next-points go together (the other part's program and CMM plan)");
  if (!args.next_program.empty() && args.strategy != "model")
    throw std::runtime_error("--next-program and --next-points need --strategy model (the tuned tables carry over)");
  if (!(args.tolerance_mm > 0.0 && args.tolerance_mm <= 0.1))
    throw std::runtime_error("--tolerance must be in (0, 0.1] mm");

  const machine::WorldConvention world = world_convention(args.world);
  const machine::Model model = machine::load_machine(args.machine);
  const ProgramFiles files(args.tool_table, args.var_file, args.machine_units);
  const bool tcp = world == machine::WorldConvention::Tcp;

  shop::FirstPartOptions options;
  options.simulation.world = world;
  options.simulation.compensation = args.compensated ? &model : nullptr;
  machine::Conditions compensation_conditions = model.reference_conditions();
  machine::apply_selection(model, types, compensation_conditions);
  options.simulation.compensation_conditions = &compensation_conditions;
  options.simulation.ball_end_tools.insert(args.ball_end_tools.begin(), args.ball_end_tools.end());
  options.surface.flute_length_mm = args.flute_length_mm;
  options.cutoff_mm = args.cutoff_mm;
  options.outlier_sigmas = args.outlier_sigmas;
  shop::ReportFormat format;
  format.unit = args.report_unit;
  format.decimal_comma = args.decimal_comma;
  if (args.deviation_sign == "actual-minus-nominal") format.sign = shop::DeviationSign::ActualMinusNominal;
  if (args.deviation_sign == "nominal-minus-actual") format.sign = shop::DeviationSign::NominalMinusActual;
  std::string layout;
  const std::vector<shop::CmmPoint> measured = shop::read_cmm_points(args.report, true, format, &layout);
  report << "volcomp selftune: " << args.report << " read as " << layout << "\n";
  const interpreter::Setup input_setup = files.setup(args.input, model, tcp);
  const predistort::ToolLengthLog input_lengths = tool_lengths_of(args.input, input_setup);
  report << "  " << args.input << ": " << input_lengths.describe(model, args.input, args.tool_table) << "\n";
  // Points matched to a program's cuts; a refusal names the points' file (a LoadError names its own).
  const auto analyse = [&](const std::string& program, const std::string& points_file,
                           const std::vector<shop::CmmPoint>& points) {
    std::ifstream in = open_program(program);
    try {
      return shop::analyse_first_part(model, in, files.setup(program, model, tcp), points, options);
    } catch (const std::runtime_error& e) {
      if (dynamic_cast<const LoadError*>(&e)) throw;
      const predistort::ToolLengthLog lengths = tool_lengths_of(program, files.setup(program, model, tcp));
      throw std::runtime_error(points_file + ": " + e.what() +
                               tool_length_cause(lengths, model, files, program, args.tool_table));
    }
  };
  const shop::FirstPart part = analyse(args.input, args.report, measured);
  print_first_part(part, report);
  const shop::FormError before = shop::form_error(measured);
  report << "  measured form error: largest " << um(before.largest_mm) << ", RMS " << um(before.rms_mm) << "\n";

  predistort::Provenance provenance{"", args.machine, model.info.name,  {}, args.var_file, args.tool_table,
                                    "", args.world,   args.tolerance_mm};
  // Local: P(i+1) keeps Pi's correction, volkins' (--compensated) or the one in Pi's numbers.
  provenance.types = args.compensated ? types.to_string() : "those " + args.input + " was pre-distorted for";
  if (args.strategy == "local") {
    provenance.title = "volcomp selftune (local): " + args.input + " shifted against the deviations of " + args.report +
                       " (gain " + number_text(args.gain) + ", radius " + number_text(args.radius_mm) + " mm, angle " +
                       number_text(args.angle_deg) + " deg)";
    shop::LocalOptions local{args.gain, args.radius_mm, args.step_mm, args.tolerance_mm, world, args.angle_deg};
    local.tilt = !args.no_tilt;
    local.min_support = args.min_support;
    shop::LocalSummary summary;
    std::ifstream in = open_program(args.input);
    tables::write_atomically(args.output, [&](std::ostream& out) {
      summary = shop::shift_program(model, part, in, files.setup(args.input, model, tcp), provenance, out, local);
    });
    report << "  local: " << summary.moves_shifted << " moves shifted (" << summary.pieces << " pieces); the tool tip "
           << "cuts " << fixed_text(summary.cutting_length_mm, 1) << " mm of path on the part, "
           << fixed_text(summary.covered_fraction * 100, 1) << " % of it within " << number_text(args.radius_mm)
           << " mm of measured points\n"
           << "  largest shift of the tool tip on the part " << um(summary.largest_tip_shift_mm)
           << "; of the linear axes' words " << um(summary.largest_axis_shift_mm)
           << (summary.largest_axis_shift_mm > 1.5 * summary.largest_tip_shift_mm
                   ? " (they carry the tool axis's turn times the rotary axes' lever arms too)"
                   : "")
           << "\n";
    print_tilt(summary.tilt, report);
    return 0;
  }

  // The other part's plan matched to its program's cuts as a report would be (no deviations).
  std::optional<shop::FirstPart> next;
  if (!args.next_program.empty()) {
    std::vector<shop::CmmPoint> plan = shop::read_cmm_points(args.next_points, false);
    for (shop::CmmPoint& p : plan) p.deviation_mm = 0.0;  // only where they are cut matters
    next = analyse(args.next_program, args.next_points, plan);
  }
  shop::ModelOptions fit_options{args.deviations, args.nodes, args.regularisation, args.smoothness};
  const shop::ModelFit fit = shop::fit_model(model, part, fit_options, next ? &*next : nullptr);
  const shop::ModelFitAdvice advice = shop::advise(fit);
  const std::string comment = "volcomp selftune (model) from " + args.report;
  const std::string machine_out =
      shop::write_machine_with_tables(model, args.tables_out, fit.tables, comment, fit.locations);
  report << "  model: " << fit.parameters << " unknowns (" << fit.unobservable << " not seen by this part) from "
         << fit.points << " points; deviation left unexplained by the model RMS " << um(fit.rms_before_mm) << " -> "
         << um(fit.rms_after_mm) << " after the fit; largest change " << um(fit.largest_change_mm) << ", "
         << fixed_text(fit.largest_change_rad * 1e6, 3) << " urad\n";
  if (fit.scatter_mm >= 0.0) {
    report << "  noise: the model leaves " << um(fit.scatter_mm) << " per point (1 sigma; " << fit.points << " points, "
           << fixed_text(fit.effective_unknowns, 1) << " effective unknowns); carried into the tuned "
           << "model at the measured points " << um(fit.carried_median_mm) << " median, " << um(fit.carried_largest_mm)
           << " largest (1 sigma)\n";
  } else {
    report << "  noise: no freedom left to estimate it (" << fit.points << " points, "
           << fixed_text(fit.effective_unknowns, 1) << " effective unknowns)\n";
  }
  if (next) {
    report << "  the next part, " << args.next_points << " (" << fit.next_points << " points on " << args.next_program
           << "'s cuts, " << next->left_out.size() << " on none), gets two things from this tuning:\n";
    if (fit.scatter_mm >= 0.0)
      report << "    this report's noise, carried: " << um(fit.next_carried_median_mm) << " median, "
             << um(fit.next_carried_largest_mm) << " largest (1 sigma)\n";
    else
      report << "    this report's noise, carried: not known (no freedom left to estimate the noise)\n";
    // The deviations this part could not determine, as the next part's points feel them.
    std::string felt;
    for (const shop::ModelFit::Unseen& u : advice.felt_by_next)
      felt += (felt.empty() ? " " : ", ") + u.symbol + " " + fixed_text(u.largest_mm_per_unit * 1e3, 2) + " um per " +
              (u.angle ? "urad" : "um");
    report << "    what this part cannot see: the deviations it did not determine stay as the machine file has them, "
              "and their error is not known from this report, so it cannot be bounded here. ";
    if (felt.empty())
      report << "The next part's points hardly feel them (under 0.05 um per um or urad of each)\n";
    else
      report << "The next part's points feel it most from (largest move per unit of the undetermined part):" << felt
             << "; measure those (laser, ballbar, probing) or cut a first part that exercises them\n";
  }
  if (advice.overfitted)
    report << "  warning: the fit spends " << fixed_text(fit.effective_unknowns, 0) << " of " << fit.points
           << " points on its unknowns, so much of the report's noise goes into the tables: measure more points, "
              "or tune fewer deviations (--deviations)\n";
  // What the part determines: the resolution of each deviation (1: the points alone fix it,
  // 0: only the ridge and the smoothness do, it stays at the model's value).
  std::string shares, unseen;
  for (const auto& s : fit.seen) shares += " " + s.symbol + " " + fixed_text(s.share, 2);
  for (const std::string& symbol : advice.unseen) unseen += " " + symbol;
  report << "  resolution (1: determined by the points alone, 0: not seen):" << shares << "\n"
         << "  not seen by this part (< 0.05: kept at the model; restrict with --deviations):"
         << (unseen.empty() ? " none" : unseen) << "\n";
  for (const shop::LocationValue& v : fit.locations) {
    const char letter = model.axes[static_cast<std::size_t>(v.joint)].letter;
    report << "  " << tables::ErrorSymbol{v.component, letter, true}.name() << " = "
           << (v.component < 3 ? um(v.value) : fixed_text(v.value * 1e6, 3) + " urad") << "\n";
  }
  report << "  updated machine file: " << machine_out << "\n";
  const machine::Model tuned = machine::load_machine(machine_out);  // as the module will read it
  if (args.compensated) {
    report << "  load it in volkins";
    if (!types.is_all()) report << " with the same compensation types on (" << types.to_string() << ")";
    report << "; the program stays as it is\n";
    return 0;
  }
  const std::string nominal = args.nominal.empty() ? args.input : args.nominal;
  // P0 pre-distorted with the tuned model for the types given (as --types in predistort).
  machine::Conditions next_conditions = tuned.reference_conditions();
  machine::apply_selection(tuned, types, next_conditions);
  predistort::Job job;
  job.model = &tuned;
  job.conditions = &next_conditions;
  job.setup = files.setup(nominal, tuned, tcp);
  job.corrector.tolerance_mm = args.tolerance_mm;
  job.corrector.world = world;
  job.provenance = provenance;
  job.provenance.machine = machine_out;
  job.provenance.types = types.to_string();
  for (const auto& t : tuned.tables) job.provenance.tables.push_back(t.table.path());
  std::ifstream in = open_program(nominal);
  predistort::Summary summary;
  tables::write_atomically(args.output, [&](std::ostream& out) { summary = predistort::predistort(in, out, job); });
  report << "  " << nominal << " pre-distorted with the updated tables: " << summary.corrector.pieces << " pieces\n";
  for (const std::string& note : predistort::correction_notes(summary, job)) report << "  " << note << "\n";
  return 0;
}

}  // namespace

void add_selftune_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<SelftuneArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "selftune", "Program of the next part from the measured deviations of this one (local or model strategy)");
  cmd->add_option("MACHINE", args->machine, "machine file the program was made for (.toml)")->required();
  cmd->add_option("PROGRAM", args->input, "program Pi that machined the measured part")->required();
  cmd->add_option("REPORT", args->report,
                  "CMM report Ri: id,x[mm],y[mm],z[mm],i,j,k,deviation[um], or a CMM software's table "
                  "export (nominal X Y Z, normal I J K out of the material, actual X Y Z or deviation)")
      ->required();
  cmd->add_option("--report-unit", args->report_unit,
                  "CMM export: the unit of the columns whose header names none (mm, um, inch)");
  cmd->add_option("--deviation-sign", args->deviation_sign,
                  "CMM export: what its deviation column is: actual-minus-nominal (+ = material left, along "
                  "an outward normal) or nominal-minus-actual")
      ->check(CLI::IsMember({"actual-minus-nominal", "nominal-minus-actual"}));
  cmd->add_flag("--decimal-comma", args->decimal_comma, "CMM export: numbers are written 12,5");
  cmd->add_option("-o,--output", args->output, "program P(i+1)");
  cmd->add_option("--strategy", args->strategy, "local (shift the path) or model (tune the tables)")
      ->capture_default_str();
  cmd->add_option("--var", args->var_file, "LinuxCNC parameter file (.var)");
  cmd->add_option("--tool-table", args->tool_table, "LinuxCNC tool table (.tbl): lengths and diameters");
  cmd->add_option("--machine-units", args->machine_units,
                  "the unit of the tool table and the .var file, LinuxCNC's [TRAJ]LINEAR_UNITS: mm or inch")
      ->capture_default_str();
  cmd->add_option("--world", args->world, "world convention: axes or tcp")->capture_default_str();
  cmd->add_flag("--compensated", args->compensated,
                "PROGRAM ran with volkins correcting with MACHINE (not pre-distorted)");
  add_types_option(*cmd, args->types,
                   "with --compensated, the compensation types volkins corrected PROGRAM with (its type pins); with "
                   "--strategy model also the types the next program is pre-distorted for (or volkins corrects it "
                   "with). A pre-distorted PROGRAM carries its types in its numbers");
  cmd->add_option("--ball-end", args->ball_end_tools, "tools with a ball end")->delimiter(',');
  cmd->add_option("--flute-length", args->flute_length_mm, "cutting length of the tools, mm")->capture_default_str();
  cmd->add_option("--cutoff", args->cutoff_mm, "shorter wavelengths are not tuned (low-pass), mm")
      ->capture_default_str();
  cmd->add_option("--outlier-sigmas", args->outlier_sigmas, "outlier threshold, robust sigmas")->capture_default_str();
  cmd->add_option("--gain", args->gain, "local: share of the deviation taken off")->capture_default_str();
  cmd->add_option("--radius", args->radius_mm, "local: deviations reach the path within this, mm")
      ->capture_default_str();
  cmd->add_option("--angle", args->angle_deg,
                  "local: deviations reach path points whose tool frame is turned less than this from the cut's, deg")
      ->capture_default_str();
  cmd->add_option(
         "--min-support", args->min_support,
         "local: where fewer measured points than this carry a shift, widen its window (radius and angle x 1.5, up to 3 times); 0: never")
      ->capture_default_str();
  cmd->add_flag("--no-tilt", args->no_tilt, "local: keep the program's tool axis on 5-axis moves (shift the tip only)");
  cmd->add_option("--step", args->step_mm, "local: longest piece of a shifted move, mm")->capture_default_str();
  cmd->add_option("--tolerance", args->tolerance_mm, "chord and blending tolerance, mm")->capture_default_str();
  cmd->add_option("--tables-out", args->tables_out, "model: folder for the updated machine file and tables");
  cmd->add_option("--nominal", args->nominal, "model: the original program P0 (default: PROGRAM)");
  cmd->add_option(
      "--next-program", args->next_program,
      "model: the program of another part (with --next-points): the noise the tuned tables carry to its points");
  cmd->add_option("--next-points", args->next_points, "model: that part's CMM plan (id,x,y,z,i,j,k)");
  cmd->add_option("--deviations", args->deviations,
                  "model: deviations to tune, e.g. EXX,EX0C (default: every table and the rotary axes' locations)")
      ->delimiter(',');
  cmd->add_option("--nodes", args->nodes,
                  "model: table nodes over each axis's travel (a full turn: a Fourier series of order (nodes - 1) / 2)")
      ->capture_default_str();
  cmd->add_option("--regularisation", args->regularisation, "model: ridge on scaled unknowns")->capture_default_str();
  cmd->add_option("--smoothness", args->smoothness, "model: penalty on second differences")->capture_default_str();
  cmd->callback([args, &exit_code] { exit_code = run_selftune(*args, std::cerr); });
}

}  // namespace vc::cli
