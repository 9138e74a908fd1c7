// `volcomp fit-tables MACHINE --controller C -o DIR`: the source's modified method for a stock
// controller (preproc/fit_tables/README.md): the controller's tables filled so that the whole
// model's tool-tip error is smallest, judged against no compensation, the usual practice and
// the full correction; DIR/report.csv and DIR/tables.csv, the controller's own files
// (LinuxCNC COMP_FILEs, Sinumerik AX_EEC.INI / NC_CEC.INI), a summary on stdout.
#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "vc/tables/atomic_file.hpp"
#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "program_files.hpp"
#include "vc/fit_tables/comp_file.hpp"
#include "vc/fit_tables/sinumerik_file.hpp"
#include "vc/fit_tables/study_csv.hpp"
#include "vc/identify/iso230_2.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/plot/gnuplot.hpp"
#include "vc/shop/tool_path.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::cli {
namespace {

struct FitTablesArgs {
  std::string machine;
  std::string controller;                       // a shipped controller's name or a controller file
  std::string output;                           // folder: report.csv, tables.csv, the controller's files
  std::string criterion = "minimax";            // minimax or ls
  std::vector<std::string> tool_lengths;        // mm, fitted (default: the machine file's)
  std::vector<std::string> check_tool_lengths;  // mm, judged only (default: midpoints, largest + 50)
  std::vector<std::string> rotary;              // "B=-90,-60,0": rotary grid positions, deg
  std::optional<int> nodes;                     // per table (default: the controller's)
  std::optional<int> levels;                    // grid positions per joint (default: the nodes)
  int fresh = 2000;                             // random poses per tool length in each fresh set
  double ridge = 1e-2, smoothness = 1e-2;       // the fit's regularisation (fit.hpp)
  std::vector<std::string> programs;            // part programs whose poses are fitted too
  bool programs_only = false;                   // ... and nothing else (the volume judged only)
  std::string tool_table, var_file;             // LinuxCNC's files the programs are read with
  std::string machine_units = "mm";
  std::vector<std::string> reversal;  // "X=runs.csv": laser runs whose reversal the COMP_FILE takes
};

double parse_number(const std::string& text, const std::string& option) {
  double v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(v))
    throw std::invalid_argument(option + ": '" + text + "' is not a number");
  return v;
}

// "B=-90,-60,0" -> 'B', {-90, -60, 0}
std::pair<char, std::vector<double>> parse_rotary(const std::string& text) {
  if (text.size() < 3 || text[1] != '=' || !std::isalpha(static_cast<unsigned char>(text[0])))
    throw std::invalid_argument("--rotary " + text +
                                ": expected LETTER=POSITIONS, e.g. --rotary B=-90,-60,-30,0,30 (deg)");
  std::vector<double> positions;
  std::stringstream list(text.substr(2));
  for (std::string v; std::getline(list, v, ',');) positions.push_back(parse_number(v, "--rotary " + text));
  return {static_cast<char>(std::toupper(static_cast<unsigned char>(text[0]))), positions};
}

