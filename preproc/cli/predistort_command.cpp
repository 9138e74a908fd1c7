// volcomp predistort: writes a part program that makes an uncompensated machine cut the
// nominal part. Never leaves a half-written output: the program is written to a temporary
// file beside the output and renamed over it only when complete. `-o -` writes to stdout,
// as a LinuxCNC AXIS program filter does ([FILTER] ngc = volcomp predistort MACHINE -o - ...),
// with AXIS's FILTER_PROGRESS protocol on stderr.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <unistd.h>
#include <vector>

#include "vc/tables/atomic_file.hpp"
#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "program_files.hpp"
#include "types_option.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/deflection.hpp"
#include "vc/predistort/predistort.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::cli {
namespace {

struct PredistortArgs {
  std::string machine;
  std::string input;
  std::string output;                        // "-": stdout (AXIS filter)
  std::string var_file;                      // LinuxCNC parameter file: work offsets, G28/G30 homes
  std::string tool_table;                    // LinuxCNC tool table: tool lengths
  std::string machine_units = "mm";          // of the tool table and the .var file: mm or inch
  std::string process;                       // cutting conditions per tool: cutting-force deflection
  std::string world = "axes";                // world convention of the uncompensated kinematics
  std::vector<std::string> subroutine_path;  // folders of NAME.ngc subroutine files
  std::string start;                         // where the machine starts: X,Y,Z[,A,B,C] or an INI (homes)
  std::string line_map;                      // CSV: output line -> input file and line
  double tolerance_mm = 0.0005;
  double tolerance_rad = 2e-5;            // tool direction between written points (rotary axes)
  std::vector<std::string> temperatures;  // NAME=VALUE (degC) of the machine file's [temperatures]
  TypesOption types;                      // the compensation types the program is pre-distorted for
  bool quiet = false;
};

namespace fs = std::filesystem;

// Progress on stderr: FILTER_PROGRESS=<percent> lines for AXIS (it sets AXIS_PROGRESS_BAR
// for its filters), a bar on a terminal, nothing otherwise.
class Progress {
 public:
  explicit Progress(long total) : total_(std::max(total, 1L)) {
    axis_ = std::getenv("AXIS_PROGRESS_BAR") != nullptr;
    terminal_ = !axis_ && isatty(STDERR_FILENO);
  }
  void operator()(long bytes) {
    const int percent = static_cast<int>(std::min(100L, bytes * 100 / total_));
    if (percent == last_) return;
    last_ = percent;
    if (axis_) {
      std::fprintf(stderr, "FILTER_PROGRESS=%d\n", percent);
    } else if (terminal_) {
      const int filled = percent / 4;
      std::fprintf(stderr, "\r[%.*s%.*s] %3d%%", filled, "#########################", 25 - filled,
                   "                         ", percent);
      if (percent == 100) std::fputc('\n', stderr);
    }
    std::fflush(stderr);
  }

