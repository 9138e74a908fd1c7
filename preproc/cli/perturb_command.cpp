// `volcomp perturb MACHINE -o FOLDER`: a "true" machine for the virtual shop, every table and
// location error off by a smooth amount, or only the named location errors and added tables.
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/shop/machine_file_writer.hpp"
#include "vc/tables/load_table.hpp"
#include "vc/tables/symbols.hpp"

namespace vc::cli {
namespace {

struct PerturbArgs {
  std::string machine;
  std::string folder;
  double low = 0.2, high = 0.5;
  unsigned seed = 1;
  std::vector<std::string> locations;   // "EX0C=15um": only these location errors, changed by these
  std::vector<std::string> add_tables;  // error tables the true machine has in addition (each under its columns' axis)
};

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
      throw std::runtime_error("--add-table " + file + ": its errors are of axis " + std::string(1, letter) +
                               ", which " + model.info.name + " does not have");
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
    const std::map<std::string, double> scale =
        length ? std::map<std::string, double>{{"um", 1e-3}, {"mm", 1.0}}
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

int run_perturb(const PerturbArgs& args, std::ostream& report) {
  if (!(args.low >= 0 && args.low <= args.high && args.high <= 2))
    throw std::runtime_error("need 0 <= --low <= --high <= 2");
  const machine::Model model = machine::load_machine(args.machine);
  if (!args.locations.empty() || !args.add_tables.empty()) return perturb_named(model, args, report);
  const std::vector<shop::ExtraTable> extras = shop::perturbation_tables(model, args.low, args.high, args.seed);
  const std::vector<shop::LocationValue> locations =
      shop::perturbation_locations(model, args.low, args.high, args.seed);
  const std::string written = shop::write_machine_with_tables(
      model, args.folder, extras,
      "virtual shop: the true machine's tables and location errors are off by " + number_text(args.low * 100) + "-" +
          number_text(args.high * 100) + " % (volcomp perturb, seed " + std::to_string(args.seed) + ")",
      locations);
  report << "volcomp perturb: " << written << " (" << extras.size() << " perturbation tables, " << locations.size()
         << " location errors changed)\n";
  return 0;
}

}  // namespace

void add_perturb_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<PerturbArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "perturb", "Write a \"true\" machine for the virtual shop: every table off by a smooth 20-50 %");
  cmd->add_option("MACHINE", args->machine, "machine file (.toml)")->required();
  cmd->add_option("-o,--output", args->folder, "folder for the true machine file and its extra tables")->required();
  cmd->add_option("--low", args->low, "smallest relative change")->capture_default_str();
  cmd->add_option("--high", args->high, "largest relative change")->capture_default_str();
  cmd->add_option("--seed", args->seed, "seed of the shapes")->capture_default_str();
  cmd->add_option("--location", args->locations,
                  "change only this location error by this much, tables kept, e.g. --location EX0C=15um "
                  "--location EA0C=-3arcsec (um, mm, arcsec, urad; repeatable)");
  cmd->add_option("--add-table", args->add_tables,
                  "an error table the true machine has in addition to the file's, listed under the axis its "
                  "columns name (repeatable; with or without --location)");
  cmd->callback([args, &exit_code] { exit_code = run_perturb(*args, std::cerr); });
}

}  // namespace vc::cli