// The report's four compensations per tool length, on the fresh poses (never fitted): M and
// Delta as clustered bars (gnuplot, preproc/plot; the drawn numbers in figures.csv beside it).
void draw_figures(const fit_tables::Study& study, const std::string& machine_name, const std::string& controller_title,
                  const std::string& image) {
  std::ostringstream data;
  data << "# volcomp fit-tables: M and Delta of the tool-tip error (um) on fresh poses (not fitted), per tool length\n"
       << "label,L[mm],fitted,none_M[um],usual_M[um],modified_M[um],full_M[um],none_Delta[um],usual_Delta[um],"
          "modified_Delta[um],full_Delta[um]\n";
  for (const fit_tables::ReportRow& r : study.rows) {
    if (r.set != "fresh") continue;
    data << number_text(r.tool_length_mm) << " mm" << (r.fitted_length ? "" : " (check)") << ','
         << number_text(r.tool_length_mm) << ',' << (r.fitted_length ? "yes" : "no");
    for (const auto* f : {&r.none, &r.usual, &r.modified, &r.full}) data << ',' << fixed_text(f->max_um, 3);
    for (const auto* f : {&r.none, &r.usual, &r.modified, &r.full}) data << ',' << fixed_text(f->delta_um, 3);
    data << '\n';
  }
  std::ostringstream gp;
  gp << "set datafile separator ','\nset style data histograms\nset style histogram clustered gap 1\n"
     << "set style fill solid 0.85 border -1\nset boxwidth 0.9\nset grid ytics\nset key outside right top\n"
     << "set multiplot layout 2,1 title "
     << plot::text_literal(machine_name + ", " + controller_title + ":\ntool-tip error on poses never fitted") << '\n'
     << "set xlabel 'tool length L (check: not fitted)'\n";
  const char* names[] = {"none", "usual practice", "modified method", "full correction (volkins): 0"};
  const char* colours[] = {"#c0392b", "#e67e22", "#2471a3", "#1e8449"};
  for (const auto& [first_column, label] :
       {std::pair{4, "M = max |error| (um)"}, std::pair{8, "Delta = max - min (um)"}}) {
    gp << "set ylabel '" << label << "'\nplot ";
    for (int k = 0; k < 4; ++k)
      gp << (k ? ", '' " : "DATA ") << "every ::1 using " << first_column + k << (k ? "" : ":xtic(1)") << " title "
         << plot::text_literal(names[k]) << " lc rgb '" << colours[k] << "'";
    gp << '\n';
  }
  gp << "unset multiplot\n";
  plot::draw({image, data.str(), gp.str(), 1400, 900});
}

// The poses of part programs as a stock machine runs them (program coordinates = the joints,
// LinuxCNC's trivkins; the tool length from G43): every sample of shop::simulate's path (at most
// 2 mm apart), thinned evenly to at most `most` per program.
std::vector<fit_tables::Pose> program_poses(const machine::Model& model, const FitTablesArgs& args, std::size_t most) {
  const ProgramFiles files(args.tool_table, args.var_file, args.machine_units);
  std::vector<fit_tables::Pose> all;
  for (const std::string& program : args.programs) {
    std::ifstream in(program, std::ios::binary);
    if (!in) throw LoadError({program}, "cannot open the program");
    shop::SimulationOptions options;
    options.step_mm = 2.0;
    options.world = machine::WorldConvention::Axes;
    std::vector<fit_tables::Pose> poses;
    shop::simulate(model, in, files.setup(program, model, false), options, [&](const shop::PathSample& sample) {
      poses.push_back({sample.joints, sample.tool_length_mm});
    });
    if (poses.empty()) throw LoadError({program}, "the program has no moves");
    const std::size_t keep = std::min(poses.size(), most);
    for (std::size_t k = 0; k < keep; ++k) all.push_back(poses[k * poses.size() / keep]);
  }
  return all;
}

std::string padded(std::string text, std::size_t width) {
  if (text.size() < width) text.resize(width, ' ');
  return text;
}

std::string figure(const fit_tables::Figures& f) {
  std::string s = fixed_text(f.max_um, 1) + " / " + fixed_text(f.delta_um, 1);
  return std::string(s.size() < 15 ? 15 - s.size() : 1, ' ') + s;
}

