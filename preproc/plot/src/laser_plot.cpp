#include "vc/plot/laser_plot.hpp"

#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "plot_format.hpp"

namespace vc::plot {

Figure laser_plot(const identify::LaserRuns& runs, const std::set<identify::RunKey>& left_out,
                  const identify::Iso230_2& e, const LaserPlotText& text, const std::string& image) {
  const bool length = runs.quantity == tables::Quantity::Length;
  const double unit = length ? 1e3 : 1e6;  // mm -> um, rad -> urad
  const std::string u = length ? "um" : "urad", p = runs.rotary ? "deg" : "mm";

  // The runs kept, up first, each by run number: its reading at every target.
  std::map<identify::RunKey, std::map<double, double>> kept;
  for (const identify::Reading& r : runs.readings)
    if (!left_out.count({r.run, r.direction})) kept[{r.run, r.direction}][r.target] = r.deviation;
  std::vector<identify::RunKey> up, down;
  for (const auto& [key, readings] : kept) (key.second == identify::Direction::Up ? up : down).push_back(key);

  std::ostringstream csv;
  csv << "# volcomp identify laser --plot: the ISO 230-2 graph " << image << " draws these numbers\n"
      << "# runs: " << runs.path << "; deviation = actual - target, " << u << "; target position in " << p << "\n"
      << "# s: the unidirectional standard uncertainty at the target (ISO 230-2), so mean_up+2s = mean_up + 2 s_up\n";
  for (const auto& [symbol, value] : text.figures) csv << "# " << symbol << " = " << value << "\n";
  csv << "target[" << p << "]";
  for (const auto& [run, direction] : up) csv << ",run" << run << "_up[" << u << "]";
  for (const auto& [run, direction] : down) csv << ",run" << run << "_down[" << u << "]";
  for (const char* column :
       {"mean_up", "mean_down", "mean_bidirectional", "mean_up+2s", "mean_up-2s", "mean_down+2s", "mean_down-2s"})
    csv << "," << column << "[" << u << "]";
  csv << "\n";
  for (const identify::TargetStatistics& t : e.targets) {
    csv << number(t.target);
    for (const auto* keys : {&up, &down})
      for (const identify::RunKey& key : *keys) {
        // The evaluation refused runs that miss a target: every kept run has one reading here.
        const auto& readings = kept.at(key);
        const auto at = readings.find(t.target);
        if (at == readings.end()) throw std::logic_error("laser_plot: a kept run misses a target");
        csv << "," << number(at->second * unit);
      }
    for (const double v : {t.mean_up, t.mean_down, t.mean, t.mean_up + 2 * t.s_up, t.mean_up - 2 * t.s_up,
                           t.mean_down + 2 * t.s_down, t.mean_down - 2 * t.s_down})
      csv << "," << number(v * unit);
    csv << "\n";
  }

  // Columns (1-based): target, the up runs, the down runs, then the seven statistics.
  const std::size_t first_statistic = 2 + up.size() + down.size();
  const auto column = [&](std::size_t offset) { return std::to_string(first_statistic + offset); };
  // The side column: the figures, then the notes (metadata, runs left out) wrapped to its width.
  std::string figures =
      "ISO 230-2 (" + std::to_string(e.runs_up) + " runs up, " + std::to_string(e.runs_down) + " down)";
  for (const auto& [symbol, value] : text.figures)  // an angle's figure is long: wrapped, indented
    for (const std::string& line : wrapped(symbol + " = " + value, 46, 4)) figures += "\n" + line;
  if (!text.notes.empty()) figures += "\n";
  for (const std::string& note : text.notes)
    for (const std::string& line : wrapped(note, 46)) figures += "\n" + line;
  const double first = e.targets.front().target, last = e.targets.back().target;
  const double pad = (last - first) * 0.02;

  std::ostringstream gp;
  gp << "set datafile separator ','\n"
     << "set title " << text_literal(text.title + "\n" + runs.path) << " font 'sans,12'\n"
     << "set xlabel " << text_literal("target position P_i (" + p + ")") << "\n"
     << "set ylabel " << text_literal("deviation x_ij = actual - target (" + u + ")") << "\n"
     << "set grid xtics ytics mxtics mytics lw 1 lc rgb '#d0d0d0', lw 0.5 lc rgb '#ececec'\n"
     << "set mxtics 2\nset mytics 2\nset xzeroaxis lt -1 lw 1\n"
     << "set lmargin at screen 0.07\nset rmargin at screen 0.70\nset tmargin at screen 0.86\nset bmargin at screen 0.09\n"
     << "set key at screen 0.72, screen 0.86 left top Left reverse samplen 3 spacing 1.15 box lc rgb '#bbbbbb'\n"
     << "set label 1 " << text_literal(figures) << " at screen 0.725, screen 0.58 left front font 'sans,10.5'\n"
     << "set xrange [" << number(first - pad) << ":" << number(last + pad) << "]\n"
     << "set autoscale yfix\nset offsets 0, 0, graph 0.06, graph 0.06\n"
     << "set style fill transparent solid 0.14 noborder\n"
     << "plot DATA using 1:" << column(3) << ":" << column(4)
     << " with filledcurves lc rgb '#1f5fbf' title 'mean up ± 2s (band)', \\\n"
     << "     DATA using 1:" << column(5) << ":" << column(6)
     << " with filledcurves lc rgb '#c0392b' title 'mean down ± 2s (band)'";
  for (std::size_t k = 0; k < up.size(); ++k)
    gp << ", \\\n     DATA using 1:" << 2 + k << " with linespoints lw 1 pt 8 ps 0.9 lc rgb '#6f9fdf' "
       << (k == 0 ? "title " + text_literal("runs up (↑), " + std::to_string(up.size())) : std::string("notitle"));
  for (std::size_t k = 0; k < down.size(); ++k)
    gp << ", \\\n     DATA using 1:" << 2 + up.size() + k
       << " with linespoints lw 1 dt 2 pt 10 ps 0.9 lc rgb '#e58a7f' "
       << (k == 0 ? "title " + text_literal("runs down (↓), " + std::to_string(down.size())) : std::string("notitle"));
  for (const auto& [offset, colour] : {std::pair{3, "#1f5fbf"}, {4, "#1f5fbf"}, {5, "#c0392b"}, {6, "#c0392b"}})
    gp << ", \\\n     DATA using 1:" << column(static_cast<std::size_t>(offset)) << " with lines lw 1 dt 3 lc rgb '"
       << colour << "' notitle";
  gp << ", \\\n     DATA using 1:" << column(0) << " with lines lw 2.5 lc rgb '#1f5fbf' title 'mean up'"
     << ", \\\n     DATA using 1:" << column(1) << " with lines lw 2.5 dt 2 lc rgb '#c0392b' title 'mean down'"
     << ", \\\n     DATA using 1:" << column(2)
     << " with linespoints lw 3 pt 7 ps 0.7 lc rgb 'black' title 'mean bidirectional'\n";
  return {image, csv.str(), gp.str(), 1400, 820};
}

}  // namespace vc::plot
