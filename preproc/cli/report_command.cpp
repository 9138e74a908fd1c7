// `volcomp report MACHINE [--measurements DIR] [--acceptance LABEL=FILE.csv ...] -o report.html`:
// the machine's accuracy on one self-contained HTML page (preproc/report/README.md). Everything is computed and drawn first;
// the page is written last, atomically: on any error there is no file (and an older one stays).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "vc/tables/atomic_file.hpp"
#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/report/accuracy_report.hpp"

namespace vc::cli {
namespace {

struct ReportArgs {
  std::string machine;
  std::string measurements;             // folder of laser runs and circular tests (optional)
  std::string output;                   // the HTML page
  std::vector<double> tool_lengths_mm;  // of the volume map (default: 0 and the machine file's)
  std::vector<std::string> acceptance;  // LABEL=FILE.csv, `acceptance evaluate` results
};

int run_report(const ReportArgs& args, std::ostream& out) {
  namespace fs = std::filesystem;
  if (fs::is_directory(args.output))
    throw std::runtime_error("-o " + args.output + ": a folder; give the page's file name");
  const fs::path folder = fs::path(args.output).parent_path();
  if (!folder.empty() && !fs::is_directory(folder))
    throw std::runtime_error("-o " + args.output + ": its folder " + folder.string() + " does not exist");
  const machine::Model model = machine::load_machine(args.machine);
  report::ReportOptions options;
  options.measurements = args.measurements;
  options.tool_lengths_mm = args.tool_lengths_mm;
  for (const std::string& a : args.acceptance) options.acceptance.push_back(report::acceptance_input(a));
  std::ostringstream command;
  command << "volcomp report " << args.machine;
  if (!args.measurements.empty()) command << " --measurements " << args.measurements;
  if (!args.tool_lengths_mm.empty()) {
    command << " --tool-lengths ";
    for (std::size_t k = 0; k < args.tool_lengths_mm.size(); ++k)
      command << (k ? "," : "") << number_text(args.tool_lengths_mm[k]);
  }
  for (const std::string& a : args.acceptance) command << " --acceptance '" << a << "'";
  command << " -o " << args.output;
  options.command = command.str();
  out << "volcomp report: " << model.info.name << " (" << args.machine << ")\n";
  const report::Report r = report::accuracy_report(model, options, out);
  tables::write_atomically(args.output, [&](std::ostream& html) { html << r.html; });
  out << "report written: " << args.output << " (" << r.sections << " sections, " << r.figures << " figures, "
      << r.measurements << " measurements, ";
  if (r.acceptance) out << r.acceptance << " acceptance evaluations, ";
  out << r.html.size() / 1024 << " KiB)\n";
  return 0;
}

}  // namespace

void add_report_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "report",
      "One self-contained HTML page of the machine's accuracy: its file and checksums, tables, location "
      "errors, accuracy balance, volume map, the laser runs and circular tests of --measurements and the "
      "acceptance results of --acceptance");
  cmd->add_option("MACHINE", args->machine, "machine description file (.toml)")->required();
  cmd->add_option("--measurements", args->measurements,
                  "folder of laser runs (ISO 230-2) and circular tests (ISO 230-4), CSV (preproc/report/README.md)");
  cmd->add_option("-o,--output", args->output, "the HTML page to write")->required();
  cmd->add_option("--tool-lengths", args->tool_lengths_mm,
                  "the volume map's tool lengths, mm (default: 0 and "
                  "the machine file's)")
      ->delimiter(',');
  cmd->add_option("--acceptance", args->acceptance,
                  "LABEL=FILE.csv: `volcomp acceptance evaluate` results under a label, e.g. \"compensation on=on/"
                  "evaluation.csv\"; repeat it to compare (preproc/report/README.md)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->callback([args, &exit_code] { exit_code = run_report(*args, std::cout); });
}

}  // namespace vc::cli
