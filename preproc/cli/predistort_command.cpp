// volcomp predistort: writes a part program that makes an uncompensated machine cut the
// nominal part. Never leaves a half-written output: the program is written to a temporary
// file beside the output and renamed over it only when complete. `-o -` writes to stdout,
// as a LinuxCNC AXIS program filter does ([FILTER] ngc = volcomp predistort MACHINE -o - ...),
// with AXIS's FILTER_PROGRESS protocol on stderr.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <vector>
#include <unistd.h>

#include "vc/tables/atomic_file.hpp"
#include "commands.hpp"
#include "format.hpp"
#include "program_files.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/deflection.hpp"
#include "vc/predistort/predistort.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::cli {
namespace {

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

}  // namespace

int run_predistort(const PredistortArgs& args, std::ostream& report) {
  if (!(args.tolerance_mm > 0.0 && args.tolerance_mm <= 0.1))
    throw std::runtime_error("--tolerance must be in (0, 0.1] mm");
  if (!(args.tolerance_rad > 0.0 && args.tolerance_rad <= 0.01))
    throw std::runtime_error("--tolerance-rad must be in (0, 0.01] rad");
  const machine::WorldConvention world = world_convention(args.world);
  const machine::Model model = machine::load_machine(args.machine);
  machine::Conditions temperatures = model.reference_conditions();  // the program is made for
  std::string conditions;  // the same, for its header
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
  job.provenance = {{}, args.machine, model.info.name + conditions, {}, args.var_file, args.tool_table, args.process,
                    args.world, args.tolerance_mm};
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
    tables::write_atomically(args.output, [&](std::ostream& out) { summary = predistort::predistort(in, out, job, std::ref(progress)); });
  }

  if (!args.line_map.empty())
    tables::write_atomically(args.line_map, [&](std::ostream& out) { out << line_map.str(); });
  if (!args.quiet) {
    const auto& c = summary.corrector;
    report << "volcomp predistort: " << summary.lines << " lines, " << c.moves << " moves corrected into "
           << c.pieces << " pieces (" << c.corrections << " corrections, " << c.checks << " checks), max error at "
           << "the check points " << format_fixed(c.max_checked_error_mm * 1e3, 3) << " um (tolerance "
           << format_number(args.tolerance_mm * 1e3) << " um)";
    if (model.rotary_count() > 0)
      report << ", tool direction " << format_fixed(c.max_checked_error_rad * 1e6, 2) << " urad (tolerance "
             << format_number(args.tolerance_rad * 1e6) << " urad)";
    if (c.max_deflection_mm > 0) report << ", max deflection taken off " << format_fixed(c.max_deflection_mm * 1e3, 3) << " um";
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

}  // namespace vc::cli
