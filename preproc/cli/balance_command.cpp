// `volcomp balance MACHINE`: the accuracy balance (preproc/identify/include/vc/identify/balance.hpp):
// each deviation's effect at the tool tip over the travel, largest first, as a table, a CSV a
// spreadsheet opens, and a bar chart (gnuplot; with the same CSV beside it).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "vc/tables/atomic_file.hpp"
#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/identify/balance.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/plot/gnuplot.hpp"

namespace vc::cli {
namespace {

struct BalanceArgs {
  std::string machine;
  int levels = 5;                        // positions per joint over the travel
  std::optional<double> tool_length_mm;  // default: the machine file's tool_length_mm
  std::string output;                    // CSV (optional)
  std::string plot;                      // bar chart, .png or .svg (optional, gnuplot; its data: .csv beside it)
};

void write_csv(const identify::Balance& b, std::ostream& out) {
  out << "# volcomp balance: each deviation alone at the tool tip, " << b.poses
      << " poses over the travel, L = " << number_text(b.tool_length_mm) << " mm\n"
      << "# M = max |error|, delta = M - min |error| (seeds/000 Appendix 6), share = RMS^2 / sum of RMS^2\n"
      << "deviation,M[um],delta[um],RMS[um],share[%],direction_max[urad]\n";
  for (const identify::DeviationEffect& e : b.effects)
    out << e.symbol << ',' << fixed_text(e.max_um, 4) << ',' << fixed_text(e.delta_um, 4) << ','
        << fixed_text(e.rms_um, 4) << ',' << fixed_text(e.share * 100, 2) << ',' << fixed_text(e.max_urad, 3) << '\n';
}

// A bar chart of M and RMS per deviation, largest first (gnuplot, preproc/plot).
void draw_bar_chart(const identify::Balance& b, const std::string& machine_name, const std::string& image) {
  std::ostringstream data;
  write_csv(b, data);
  std::ostringstream gp;
  gp << "set datafile separator ','\n"
     << "set title "
     << plot::text_literal("Accuracy balance of " + machine_name + ": each deviation alone at the tool tip (" +
                           std::to_string(b.poses) + " poses, L = " + number_text(b.tool_length_mm) + " mm)")
     << "\nset style data histograms\nset style histogram clustered gap 1\n"
     << "set style fill solid 0.8 border -1\nset boxwidth 0.9\nset grid ytics\nset key top right\n"
     << "set ylabel 'tool-tip error (um)'\nset xtics rotate by -60 font 'sans,9'\n"
     // every ::1: the header line is not a bar (it would leave an empty slot at the left)
     << "plot DATA every ::1 using 2:xtic(1) title 'M = max |error|' lc rgb '#c0392b', "
     << "'' every ::1 using 4 title 'RMS' lc rgb '#2e86c1'\n";
  plot::draw({image, data.str(), gp.str(), 1400, 700});
}

int run_balance(const BalanceArgs& args, std::ostream& out) {
  const machine::Model model = machine::load_machine(args.machine);
  identify::BalanceOptions options;
  options.levels = args.levels;
  options.tool_length_mm = args.tool_length_mm;
  const identify::Balance b = identify::accuracy_balance(model, options);
  out << "accuracy balance of " << model.info.name << ": each deviation alone at the tool tip, " << b.poses
      << " poses over the travel (" << args.levels << " per joint), L = " << number_text(b.tool_length_mm) << " mm\n"
      << "all together: M " << fixed_text(b.total.max_um, 3) << " um, RMS " << fixed_text(b.total.rms_um, 3)
      << " um, direction up to " << fixed_text(b.total.max_urad, 1) << " urad\n"
      << "  deviation        M [um]   delta [um]    RMS [um]   share [%]   direction [urad]\n";
  for (const identify::DeviationEffect& e : b.effects) {
    std::string row = "  " + e.symbol;
    row.resize(14, ' ');
    auto column = [&](const std::string& text, std::size_t width) {
      row += std::string(width > text.size() ? width - text.size() : 1, ' ') + text;
    };
    column(fixed_text(e.max_um, 3), 12);
    column(fixed_text(e.delta_um, 3), 13);
    column(fixed_text(e.rms_um, 3), 12);
    column(fixed_text(e.share * 100, 1), 12);
    column(fixed_text(e.max_urad, 1), 19);
    out << row << '\n';
  }
  out << "(M = max |error| and delta = M - min |error|, the source's criteria; share = RMS^2 over the sum of all RMS^2:\n"
         " measure the top of the list first)\n";
  // The plot first: a failing gnuplot leaves no output at all.
  if (!args.plot.empty()) draw_bar_chart(b, model.info.name, args.plot);
  if (!args.output.empty()) tables::write_atomically(args.output, [&](std::ostream& csv) { write_csv(b, csv); });
  return 0;
}

}  // namespace

void add_balance_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<BalanceArgs>();
  CLI::App* cmd =
      volcomp.add_subcommand("balance",
                             "Accuracy balance: each deviation's effect at the tool tip over the travel, largest first "
                             "(what to measure first)");
  cmd->add_option("MACHINE", args->machine, "machine description file (.toml)")->required();
  cmd->add_option("--levels", args->levels, "positions per joint over its travel (2..21)")->capture_default_str();
  cmd->add_option("--tool-length", args->tool_length_mm, "tool length L, mm (default: the machine file's)");
  cmd->add_option("-o,--output", args->output, "CSV: deviation, M, delta, RMS (um), share (%), direction (urad)");
  cmd->add_option("--plot", args->plot,
                  "bar chart, .png or .svg (gnuplot); the data it draws goes to a .csv beside it");
  cmd->callback([args, &exit_code] { exit_code = run_balance(*args, std::cout); });
}

}  // namespace vc::cli