// "--reversal X=runs.csv": the joint's reversal B_i at the laser's targets (ISO 230-2, the
// suspicious runs left out as identify laser leaves them), in machine units (mm or deg).
fit_tables::JointReversal read_reversal(const machine::Model& model, const std::string& text, std::ostream& out) {
  const char letter =
      text.size() > 2 && text[1] == '=' ? static_cast<char>(std::toupper(static_cast<unsigned char>(text[0]))) : 0;
  const int joint = letter ? model.joint_of(letter) : -1;
  if (joint < 0)
    throw std::invalid_argument("--reversal " + text + ": AXIS=RUNS.csv, AXIS one of the machine's (" +
                                model.coordinates() + ")");
  const std::string path = text.substr(2);
  const identify::LaserRuns runs = identify::read_laser_runs(path);
  const bool rotary = model.axes[static_cast<std::size_t>(joint)].type == machine::AxisType::Rotary;
  if (runs.rotary != rotary || runs.quantity != (rotary ? tables::Quantity::Angle : tables::Quantity::Length))
    throw std::invalid_argument(path + ": not " + letter + "'s positioning (" +
                                (rotary ? "targets in deg, deviations angles" : "targets in mm, deviations lengths") +
                                ")");
  std::set<identify::RunKey> left_out;
  for (const identify::SuspiciousRun& s : identify::suspicious_runs(runs)) left_out.insert(s.run);
  const identify::Iso230_2 e = identify::evaluate_iso230_2(runs, left_out);
  const double unit = rotary ? 180.0 / M_PI : 1.0;  // core units (mm, rad) -> machine units (mm, deg)
  fit_tables::JointReversal r;
  r.joint = joint;
  for (const identify::TargetStatistics& t : e.targets) {
    r.target.push_back(t.target);
    r.reversal.push_back(t.reversal * unit);
  }
  const double shown = rotary ? 3600.0 * 180.0 / M_PI : 1e3;
  const char* symbol = rotary ? " arcsec" : " um";
  out << "reversal of " << letter << " from " << path << " (" << e.targets.size() << " targets, " << e.runs_up << " + "
      << e.runs_down << " runs" << (left_out.empty() ? "" : ", " + std::to_string(left_out.size()) + " left out")
      << "): B = " << fixed_text(e.reversal * shown, 2) << symbol << ", mean " << fixed_text(e.mean_reversal * shown, 2)
      << symbol << ": its COMP_FILE's forward column is the value - B/2, the reverse one + B/2\n";
  return r;
}

