// `volcomp balance MACHINE`: the accuracy balance (preproc/identify/include/vc/identify/balance.hpp):
// each deviation's effect at the tool tip over the travel, largest first, as a table, a CSV a
// spreadsheet opens, and a bar chart (gnuplot).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <unistd.h>
#include <fstream>
#include <stdexcept>

#include "atomic_output.hpp"
#include "commands.hpp"
#include "format.hpp"
#include "vc/identify/balance.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::cli {
namespace {

void write_csv(const identify::Balance& b, std::ostream& out) {
  out << "# volcomp balance: each deviation alone at the tool tip, " << b.poses << " poses over the travel, L = "
      << format_number(b.tool_length_mm) << " mm\n"
      << "# M = max |error|, delta = M - min |error| (seeds/000 Appendix 6), share = RMS^2 / sum of RMS^2\n"
      << "deviation,M[um],delta[um],RMS[um],share[%],direction_max[urad]\n";
  for (const identify::DeviationEffect& e : b.effects)
    out << e.symbol << ',' << format_fixed(e.max_um, 4) << ',' << format_fixed(e.delta_um, 4) << ','
        << format_fixed(e.rms_um, 4) << ',' << format_fixed(e.share * 100, 2) << ',' << format_fixed(e.max_urad, 3)
        << '\n';
}

// A bar chart of M and RMS per deviation, largest first, drawn by gnuplot into `png`.
void plot(const identify::Balance& b, const std::string& machine_name, const std::string& png) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("volcomp-balance-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string data = (dir / "balance.csv").string(), script = (dir / "balance.gp").string();
  const std::string temporary = png + ".part";
  {
    std::ofstream out(data);
    write_csv(b, out);
  }
  {
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 1400,700 font 'sans,11'\n"
       << "set output '" << temporary << "'\n"
       << "set title 'Accuracy balance of " << machine_name << ": each deviation alone at the tool tip (" << b.poses
       << " poses, L = " << format_number(b.tool_length_mm) << " mm)'\n"
       << "set datafile separator ','\nset style data histograms\nset style histogram clustered gap 1\n"
       << "set style fill solid 0.8 border -1\nset boxwidth 0.9\nset grid ytics\nset key top right\n"
       << "set ylabel 'tool-tip error (um)'\nset xtics rotate by -60 font 'sans,9'\n"
       << "plot '" << data << "' using 2:xtic(1) title 'M = max |error|' lc rgb '#c0392b', "
       << "'' using 4 title 'RMS' lc rgb '#2e86c1'\n";
  }
  const int status = std::system(("gnuplot '" + script + "' 2>&1").c_str());
  fs::remove_all(dir);
  if (status != 0) {
    std::remove(temporary.c_str());
    throw std::runtime_error("gnuplot failed (is it installed?): the plot " + png + " was not written");
  }
  fs::rename(temporary, png);
}

}  // namespace

int run_balance(const BalanceArgs& args, std::ostream& out) {
  const machine::Model model = machine::load_machine(args.machine);
  identify::BalanceOptions options;
  options.levels = args.levels;
  options.tool_length_mm = args.tool_length_mm;
  const identify::Balance b = identify::accuracy_balance(model, options);
  out << "accuracy balance of " << model.info.name << ": each deviation alone at the tool tip, " << b.poses
      << " poses over the travel (" << args.levels << " per joint), L = " << format_number(b.tool_length_mm) << " mm\n"
      << "all together: M " << format_fixed(b.total.max_um, 3) << " um, RMS " << format_fixed(b.total.rms_um, 3)
      << " um, direction up to " << format_fixed(b.total.max_urad, 1) << " urad\n"
      << "  deviation        M [um]   delta [um]    RMS [um]   share [%]   direction [urad]\n";
  for (const identify::DeviationEffect& e : b.effects) {
    std::string row = "  " + e.symbol;
    row.resize(14, ' ');
    auto column = [&](const std::string& text, std::size_t width) {
      row += std::string(width > text.size() ? width - text.size() : 1, ' ') + text;
    };
    column(format_fixed(e.max_um, 3), 12);
    column(format_fixed(e.delta_um, 3), 13);
    column(format_fixed(e.rms_um, 3), 12);
    column(format_fixed(e.share * 100, 1), 12);
    column(format_fixed(e.max_urad, 1), 19);
    out << row << '\n';
  }
  out << "(M = max |error| and delta = M - min |error|, the source's criteria; share = RMS^2 over the sum of all RMS^2:\n"
         " measure the top of the list first)\n";
  if (!args.output.empty()) write_atomically(args.output, [&](std::ostream& csv) { write_csv(b, csv); });
  if (!args.plot.empty()) plot(b, model.info.name, args.plot);
  return 0;
}

}  // namespace vc::cli