 private:
  long total_;
  bool axis_ = false, terminal_ = false;
  int last_ = -1;
};

int run_predistort(const PredistortArgs& args, std::ostream& report) {
  const machine::TypeSelection types = args.types.selection();
  if (!(args.tolerance_mm > 0.0 && args.tolerance_mm <= 0.1))
    throw std::runtime_error("--tolerance must be in (0, 0.1] mm");
  if (!(args.tolerance_rad > 0.0 && args.tolerance_rad <= 0.01))
    throw std::runtime_error("--tolerance-rad must be in (0, 0.01] rad");
  const machine::WorldConvention world = world_convention(args.world);
  const machine::Model model = machine::load_machine(args.machine);
  machine::Conditions temperatures = model.reference_conditions();  // the program is made for
  std::string conditions;                                           // the same, for its header
  for (const std::string& t : args.temperatures) {
    const auto eq = t.find('=');
    double value = 0;
    try {
      if (eq == std::string::npos) throw std::invalid_argument("");
      value = std::stod(t.substr(eq + 1));
    } catch (const std::logic_error&) {
      throw std::runtime_error("--temperature " + t + ": NAME=VALUE in degC, e.g. x_screw=27.5");
    }
    model.set_temperature(temperatures, t.substr(0, eq), value);
    conditions += ", " + t.substr(0, eq) + " " + t.substr(eq + 1) + " degC";
  }
  // After --temperature: without thermal the temperatures go back to their references.
  machine::apply_selection(model, types, temperatures);
  if (!types.thermal && !args.temperatures.empty()) conditions += " (not compensated: thermal is off)";
  const ProgramFiles files(args.tool_table, args.var_file, args.machine_units);
  const std::optional<predistort::Deflection> deflection = files.deflection(args.process, model);

  predistort::Job job;
  job.model = &model;
  job.conditions = &temperatures;
  job.setup = files.setup(args.input, model, world == machine::WorldConvention::Tcp);
  job.setup.subroutine_path = args.subroutine_path;
  if (!args.start.empty()) job.setup.start_world = start_position(args.start, files.machine_unit_mm);
  job.corrector.tolerance_mm = args.tolerance_mm;
  job.corrector.tolerance_rad = args.tolerance_rad;
  job.corrector.world = world;
  job.deflection = deflection ? &*deflection : nullptr;
  job.provenance = {{},           args.machine,  model.info.name + conditions,
                    {},           args.var_file, args.tool_table,
                    args.process, args.world,    args.tolerance_mm};
  job.provenance.types = types.to_string();
  for (const auto& t : model.tables) job.provenance.tables.push_back(t.table.path());

  // Read in 1 MiB pieces, not the stream's default 8 KiB: a million-line program is then
  // ~50 reads instead of ~6,500 system calls.
  std::vector<char> read_buffer(std::size_t{1} << 20);
  std::ifstream in;
  in.rdbuf()->pubsetbuf(read_buffer.data(), static_cast<std::streamsize>(read_buffer.size()));
  in.open(args.input, std::ios::binary);
  if (!in) throw LoadError({args.input}, "cannot open the program");
  std::error_code size_error;
  const auto size = fs::file_size(args.input, size_error);
  Progress progress(size_error ? 1 : static_cast<long>(size));

  std::ostringstream line_map;
  if (!args.line_map.empty()) {
    line_map << "output_line,input_file,input_line\n";
    job.line_map = &line_map;
  }
  predistort::Summary summary;
  if (args.output == "-") {
    summary = predistort::predistort(in, std::cout, job, std::ref(progress));
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("cannot write to stdout");
  } else {
    tables::write_atomically(
        args.output, [&](std::ostream& out) { summary = predistort::predistort(in, out, job, std::ref(progress)); });
  }

  if (!args.line_map.empty())
    tables::write_atomically(args.line_map, [&](std::ostream& out) { out << line_map.str(); });
  if (!args.quiet) {
    const auto& c = summary.corrector;
    report << "volcomp predistort: " << summary.lines << " lines, " << c.moves << " moves corrected into " << c.pieces
           << " pieces (" << c.corrections << " corrections, " << c.checks << " checks), max error at "
           << "the check points " << fixed_text(c.max_checked_error_mm * 1e3, 3) << " um (tolerance "
           << number_text(args.tolerance_mm * 1e3) << " um)";
    if (model.rotary_count() > 0)
      report << ", tool direction " << fixed_text(c.max_checked_error_rad * 1e6, 2) << " urad (tolerance "
             << number_text(args.tolerance_rad * 1e6) << " urad)";
    if (c.max_deflection_mm > 0)
      report << ", max deflection taken off " << fixed_text(c.max_deflection_mm * 1e3, 3) << " um";
    report << '\n';
    if (summary.written_as_is_moves)
      report << "  " << summary.written_as_is_moves
             << " moves written as they are (G28/G30, or rapids before every axis was set)\n";
    if (c.tolerance_misses) report << "  warning: " << c.tolerance_misses << " moves could not meet the tolerance\n";
    // The tool lengths used and where they came from; moves without G43; points off the grids.
    for (const std::string& note : predistort::correction_notes(summary, job)) report << "  " << note << '\n';
  }
  return 0;
}

}  // namespace

void add_predistort_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<PredistortArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "predistort", "Write a part program that makes the uncompensated machine cut the nominal part");
  cmd->add_option("MACHINE", args->machine, "machine description file (.toml)")->required();
  cmd->add_option("PROGRAM", args->input, "part program (RS274/NGC)")->required();
  cmd->add_option("-o,--output", args->output, "pre-distorted program, or - for stdout")->required();
  cmd->add_option("--var", args->var_file, "LinuxCNC parameter file (.var): work offsets G54..G59.3, G28/G30 homes");
  cmd->add_option("--tool-table", args->tool_table, "LinuxCNC tool table (.tbl): tool lengths");
  cmd->add_option("--machine-units", args->machine_units,
                  "the unit of the tool table and the .var file, LinuxCNC's [TRAJ]LINEAR_UNITS: mm or inch")
      ->capture_default_str();
  cmd->add_option("--subroutine-path", args->subroutine_path,
                  "folders searched for NAME.ngc when o<name> call or M98 P<n> finds no definition in the program "
                  "(the INI's [RS274NGC]SUBROUTINE_PATH and [DISPLAY]PROGRAM_PREFIX); ':'-separated or repeated")
      ->delimiter(':')
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--line-map", args->line_map,
                  "write output_line,input_file,input_line for every line of the output (CSV): where "
                  "each line of the flat program comes from");
  cmd->add_option(
      "--start", args->start,
      "where the machine is when the program starts, for a program that cuts before it has moved every axis: "
      "X,Y,Z[,A,B,C] (machine coordinates, mm and deg) or the machine's LinuxCNC INI file (its [JOINT_n]HOME, "
      "the position after homing). Without it such a program is refused");
  cmd->add_option("--process", args->process, "cutting conditions per tool (.toml): adds the cutting-force deflection");
  cmd->add_option("--tolerance", args->tolerance_mm, "largest path deviation from the exact correction, mm")
      ->capture_default_str();
  cmd->add_option("--temperature", args->temperatures,
                  "NAME=VALUE: a temperature input of the machine file, degC (repeatable; default: its reference)");
  add_types_option(*cmd, args->types, "the compensation types the program is pre-distorted for (named in its header)");
  cmd->add_option("--tolerance-rad", args->tolerance_rad,
                  "largest tool direction deviation from the exact correction between the written points, "
                  "rad (machines with rotary axes)")
      ->capture_default_str();
  cmd->add_option("--world", args->world, "world convention of the machine's kinematics: axes (trivkins) or tcp")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", args->quiet, "no summary on stderr");
  cmd->callback([args, &exit_code] { exit_code = run_predistort(*args, std::cerr); });
}

}  // namespace vc::cli
