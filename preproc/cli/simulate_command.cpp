// `volcomp simulate MACHINE PROGRAM -o PATH`: the virtual shop's machine tool. The program runs on a
// "true" machine (with or without volkins correcting it) and leaves the tool path it cuts.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "program_files.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/tool_lengths.hpp"
#include "vc/shop/machined_surface.hpp"
#include "vc/tables/atomic_file.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::cli {
namespace {

struct SimulateArgs {
  std::string machine;  // the "true" machine
  std::string input;
  std::string output;  // tool path CSV
  std::string var_file, tool_table, process;
  std::string machine_units = "mm";
  std::string compensation;  // machine file volkins corrects with (none: uncompensated)
  std::string world = "axes";
  double step_mm = 0.5;
  std::vector<int> ball_end_tools;
};

int run_simulate(const SimulateArgs& args, std::ostream& report) {
  if (!(args.step_mm > 0 && args.step_mm <= 10)) throw std::runtime_error("--step must be in (0, 10] mm");
  const machine::WorldConvention world = world_convention(args.world);
  const machine::Model machine = machine::load_machine(args.machine);
  std::optional<machine::Model> compensation;
  if (!args.compensation.empty()) compensation = machine::load_machine(args.compensation);
  const ProgramFiles files(args.tool_table, args.var_file, args.machine_units);
  const std::optional<predistort::Deflection> deflection = files.deflection(args.process, machine);

  shop::SimulationOptions options;
  options.step_mm = args.step_mm;
  options.world = world;
  options.compensation = compensation ? &*compensation : nullptr;
  options.deflection = deflection ? &*deflection : nullptr;
  options.ball_end_tools.insert(args.ball_end_tools.begin(), args.ball_end_tools.end());

  std::ifstream in(args.input, std::ios::binary);
  if (!in) throw LoadError({args.input}, "cannot open the program");
  long samples = 0, cutting = 0;
  double largest = 0;
  tables::write_atomically(args.output, [&](std::ostream& out) {
    shop::write_path_header(
        out, {"volcomp simulate: tool tip and axis in the part frame, error = tip - ideal tip",
              "machine " + args.machine + ", program " + args.input,
              "compensation " + (args.compensation.empty() ? std::string("none") : args.compensation) +
                  ", cutting-force deflection " + (args.process.empty() ? std::string("none") : args.process)});
    shop::simulate(machine, in, files.setup(args.input, machine, world == machine::WorldConvention::Tcp), options,
                   [&](const shop::PathSample& s) {
                     shop::write_path_sample(out, s);
                     ++samples;
                     if (s.cutting) {
                       ++cutting;
                       largest = std::max(largest, s.error_mm.norm());
                     }
                   });
  });
  report << "volcomp simulate: " << samples << " samples (" << cutting
         << " cutting), largest tool-tip error while cutting " << fixed_text(largest * 1e3, 3) << " um\n";
  if (compensation) {  // it corrects: for which L, and from where (a second, interpreting-only pass)
    std::ifstream again(args.input, std::ios::binary);
    const predistort::ToolLengthLog lengths =
        predistort::read_tool_lengths(again, files.setup(args.input, machine, world == machine::WorldConvention::Tcp));
    report << "  compensation " << lengths.describe(*compensation, args.input, args.tool_table) << "\n";
  }
  return 0;
}

}  // namespace

void add_simulate_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "simulate", "Run a program on a (true) machine and write the actual tool path (part frame)");
  cmd->add_option("MACHINE", args->machine, "the true machine's description file (.toml)")->required();
  cmd->add_option("PROGRAM", args->input, "part program (RS274/NGC)")->required();
  cmd->add_option("-o,--output", args->output, "tool path CSV")->required();
  cmd->add_option("--var", args->var_file, "LinuxCNC parameter file (.var)");
  cmd->add_option("--tool-table", args->tool_table, "LinuxCNC tool table (.tbl): lengths and diameters");
  cmd->add_option("--machine-units", args->machine_units,
                  "the unit of the tool table and the .var file, LinuxCNC's [TRAJ]LINEAR_UNITS: mm or inch")
      ->capture_default_str();
  cmd->add_option("--process", args->process, "cutting conditions per tool (.toml): cutting-force deflection");
  cmd->add_option("--compensation", args->compensation,
                  "machine file the kinematics module corrects with (default: none, uncompensated)");
  cmd->add_option("--world", args->world, "world convention: axes or tcp")->capture_default_str();
  cmd->add_option("--step", args->step_mm, "largest distance between samples, mm")->capture_default_str();
  cmd->add_option("--ball-end", args->ball_end_tools, "tools with a ball end, e.g. --ball-end 2,5")->delimiter(',');
  cmd->callback([args, &exit_code] { exit_code = run_simulate(*args, std::cerr); });
}

}  // namespace vc::cli
