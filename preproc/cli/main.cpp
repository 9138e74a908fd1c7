// volcomp: the command line of the volumetric compensation tools. Each command registers itself
// (commands.hpp), in the order `volcomp --help` lists them; here only the exit codes: CLI11's for
// a bad command line, the command's own, 2 for an exception (a bad input file, a failed write).
#include <CLI/CLI.hpp>
#include <iostream>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App volcomp{"volcomp: volumetric error compensation for CNC machines (machine file + error tables)"};
  volcomp.require_subcommand(1);
  int exit_code = 0;
  vc::cli::add_check_command(volcomp, exit_code);
  vc::cli::add_pose_commands(volcomp, exit_code);
  vc::cli::add_trace_command(volcomp, exit_code);
  vc::cli::add_predistort_command(volcomp, exit_code);
  vc::cli::add_simulate_command(volcomp, exit_code);
  vc::cli::add_measure_command(volcomp, exit_code);
  vc::cli::add_perturb_command(volcomp, exit_code);
  vc::cli::add_selftune_command(volcomp, exit_code);
  vc::cli::add_balance_command(volcomp, exit_code);
  vc::cli::add_plot_command(volcomp, exit_code);
  vc::cli::add_report_command(volcomp, exit_code);
  vc::cli::add_fit_tables_command(volcomp, exit_code);
  vc::cli::add_identify_commands(volcomp, exit_code);
  vc::cli::add_probe_plan_command(volcomp, exit_code);
  vc::cli::add_init_command(volcomp, exit_code);
  vc::cli::add_acceptance_commands(volcomp, exit_code);

  // The chosen command runs in its callback, after CLI11 has parsed and checked the whole line.
  try {
    CLI11_PARSE(volcomp, argc, argv);
  } catch (const std::exception& e) {
    std::cout.flush();
    std::cerr << e.what() << '\n';
    return 2;
  }
  return exit_code;
}
