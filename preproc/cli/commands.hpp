// The subcommands of `volcomp`, each registered by the file that runs it: its subcommand, its
// options and the callback that runs it. A callback leaves the command's exit code in `exit_code`
// and may throw vc::LoadError (bad input file) or std::exception; main() prints those.
#pragma once

namespace CLI {
class App;
}

namespace vc::cli {

void add_check_command(CLI::App& volcomp, int& exit_code);
void add_pose_commands(CLI::App& volcomp, int& exit_code);  // error, correct
void add_trace_command(CLI::App& volcomp, int& exit_code);
void add_predistort_command(CLI::App& volcomp, int& exit_code);
void add_simulate_command(CLI::App& volcomp, int& exit_code);
void add_measure_command(CLI::App& volcomp, int& exit_code);
void add_perturb_command(CLI::App& volcomp, int& exit_code);
void add_selftune_command(CLI::App& volcomp, int& exit_code);
void add_balance_command(CLI::App& volcomp, int& exit_code);
void add_plot_command(CLI::App& volcomp, int& exit_code);
void add_report_command(CLI::App& volcomp, int& exit_code);
void add_fit_tables_command(CLI::App& volcomp, int& exit_code);
void add_identify_commands(CLI::App& volcomp, int& exit_code);  // identify laser, circle, sphere
void add_probe_plan_command(CLI::App& volcomp, int& exit_code);
void add_init_command(CLI::App& volcomp, int& exit_code);
void add_acceptance_commands(CLI::App& volcomp, int& exit_code);  // acceptance plan, simulate, evaluate

}  // namespace vc::cli
