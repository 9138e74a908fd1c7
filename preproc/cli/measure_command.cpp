// `volcomp measure PATH PLAN -o REPORT`: the virtual shop's CMM. It measures the surface a tool
// path (volcomp simulate) machined, at the points of a plan.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/shop/cmm.hpp"
#include "vc/shop/machined_surface.hpp"
#include "vc/tables/atomic_file.hpp"

namespace vc::cli {
namespace {

struct MeasureArgs {
  std::string path;    // tool path CSV (volcomp simulate)
  std::string plan;    // CMM plan CSV
  std::string output;  // CMM report CSV
  double noise_um = 0.0;
  double probe_radius_mm = 0.0;
  double flute_length_mm = 30.0;
  unsigned seed = 1;
};

int run_measure(const MeasureArgs& args, std::ostream& report) {
  if (!(args.noise_um >= 0 && args.noise_um <= 100)) throw std::runtime_error("--noise must be in [0, 100] um");
  if (!(args.probe_radius_mm >= 0 && args.probe_radius_mm <= 5))
    throw std::runtime_error("--probe-radius must be in [0, 5] mm");
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
                            "noise " + number_text(args.noise_um) + " um (seed " + std::to_string(args.seed) +
                                "), probe radius " + number_text(args.probe_radius_mm) + " mm"});
  });
  report << "volcomp measure: " << measured.size() << " points, largest deviation " << fixed_text(largest * 1e3, 3)
         << " um\n";
  return 0;
}

}  // namespace

void add_measure_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<MeasureArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "measure", "Virtual CMM: measure the surface a tool path machined at the points of a plan");
  cmd->add_option("PATH", args->path, "tool path CSV (volcomp simulate)")->required();
  cmd->add_option("PLAN", args->plan, "CMM plan CSV: id,x[mm],y[mm],z[mm],i,j,k")->required();
  cmd->add_option("-o,--output", args->output, "CMM report CSV")->required();
  cmd->add_option("--noise", args->noise_um, "gaussian noise (standard deviation), um")->capture_default_str();
  cmd->add_option("--probe-radius", args->probe_radius_mm, "stylus ball radius, mm")->capture_default_str();
  cmd->add_option("--flute-length", args->flute_length_mm, "cutting length of the tools, mm")->capture_default_str();
  cmd->add_option("--seed", args->seed, "seed of the noise")->capture_default_str();
  cmd->callback([args, &exit_code] { exit_code = run_measure(*args, std::cerr); });
}

}  // namespace vc::cli
