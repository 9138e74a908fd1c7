// `volcomp probe-plan MACHINE --centre X,Y,Z --grid B=... --grid C=...`: the LinuxCNC program that
// probes a sphere at every combination of the rotary positions, for `volcomp identify sphere`.
#include <CLI/CLI.hpp>
#include <cctype>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "vc/identify/probe_plan.hpp"
#include "vc/identify/rotary_grid.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/atomic_file.hpp"

namespace vc::cli {
namespace {

struct ProbePlanArgs {
  std::string machine;
  std::vector<double> centre;  // X,Y,Z of the sphere's centre at rotary 0 (joints, mm)
  double sphere_diameter_mm = 25.0;
  double ball_diameter_mm = 2.0;
  std::optional<double> probe_length_mm;  // default: the machine file's tool length
  std::vector<std::string> grid;          // "B=0,-30,-60" "C=0,90,180,270"
  std::string log_file = "volcomp_sphere_probe.txt";
  double clearance_mm = 3.0;         // the search starts this far off the surface
  double probe_feed_mm_min = 100.0;  // the search
  double back_off_mm = 0.3;
  double touch_feed_mm_min = 10.0;  // the measuring touch
  std::string output;               // the program (default: stdout)
};

int run_probe_plan(const ProbePlanArgs& args, std::ostream& out) {
  const machine::Model model = machine::load_machine(args.machine);
  identify::ProbePlanOptions o;
  if (args.centre.size() != 3)
    throw std::runtime_error("--centre X,Y,Z: the sphere's centre at rotary 0 (the DRO, mm)");
  o.centre_mm = Eigen::Vector3d(args.centre[0], args.centre[1], args.centre[2]);
  o.sphere_diameter_mm = args.sphere_diameter_mm;
  o.ball_diameter_mm = args.ball_diameter_mm;
  o.probe_length_mm = args.probe_length_mm.value_or(0.0);
  o.log_file = args.log_file;
  o.clearance_mm = args.clearance_mm;
  o.probe_feed_mm_min = args.probe_feed_mm_min;
  o.back_off_mm = args.back_off_mm;
  o.touch_feed_mm_min = args.touch_feed_mm_min;
  if (!(o.sphere_diameter_mm > 0) || !(o.ball_diameter_mm >= 0))
    throw std::runtime_error("the diameters must be positive");
  // --grid B=0,-30,-60 --grid C=0,90,180,270: every combination, in joint order.
  std::vector<std::vector<double>> axes;
  for (int j = 0; j < model.joint_count(); ++j) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
    if (a.type != machine::AxisType::Rotary) continue;
    std::vector<double> values;
    for (const std::string& g : args.grid)
      if (g.size() > 2 && std::toupper(static_cast<unsigned char>(g[0])) == a.letter && g[1] == '=') {
        std::stringstream list(g.substr(2));
        for (std::string v; std::getline(list, v, ',');) values.push_back(std::stod(v));
      }
    if (values.empty())
      throw std::runtime_error("--grid " + std::string(1, a.letter) + "=...: the positions of " + a.letter);
    axes.push_back(values);
  }
  o.rotary_positions = identify::rotary_grid(axes);
  const std::string program = identify::probe_plan(model, o);
  if (args.output.empty() || args.output == "-") {
    out << program;
  } else {
    tables::write_atomically(args.output, [&](std::ostream& file) { file << program; });
    std::cerr << "volcomp probe-plan: " << args.output << ", " << o.rotary_positions.size()
              << " poses, 5 points each\n";
  }
  return 0;
}

}  // namespace

void add_probe_plan_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<ProbePlanArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "probe-plan", "A LinuxCNC program that probes a sphere at rotary positions for 'identify sphere' (G38.2, LOG)");
  cmd->add_option("MACHINE", args->machine, "machine description file (.toml)")->required();
  cmd->add_option("--centre", args->centre, "X,Y,Z: the sphere's centre at rotary 0, as the DRO shows it (mm)")
      ->delimiter(',')
      ->required();
  cmd->add_option("--sphere-diameter", args->sphere_diameter_mm, "mm")->capture_default_str();
  cmd->add_option("--ball-diameter", args->ball_diameter_mm, "the stylus ball, mm")->capture_default_str();
  cmd->add_option("--probe-length", args->probe_length_mm,
                  "gauge point to ball centre, mm (default: the machine file's)");
  cmd->add_option("--grid", args->grid, "rotary positions, e.g. --grid B=0,-30,-60,-90 --grid C=0,90,180,270")
      ->required();
  cmd->add_option("--clearance", args->clearance_mm, "the search starts this far off the surface, mm")
      ->capture_default_str();
  cmd->add_option("--probe-feed", args->probe_feed_mm_min, "the search for the surface, mm/min")->capture_default_str();
  cmd->add_option("--back-off", args->back_off_mm, "back-off after the search, mm")->capture_default_str();
  cmd->add_option(
         "--touch-feed", args->touch_feed_mm_min,
         "the measuring touch, mm/min (its trip is logged: LinuxCNC latches it up to feed x servo period late)")
      ->capture_default_str();
  cmd->add_option("--log", args->log_file, "the log file LinuxCNC writes (LOGOPEN)")->capture_default_str();
  cmd->add_option("-o,--output", args->output, "the program (default: stdout)");
  cmd->callback([args, &exit_code] { exit_code = run_probe_plan(*args, std::cout); });
}

}  // namespace vc::cli
