// `volcomp plot MACHINE -o FOLDER`: the machine file's errors as pictures (preproc/plot/README.md):
// per axis its component errors against its position (<letter>_axis.png or .svg, with the
// data drawn beside it as <letter>_axis.csv), and the location errors listed with their units
// (location_errors.csv, the non-zero ones printed).
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "atomic_output.hpp"
#include "commands.hpp"
#include "format.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/plot/machine_plot.hpp"

namespace vc::cli {

int run_plot(const PlotArgs& args, std::ostream& out) {
  namespace fs = std::filesystem;
  if (args.format != "png" && args.format != "svg") throw std::runtime_error("--format must be png or svg");
  const machine::Model model = machine::load_machine(args.machine);
  fs::create_directories(args.folder);
  out << "volcomp plot: " << model.info.name << " (" << args.machine << ") into " << args.folder << "\n";
  for (int joint = 0; joint < model.joint_count(); ++joint) {
    const machine::Axis& axis = model.axes[static_cast<std::size_t>(joint)];
    const std::string letter(1, static_cast<char>(std::tolower(static_cast<unsigned char>(axis.letter))));
    const std::string image = (fs::path(args.folder) / (letter + "_axis." + args.format)).string();
    const plot::AxisPlot p = plot::axis_plot(model, joint, image);
    if (p.drawn) {
      plot::draw(p.figure);
      out << "  axis " << axis.letter << ": " << image << " (its data: " << plot::data_path(image) << ")\n";
    } else {
      out << "  axis " << axis.letter << ": no table over its own position alone, nothing drawn\n";
    }
    for (const std::string& n : p.not_drawn) out << "    not drawn: " << n << "\n";
  }
  const std::string listing = (fs::path(args.folder) / "location_errors.csv").string();
  write_atomically(listing, [&](std::ostream& csv) { csv << plot::location_errors_csv(model); });
  out << "location errors: " << listing << " (every axis line and the spindle line; the non-zero ones:)\n";
  for (const plot::LocationRow& r : plot::location_errors(model))
    if (r.value != 0.0)
      out << "  " << r.symbol << " = " << format_fixed(r.value, 3) << " " << r.unit << "  (" << r.meaning << ")\n";
  return 0;
}

}  // namespace vc::cli