int run_fit_tables(const FitTablesArgs& args, std::ostream& out) {
  namespace fs = std::filesystem;
  fit_tables::StudyOptions o;
  if (args.criterion == "ls") {
    o.fit.criterion = fit_tables::Criterion::LeastSquares;
  } else if (args.criterion != "minimax") {
    throw std::invalid_argument("--criterion " + args.criterion + ": ls (least squares) or minimax (smallest M)");
  }
  o.nodes = args.nodes;
  o.levels = args.levels;
  o.fresh_poses = args.fresh;
  if (!(args.ridge >= 0) || !(args.smoothness >= 0) || !std::isfinite(args.ridge) || !std::isfinite(args.smoothness))
    throw std::invalid_argument("--ridge and --smoothness must be numbers >= 0");
  o.fit.ridge = args.ridge;
  o.fit.smoothness = args.smoothness;
  for (const std::string& t : args.tool_lengths) o.tool_lengths_mm.push_back(parse_number(t, "--tool-lengths"));
  if (!args.check_tool_lengths.empty()) {
    o.check_tool_lengths_mm.emplace();
    for (const std::string& t : args.check_tool_lengths)
      o.check_tool_lengths_mm->push_back(parse_number(t, "--check-tool-lengths"));
  }
  for (const std::string& r : args.rotary) {
    auto [letter, positions] = parse_rotary(r);
    if (o.rotary.count(letter)) throw std::invalid_argument(std::string("--rotary ") + letter + " is given twice");
    o.rotary[letter] = positions;
  }
  if (fs::exists(args.output) && !fs::is_directory(args.output))
    throw std::invalid_argument("-o " + args.output + ": exists and is not a folder");

  const machine::Model model = machine::load_machine(args.machine);
  if (!args.programs.empty()) o.program_poses = program_poses(model, args, 5000);
  if (args.programs_only && args.programs.empty()) throw std::invalid_argument("--programs-only needs --programs");
  o.programs_only = args.programs_only;
  const fit_tables::Controller controller = fit_tables::load_controller(fit_tables::controller_file(args.controller));
  // The reversals are read (and refused) before the study's minutes.
  if (!args.reversal.empty() && controller.format != "linuxcnc-comp-file")
    throw std::invalid_argument("--reversal: the tables of " + controller.title +
                                " have one value per node for both directions; set the drive's backlash instead");
  std::vector<fit_tables::JointReversal> reversals;
  for (const std::string& r : args.reversal) {
    reversals.push_back(read_reversal(model, r, out));
    for (std::size_t k = 0; k + 1 < reversals.size(); ++k)
      if (reversals[k].joint == reversals.back().joint)
        throw std::invalid_argument("--reversal " + r + ": that axis is given twice");
  }
  const fit_tables::Study study = fit_tables::run_study(model, controller, o);

  // Every file is complete in memory before any is written.
  std::vector<std::pair<std::string, std::string>> files;  // name, text
  std::ostringstream report, tables;
  fit_tables::write_report_csv(study, model, controller, o, report);
  fit_tables::write_tables_csv(study, model, controller, tables);
  files.emplace_back("report.csv", report.str());
  files.emplace_back("tables.csv", tables.str());
  std::string ini_lines;
  if (controller.format == "linuxcnc-comp-file") {
    const auto comp = fit_tables::linuxcnc_comp_files(model, study.set, study.modified, reversals);
    for (const fit_tables::LinuxcncCompFile& f : comp) files.emplace_back(f.file_name, f.text);
    ini_lines = fit_tables::linuxcnc_ini_lines(comp);
    files.emplace_back("linuxcnc_ini_lines.txt", ini_lines);
    // The usual practice's tables too, to run the comparison on the machine itself.
    for (const fit_tables::LinuxcncCompFile& f :
         fit_tables::linuxcnc_comp_files(model, study.set, study.usual, reversals))
      files.emplace_back("usual_practice/" + f.file_name, f.text);
  }
  std::string sinumerik_setup;
  if (controller.format == "sinumerik-lec-cec") {
    const auto sinumerik =
        fit_tables::sinumerik_files(model, study.set, study.modified, fit_tables::sinumerik_resolution(controller));
    for (const fit_tables::SinumerikFile& f : sinumerik) files.emplace_back(f.file_name, f.text);
    sinumerik_setup = fit_tables::sinumerik_setup_lines(study.set, sinumerik);
    files.emplace_back("sinumerik_setup.txt", sinumerik_setup);
  }
  // The plot first (it writes figures.png and figures.csv, each atomically): a failing gnuplot
  // leaves nothing behind.
  fs::create_directories(args.output);
  draw_figures(study, model.info.name, controller.title, (fs::path(args.output) / "figures.png").string());
  for (const auto& [name, text] : files) {
    const fs::path path = fs::path(args.output) / name;
    fs::create_directories(path.parent_path());
    tables::write_atomically(path.string(), [&](std::ostream& f) { f << text; });
  }

  out << "fit-tables: " << model.info.name << " with " << controller.name << " (" << controller.title << ")\n";
  for (const std::string& note : study.set.notes) out << "note: " << note << '\n';
  out << study.set.tables.size() << " tables, " << study.set.unknowns << " values; criterion " << args.criterion
      << "; ";
  if (o.programs_only)
    out << "fitted to " << study.program_poses << " poses of the part programs alone (the grid's " << study.grid_poses
        << " poses and the fresh ones judged only: see what the tables leave there)\n";
  else
    out << study.grid_poses << " grid poses (" << study.levels << " per joint) + " << study.program_poses
        << " poses of the part programs + " << study.added_poses << " worst fresh poses refitted\n";
  if (o.fit.criterion == fit_tables::Criterion::Minimax && study.fit.lower_bound_mm > 0)
    out << "minimax (Lawson): " << study.fit.iterations << " solves; the linearised M is within "
        << fixed_text(100.0 * (study.fit.linear_max_mm / study.fit.lower_bound_mm - 1.0), 2)
        << " % of the minimax's lower bound\n";
  out << "M / Delta of the tool-tip error, um (nonlinear model):\n"
      << "  L [mm]  fitted  set                none           usual        modified            full\n";
  for (const fit_tables::ReportRow& r : study.rows) {
    std::string l = number_text(r.tool_length_mm);
    out << "  " << std::string(l.size() < 6 ? 6 - l.size() : 1, ' ') << l << "  "
        << (r.fitted_length ? "  yes " : "   no ") << "  " << padded(r.set, 8) << figure(r.none) << figure(r.usual)
        << figure(r.modified) << figure(r.full) << '\n';
  }
  if (!ini_lines.empty()) out << "the INI lines (" << args.output << "/linuxcnc_ini_lines.txt):\n" << ini_lines;
  if (!sinumerik_setup.empty())
    out << "the Sinumerik steps (" << args.output << "/sinumerik_setup.txt):\n" << sinumerik_setup;
  out << "written in " << args.output << ": figures.png figures.csv";
  for (const auto& f : files) out << ' ' << f.first;
  out << '\n';
  return 0;
}

}  // namespace

