// volcomp simulate and volcomp measure: the virtual shop. A program runs on a "true"
// machine and leaves a tool path; a virtual CMM measures the surface that path machined.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

#include "vc/tables/atomic_file.hpp"
#include "commands.hpp"
#include "format.hpp"
#include "program_files.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/tool_lengths.hpp"
#include "vc/shop/cmm.hpp"
#include "vc/shop/machined_surface.hpp"
#include "vc/shop/table_set.hpp"
#include "vc/tables/load_table.hpp"
#include "vc/tables/source_error.hpp"
#include "vc/tables/symbols.hpp"

namespace vc::cli {

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
    shop::write_path_header(out, {"volcomp simulate: tool tip and axis in the part frame, error = tip - ideal tip",
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
  report << "volcomp simulate: " << samples << " samples (" << cutting << " cutting), largest tool-tip error while cutting "
         << format_fixed(largest * 1e3, 3) << " um\n";
  if (compensation) {  // it corrects: for which L, and from where (a second, interpreting-only pass)
    std::ifstream again(args.input, std::ios::binary);
    const predistort::ToolLengthLog lengths = predistort::read_tool_lengths(
        again, files.setup(args.input, machine, world == machine::WorldConvention::Tcp));
    report << "  compensation " << lengths.describe(*compensation, args.input, args.tool_table) << "\n";
  }
  return 0;
}

int run_measure(const MeasureArgs& args, std::ostream& report) {
  if (!(args.noise_um >= 0 && args.noise_um <= 100)) throw std::runtime_error("--noise must be in [0, 100] um");
  if (!(args.probe_radius_mm >= 0 && args.probe_radius_mm <= 5)) throw std::runtime_error("--probe-radius must be in [0, 5] mm");
  const shop::ToolPath path = shop::read_tool_path(args.path);
  for (const shop::PathSample& s : path)
    if (s.cutting && !(s.radius_mm > 0))
      throw std::runtime_error(args.path + ": tool T" + std::to_string(s.tool) +
                               " has no radius (give volcomp simulate a tool table with its D column)");
  shop::SurfaceOptions surface_options;
  surface_options.flute_length_mm = args.flute_length_mm;
  const shop::MachinedSurface surface(path, surface_options);
  const std::vector<shop::CmmPoint> plan = shop::read_cmm_points(args.plan, false);
  std::vector<shop::CmmPoint> measured;
  try {
    measured = shop::measure(surface, plan, {args.noise_um, args.probe_radius_mm, args.seed});
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(args.plan + ": " + e.what());
  }
  double largest = 0;
  for (const auto& p : measured) largest = std::max(largest, std::abs(*p.deviation_mm));
  tables::write_atomically(args.output, [&](std::ostream& out) {
    shop::write_cmm_report(out, measured,
                     {"volcomp measure: virtual CMM, deviation along the normal, + = material left",
                      "tool path " + args.path + ", plan " + args.plan,
                      "noise " + format_number(args.noise_um) + " um (seed " + std::to_string(args.seed) +
                          "), probe radius " + format_number(args.probe_radius_mm) + " mm"});
  });
  report << "volcomp measure: " << measured.size() << " points, largest deviation " << format_fixed(largest * 1e3, 3)
         << " um\n";
  return 0;
}

namespace {

// --location EX0C=15um ... and --add-table FILE ...: a true machine that differs from the file in
// these location errors only (by these amounts) and has these tables in addition to its own (each
// listed under the axis its error columns name, summed with that axis's tables), e.g. to prove an
// identification of them on it.
int perturb_named(const machine::Model& model, const PerturbArgs& args, std::ostream& report) {
  std::vector<shop::ExtraTable> extras;
  std::string changed;
  for (const std::string& file : args.add_tables) {
    tables::ErrorTable table = tables::load_table(file);
    const char letter = table.columns().front().symbol.axis;
    const int joint = model.joint_of(letter);
    if (joint < 0)
      throw std::runtime_error("--add-table " + file + ": its errors are of axis " + std::string(1, letter) + ", which " +
                               model.info.name + " does not have");
    const std::string name = std::filesystem::path(file).filename().string();
    for (const int t : model.axes[static_cast<std::size_t>(joint)].tables)
      if (std::filesystem::path(model.tables[static_cast<std::size_t>(t)].table.path()).filename() == name)
        throw std::runtime_error("--add-table " + file + ": axis " + std::string(1, letter) +
                                 " already lists a table of that name; rename it");
    extras.push_back({joint, name, std::move(table), {"added by volcomp perturb --add-table " + file}});
    changed += (changed.empty() ? "" : ", ") + std::string("table ") + name + " added under " + letter;
  }
  std::vector<shop::LocationValue> values;
  for (const std::string& spec : args.locations) {
    const std::size_t eq = spec.find('=');
    const auto symbol = tables::parse_error_symbol(spec.substr(0, eq));
    if (eq == std::string::npos || !symbol || !symbol->location || model.joint_of(symbol->axis) < 0)
      throw std::runtime_error("--location " + spec + ": a location error of " + model.info.name +
                               " and its change, e.g. EX0C=15um or EA0C=-3arcsec");
    std::size_t used = 0;
    const std::string amount = spec.substr(eq + 1);
    double v = 0;
    try {
      v = std::stod(amount, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    const std::string unit = amount.substr(used);
    const bool length = symbol->component < 3;
    const std::map<std::string, double> scale = length
        ? std::map<std::string, double>{{"um", 1e-3}, {"mm", 1.0}}
        : std::map<std::string, double>{{"arcsec", M_PI / 648000.0}, {"urad", 1e-6}};
    if (used == 0 || !scale.count(unit))
      throw std::runtime_error("--location " + spec + ": the change needs its unit (" +
                               (length ? "um or mm" : "arcsec or urad") + ")");
    const int joint = model.joint_of(symbol->axis);
    const machine::Axis& a = model.axes[static_cast<std::size_t>(joint)];
    const double before = length ? a.location_mm[symbol->component] : a.location_rad[symbol->component - 3];
    values.push_back({joint, symbol->component, before + v * scale.at(unit)});
    changed += (changed.empty() ? "" : ", ") + std::string("location ") + spec;
  }
  const std::string written = shop::write_machine_with_tables(
      model, args.folder, extras, "a true machine: " + changed + " (volcomp perturb)", values);
  machine::load_machine(written);  // it loads
  report << "volcomp perturb: " << written << " (" << values.size() << " location errors changed, " << extras.size()
         << " tables added, the file's tables kept)\n";
  return 0;
}

}  // namespace

int run_perturb(const PerturbArgs& args, std::ostream& report) {
  if (!(args.low >= 0 && args.low <= args.high && args.high <= 2))
    throw std::runtime_error("need 0 <= --low <= --high <= 2");
  const machine::Model model = machine::load_machine(args.machine);
  if (!args.locations.empty() || !args.add_tables.empty()) return perturb_named(model, args, report);
  const std::vector<shop::ExtraTable> extras = shop::perturbation_tables(model, args.low, args.high, args.seed);
  const std::vector<shop::LocationValue> locations = shop::perturbation_locations(model, args.low, args.high, args.seed);
  const std::string written = shop::write_machine_with_tables(
      model, args.folder, extras,
      "virtual shop: the true machine's tables and location errors are off by " + format_number(args.low * 100) + "-" +
          format_number(args.high * 100) + " % (volcomp perturb, seed " + std::to_string(args.seed) + ")",
      locations);
  report << "volcomp perturb: " << written << " (" << extras.size() << " perturbation tables, " << locations.size()
         << " location errors changed)\n";
  return 0;
}

}  // namespace vc::cli
