// `volcomp plot MACHINE -o FOLDER`: the machine file's errors as pictures (preproc/plot/README.md):
// per axis its component errors against its position (<letter>_axis.png or .svg, with the
// data drawn beside it as <letter>_axis.csv), and the location errors listed with their units
// (location_errors.csv, the non-zero ones printed). With --volume also the volume map
// (volume_<L>_rotary0.png, volume_<L>_worst.png and their CSVs): the tool-tip error over the
// working volume per tool length, before correction and with a stock controller's tables.
#include <CLI/CLI.hpp>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "vc/tables/atomic_file.hpp"
#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/plot/machine_plot.hpp"
#include "vc/plot/volume_map.hpp"
#include "vc/plot/volume_map_plot.hpp"

namespace vc::cli {
namespace {

struct PlotArgs {
  std::string machine;
  std::string folder;                   // per axis <letter>_axis.png (or .svg) and .csv; location_errors.csv
  std::string format = "png";           // png or svg
  bool volume = false;                  // also the volume map: volume_L<mm>_rotary0 / _worst images and CSVs
  std::vector<double> tool_lengths_mm;  // of the volume map (default: the machine file's)
  std::string plane;                    // of the volume map: "xz", "yz" ... (default: the first two linear axes)
  std::string controller = "linuxcnc";  // whose tables the volume map judges; "none" for none
};

// The volume map's sheets drawn, and their largest errors printed.
void draw_volume_map(const plot::VolumeMap& map, const machine::Model& model, const PlotArgs& args, std::ostream& out) {
  namespace fs = std::filesystem;
  out << "volume map: " << map.poses << " poses (" << map.first_mm.size() << " x " << map.second_mm.size() << " x "
      << map.levels_mm.size() << " levels per sheet), " << fixed_text(map.seconds, 1) << " s; largest |e| in um:\n";
  for (std::size_t s = 0; s < map.sheets.size(); ++s) {
    const plot::MapSheet& sheet = map.sheets[s];
    // Another plane than the default gets its own names: volume_xz_L100_rotary0.png.
    std::string name = plot::volume_map_name(sheet);
    if (!args.plane.empty()) name.insert(std::string("volume_").size(), args.plane + "_");
    const std::string image = (fs::path(args.folder) / (name + "." + args.format)).string();
    plot::draw(plot::volume_map_plot(map, s, model, image));
    out << "  L " << number_text(sheet.tool_length_mm) << " mm, " << sheet.rotary.label << ":";
    for (std::size_t c = 0; c < map.compensations.size(); ++c)
      out << (c ? ", " : " ") << map.compensations[c] << " " << fixed_text(sheet.max_um[c], 1);
    out << "  (" << image << ")\n";
  }
  if (!map.controller_title.empty())
    out << "  (tables: " << map.controller_title << ", fitted over these tool lengths)\n";
  out << "  " << plot::full_correction_statement(map) << "\n";
}

int run_plot(const PlotArgs& args, std::ostream& out) {
  namespace fs = std::filesystem;
  if (args.format != "png" && args.format != "svg") throw std::runtime_error("--format must be png or svg");
  if ((!args.tool_lengths_mm.empty() || !args.plane.empty() || args.controller != "linuxcnc") && !args.volume)
    throw std::runtime_error("--tool-lengths, --plane and --controller are for the volume map: add --volume");
  const machine::Model model = machine::load_machine(args.machine);
  // The map before any picture: its bad input (a tool length, a machine without three linear
  // axes) leaves no file behind.
  std::optional<plot::VolumeMap> map;
  if (args.volume) {
    plot::VolumeMapOptions options;
    options.tool_lengths_mm = args.tool_lengths_mm;
    options.plane = args.plane;
    options.controller = args.controller == "none" ? "" : args.controller;
    map = plot::volume_map(model, options);
  }
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
  tables::write_atomically(listing, [&](std::ostream& csv) { csv << plot::location_errors_csv(model); });
  out << "location errors: " << listing << " (every axis line and the spindle line; the non-zero ones:)\n";
  for (const plot::LocationRow& r : plot::location_errors(model))
    if (r.value != 0.0)
      out << "  " << r.symbol << " = " << fixed_text(r.value, 3) << " " << r.unit << "  (" << r.meaning << ")\n";
  if (map) draw_volume_map(*map, model, args, out);
  return 0;
}

}  // namespace

void add_plot_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<PlotArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "plot",
      "Draw a machine file's errors: per axis its component errors against its position (PNG or SVG with "
      "the data as CSV), and the location errors listed with units");
  cmd->add_option("MACHINE", args->machine, "machine description file (.toml)")->required();
  cmd->add_option("-o,--output", args->folder, "folder for <axis>_axis.png and .csv and location_errors.csv")
      ->required();
  cmd->add_option("--format", args->format, "png or svg")->capture_default_str();
  cmd->add_flag("--volume", args->volume,
                "also the volume map: the tool-tip error |e| (um) over X-Y at three Z levels, rotary axes at 0 "
                "and at their worst, before correction and with LinuxCNC's tables (usual practice, modified method)");
  cmd->add_option("--tool-lengths", args->tool_lengths_mm,
                  "the volume map's tool lengths, mm, e.g. 0,100 "
                  "(default: the machine file's)")
      ->delimiter(',');
  cmd->add_option("--plane", args->plane,
                  "the volume map's plane, two linear axes, e.g. xz or yz, the third "
                  "giving the levels (default: the first two, X-Y)");
  cmd->add_option("--controller", args->controller,
                  "the stock controller whose tables the volume map judges "
                  "(as fit-tables --controller), or none")
      ->capture_default_str();
  cmd->callback([args, &exit_code] { exit_code = run_plot(*args, std::cout); });
}

}  // namespace vc::cli