void add_fit_tables_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<FitTablesArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "fit-tables",
      "A stock controller's compensation tables by the source's modified method: all tables fitted "
      "together to the whole model; M and Delta of none, usual practice, fit and full correction");
  cmd->add_option("MACHINE", args->machine, "machine description file (.toml)")->required();
  cmd->add_option("--controller", args->controller,
                  "the controller's tables: linuxcnc, source14, or a controller file (.toml)")
      ->required();
  cmd->add_option("-o,--output", args->output,
                  "folder for report.csv, tables.csv and the controller's own files (LinuxCNC: COMP_FILEs "
                  "and the INI lines)")
      ->required();
  cmd->add_option("--criterion", args->criterion, "minimax (smallest M) or ls (least squares)")->capture_default_str();
  cmd->add_option("--tool-lengths", args->tool_lengths,
                  "tool lengths L fitted together, mm, e.g. 0,100,200 (default: the machine file's)")
      ->delimiter(',');
  cmd->add_option("--check-tool-lengths", args->check_tool_lengths,
                  "tool lengths judged but not fitted, mm (default: the fitted ones' midpoints and largest + 50)")
      ->delimiter(',');
  cmd->add_option("--rotary", args->rotary,
                  "rotary grid positions, deg, e.g. --rotary B=-90,-60,-30,0,30 (repeatable; default: --levels "
                  "positions over the travel)");
  cmd->add_option("--nodes", args->nodes,
                  "nodes per table, equally spaced over the travel (default: the controller's)");
  cmd->add_option("--levels", args->levels, "grid positions per joint (default: the nodes)");
  cmd->add_option("--fresh", args->fresh, "random poses per tool length in each fresh set (refit, check)")
      ->capture_default_str();
  cmd->add_option("--ridge", args->ridge,
                  "regularisation towards the usual practice, relative to each table's tip effect")
      ->capture_default_str();
  cmd->add_option("--smoothness", args->smoothness,
                  "regularisation of the second differences of the departure from the usual practice")
      ->capture_default_str();
  cmd->add_option("--programs", args->programs,
                  "part programs (G-code, as the stock machine runs them: no TCP) whose poses are fitted "
                  "with the grid and judged as the set 'programs'")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--programs-only", args->programs_only,
                "fit the programs' poses alone: best for those parts, the volume only judged");
  cmd->add_option("--tool-table", args->tool_table, "LinuxCNC tool table the programs are read with");
  cmd->add_option("--var", args->var_file, "LinuxCNC parameter file (.var) the programs are read with");
  cmd->add_option("--machine-units", args->machine_units, "mm or inch: LinuxCNC's [TRAJ]LINEAR_UNITS");
  cmd->add_option("--reversal", args->reversal,
                  "AXIS=RUNS.csv: laser runs of that axis in both directions (identify laser's format); "
                  "its COMP_FILE's forward and reverse columns take their reversal B (LinuxCNC only; repeatable)");
  cmd->callback([args, &exit_code] { exit_code = run_fit_tables(*args, std::cout); });
}

}  // namespace vc::cli
