// `volcomp acceptance plan|simulate|evaluate`: the acceptance tests of a compensated machine
// (issue 47; preproc/acceptance/README.md): the ISO 230-6 diagonal displacement tests and the
// ISO 230-4 circular tests.
// Every input is read and checked before anything is written; each file is written atomically.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "vc/acceptance/circle_ballbar.hpp"
#include "vc/acceptance/circle_evaluation.hpp"
#include "vc/acceptance/circle_program.hpp"
#include "vc/acceptance/diagonal_evaluation.hpp"
#include "vc/acceptance/diagonal_laser.hpp"
#include "vc/acceptance/diagonal_measurements.hpp"
#include "vc/acceptance/diagonal_program.hpp"
#include "vc/acceptance/plan_file.hpp"
#include "vc/acceptance/rtest_evaluation.hpp"
#include "vc/acceptance/rtest_program.hpp"
#include "vc/acceptance/tolerances.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/atomic_file.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::cli {
namespace {

namespace fs = std::filesystem;
using Files = std::vector<std::pair<fs::path, std::string>>;  // path, contents

void write_all(const Files& files) {
  for (const auto& [path, text] : files) {
    if (!path.parent_path().empty()) fs::create_directories(path.parent_path());
    tables::write_atomically(path.string(), [&](std::ostream& out) { out << text; });
  }
}

struct PlanArgs {
  std::string machine, output, volume;
  std::optional<double> tool_length_mm;
  acceptance::DiagonalSettings settings;
  std::string axis_runs = "X,Y,Z", circles = "XY,YZ,ZX";
  double circle_radius_mm = 0;
  int rtest_steps = 7;
};

int run_plan(const PlanArgs& args, std::ostream& report) {
  const machine::Model model = machine::load_machine(args.machine);
  acceptance::Plan plan;
  plan.machine = args.machine;
  plan.coordinates = model.coordinates();
  plan.settings = args.settings;
  plan.settings.volume = args.volume.empty() ? acceptance::default_volume(model) : acceptance::parse_volume(model, args.volume);
  plan.settings.tool_length_mm = args.tool_length_mm.value_or(model.tool_length_mm);
  plan.tool_offset_mm = plan.settings.tool_length_mm - model.tool_length_reference_mm;
  plan.rest = acceptance::rest_joints(model, plan.settings.volume);
  plan.diagonals = acceptance::plan_diagonals(model, plan.settings);
  plan.axis_runs = acceptance::plan_axis_runs(model, plan.settings, args.axis_runs);
  plan.circles = acceptance::plan_circles(plan.settings.volume, args.circles, args.circle_radius_mm);
  plan.rtest = acceptance::plan_rtest(model, plan.settings.volume, plan.settings.tool_length_mm, args.rtest_steps);
  if (plan.diagonals.empty() && plan.axis_runs.empty() && plan.circles.empty() && plan.rtest.empty())
    throw std::runtime_error("--diagonals none --axis-runs none --circles none: no test");

  const fs::path dir(args.output);
  Files files{{dir / "plan.toml", acceptance::plan_toml(plan)}, {dir / "README.md", acceptance::plan_index(plan, model)}};
  for (const acceptance::Diagonal* d : acceptance::laser_lines(plan)) {
    files.push_back({dir / acceptance::program_path(*d), acceptance::diagonal_program(plan, *d, model)});
    files.push_back({dir / acceptance::sheet_path(*d), acceptance::diagonal_sheet(plan, *d, model)});
  }
  for (const acceptance::Circle& c : plan.circles) {
    files.push_back({dir / acceptance::program_path(c), acceptance::circle_program(plan, c, model)});
    files.push_back({dir / acceptance::sheet_path(c), acceptance::circle_sheet(plan, c, model)});
  }
  if (!plan.rtest.empty()) {
    files.push_back({dir / acceptance::kRTestProgram, acceptance::rtest_program(plan, model)});
    files.push_back({dir / acceptance::kRTestSheet, acceptance::rtest_sheet(plan, model)});
  }
  write_all(files);
  const auto bodies = std::count_if(plan.diagonals.begin(), plan.diagonals.end(),
                                    [](const acceptance::Diagonal& d) { return d.kind == "body"; });
  report << "volcomp acceptance plan: " << plan.diagonals.size() << " ISO 230-6 diagonals of " << model.info.name
         << " (" << bodies << " body, " << plan.diagonals.size() - static_cast<std::size_t>(bodies) << " face), "
         << plan.axis_runs.size() << " ISO 230-2 axis runs, " << plan.settings.targets << " targets and "
         << plan.settings.runs << " bidirectional runs each, " << plan.circles.size() << " ISO 230-4 circles and "
         << plan.rtest.sequences.size() << " R-test sequences, L " << number_text(plan.settings.tool_length_mm)
         << " mm, in " << args.output << " (plan.toml, README.md, diagonals/, axes/, circles/, rtest/)\n";
  return 0;
}

struct SimulateArgs {
  std::string plan_dir, truth, compensation = "off", output;
  double noise_um = 0, reversal_um = 0;
  std::uint64_t seed = 1;
};

int run_simulate(const SimulateArgs& args, std::ostream& report) {
  if (!(args.noise_um >= 0)) throw std::runtime_error("--noise-um must be >= 0");
  const acceptance::Plan plan = acceptance::read_plan(args.plan_dir);
  const machine::Model truth = machine::load_machine(args.truth);
  if (truth.coordinates() != plan.coordinates)
    throw std::runtime_error(args.truth + " has the joints " + truth.coordinates() + ", the plan's machine " +
                             plan.coordinates);
  std::optional<machine::Model> compensation;
  if (args.compensation != "off") {
    compensation = machine::load_machine(args.compensation);
    if (compensation->coordinates() != plan.coordinates)
      throw std::runtime_error(args.compensation + " has the joints " + compensation->coordinates() +
                               ", the plan's machine " + plan.coordinates);
  }
  acceptance::LaserSimulation sim;
  sim.truth = &truth;
  sim.compensation = compensation ? &*compensation : nullptr;
  sim.noise_mm = args.noise_um * 1e-3;
  sim.reversal_mm = args.reversal_um * 1e-3;
  sim.seed = args.seed;
  const std::vector<std::string> comments = {
      "instrument: simulated laser interferometer (volcomp acceptance simulate, seed " + std::to_string(args.seed) +
          ", noise " + number_text(args.noise_um) + " um, reversal " + number_text(args.reversal_um) + " um)",
      "truth: " + args.truth, "compensation: " + args.compensation,
      "tool_length_mm: " + number_text(plan.settings.tool_length_mm),
      "deviation: the displacement along the line minus the target (actual - nominal)"};
  Files files;
  double largest = 0;
  const std::vector<const acceptance::Diagonal*> lines = acceptance::laser_lines(plan);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const acceptance::Diagonal& d = *lines[k];
    const auto readings = acceptance::simulate_diagonal(plan, d, sim, static_cast<int>(k));
    for (const auto& r : readings) largest = std::max(largest, std::abs(r.deviation));
    files.push_back({fs::path(args.output) / acceptance::measurements_name(d), acceptance::laser_csv(d, readings, comments)});
  }
  const std::vector<std::string> ballbar_comments = {
      "instrument: simulated ballbar (volcomp acceptance simulate, seed " + std::to_string(args.seed) + ", noise " +
          number_text(args.noise_um) + " um, reversal spikes " + number_text(args.reversal_um) + " um)",
      "truth: " + args.truth, "compensation: " + args.compensation,
      "deviation: the ballbar's length minus its nominal length (+: longer)"};
  for (std::size_t k = 0; k < plan.circles.size(); ++k) {
    const acceptance::Circle& c = plan.circles[k];
    const identify::CircularTest test = acceptance::simulate_circle(plan, c, sim, static_cast<int>(k));
    for (const auto& run : test.runs)
      for (const auto& [angle, deviation] : run.points) largest = std::max(largest, std::abs(deviation));
    files.push_back({fs::path(args.output) / acceptance::measurements_name(c),
                     acceptance::ballbar_csv(plan, c, truth, test, ballbar_comments)});
  }
  if (!plan.rtest.empty())
    files.push_back({fs::path(args.output) / acceptance::kRTestMeasurements,
                     acceptance::simulate_rtest_csv(
                         plan, sim,
                         {"instrument: simulated R-test nest (volcomp acceptance simulate, seed " + std::to_string(args.seed) +
                              ", noise " + number_text(args.noise_um) + " um)",
                          "truth: " + args.truth, "compensation: " + args.compensation})});
  write_all(files);
  report << "volcomp acceptance simulate: " << plan.diagonals.size() << " diagonals, " << plan.axis_runs.size()
         << " axis runs, " << plan.circles.size() << " circles and " << (plan.rtest.empty() ? "no" : "the")
         << " R-test into " << args.output
         << ", compensation " << args.compensation << ", largest deviation " << fixed_text(largest * 1e3, 3)
         << " um\n";
  return 0;
}

struct EvaluateArgs {
  std::string plan_dir, measurements, tolerances, output;
  double laser_uncertainty_um = acceptance::kTypicalLaserUncertaintyUm;
  double ballbar_uncertainty_um = acceptance::kTypicalBallbarUncertaintyUm;
  double sensor_uncertainty_um = acceptance::kTypicalSensorUncertaintyUm;
  std::string machine;  // the R-test's nominal kinematics (default: the plan's machine file)
};

// A test's measurements file, which must exist.
fs::path measurements_file(const EvaluateArgs& args, const std::string& name, const std::string& test,
                           std::size_t tests) {
  const fs::path file = fs::path(args.measurements) / name;
  if (!fs::exists(file))
    throw std::runtime_error(file.string() + ": no measurements of " + test + " (the plan's " + std::to_string(tests) +
                             " tests each need their file)");
  return file;
}

int run_evaluate(const EvaluateArgs& args, std::ostream& out) {
  if (!(args.laser_uncertainty_um >= 0)) throw std::runtime_error("--laser-uncertainty-um must be >= 0");
  if (!(args.ballbar_uncertainty_um >= 0)) throw std::runtime_error("--ballbar-uncertainty-um must be >= 0");
  const acceptance::Plan plan = acceptance::read_plan(args.plan_dir);
  std::optional<acceptance::Tolerances> tolerances;
  if (!args.tolerances.empty()) tolerances = acceptance::read_tolerances(args.tolerances);
  const acceptance::Tolerances* limits = tolerances ? &*tolerances : nullptr;
  const double u_laser = args.laser_uncertainty_um * 1e-3, u_ballbar = args.ballbar_uncertainty_um * 1e-3;
  const std::vector<const acceptance::Diagonal*> laser_lines = acceptance::laser_lines(plan);
  const std::size_t tests = laser_lines.size() + plan.circles.size();
  std::vector<acceptance::DiagonalResult> lines;
  for (const acceptance::Diagonal* d : laser_lines) {
    const fs::path file = measurements_file(args, acceptance::measurements_name(*d), d->name, tests);
    lines.push_back(acceptance::evaluate_diagonal(*d, acceptance::read_diagonal_runs(file.string(), *d), u_laser, limits));
  }
  std::vector<acceptance::CircleResult> circles;
  for (const acceptance::Circle& c : plan.circles) {
    const fs::path file = measurements_file(args, acceptance::measurements_name(c), c.name, tests);
    circles.push_back(acceptance::evaluate_circle(c, acceptance::read_circle_run(file.string(), c), u_ballbar, limits));
  }
  const std::string prefix = args.output.empty() ? (fs::path(args.plan_dir) / "evaluation").string() : args.output;
  std::string summary;
  if (!lines.empty())
    summary = acceptance::summary_markdown(lines, args.plan_dir, args.measurements, args.tolerances, u_laser);
  std::vector<acceptance::RTestResult> rtest;
  if (!plan.rtest.empty()) {
    if (!(args.sensor_uncertainty_um >= 0)) throw std::runtime_error("--sensor-uncertainty-um must be >= 0");
    const machine::Model model = machine::load_machine(args.machine.empty() ? plan.machine : args.machine);
    if (model.coordinates() != plan.coordinates)
      throw std::runtime_error(model.path + " has the joints " + model.coordinates() + ", the plan's machine " +
                               plan.coordinates);
    const fs::path file = measurements_file(args, acceptance::kRTestMeasurements, "the R-test", tests);
    rtest = acceptance::evaluate_rtest(plan, model, acceptance::read_planned_rtest(file.string(), plan, model),
                                       args.sensor_uncertainty_um * 1e-3, limits);
  }
  if (!circles.empty()) summary += (summary.empty() ? "" : "\n") + acceptance::circles_markdown(circles, u_ballbar);
  if (!rtest.empty())
    summary += (summary.empty() ? "" : "\n") + acceptance::rtest_markdown(rtest, args.sensor_uncertainty_um * 1e-3);
  std::vector<acceptance::EvaluationRow> rows = acceptance::evaluation_rows(lines);
  for (acceptance::EvaluationRow& r : acceptance::evaluation_rows(circles)) rows.push_back(r);
  for (acceptance::EvaluationRow& r : acceptance::evaluation_rows(rtest)) rows.push_back(r);
  const std::string csv = acceptance::evaluation_csv(
      "ISO 230-6 diagonals and ISO 230-2 axis runs (the ISO 230-2 figures along each line), ISO 230-4 circles, "
      "the ISO 10791-6 R-test",
      {"u_repeatability: from the runs; u_instrument: the laser, " + number_text(args.laser_uncertainty_um) +
       " um per reading, the ballbar, " + number_text(args.ballbar_uncertainty_um) + " um, the R-test's sensors, " +
       number_text(args.sensor_uncertainty_um) + " um"},
      rows);
  write_all({{prefix + ".csv", csv}, {prefix + ".md", summary}});
  out << summary << "\nWritten: " << prefix << ".csv, " << prefix << ".md\n";
  for (const auto& r : lines)
    if (r.judged && !r.passes()) return 1;
  for (const auto& r : circles)
    if (r.judged && !r.passes()) return 1;
  for (const auto& r : rtest)
    if (r.judged && !r.passes()) return 1;
  return 0;
}

}  // namespace

void add_acceptance_commands(CLI::App& volcomp, int& exit_code) {
  CLI::App* acceptance = volcomp.add_subcommand(
      "acceptance", "Acceptance tests of the compensated machine: plan, simulate, evaluate (ISO 230-6 diagonals, ISO 230-4 circles)");
  acceptance->require_subcommand(1);

  auto plan = std::make_shared<PlanArgs>();
  CLI::App* p = acceptance->add_subcommand("plan", "Programs, setup sheets and plan.toml of the diagonal and circular tests");
  p->add_option("MACHINE", plan->machine, "machine file (.toml) with linear X, Y, Z axes")->required();
  p->add_option("-o,--output", plan->output, "folder for the plan")->required();
  p->add_option("--volume", plan->volume, "work volume x0:x1,y0:y1,z0:z1 in mm (default: the travel less 10 % each side)");
  p->add_option("--tool-length", plan->tool_length_mm, "L of the tool-side optic below the gauge point, mm (default: the machine file's)");
  p->add_option("--feed", plan->settings.feed_mm_per_min, "mm/min")->capture_default_str();
  p->add_option("--dwell", plan->settings.dwell_s, "s at each target")->capture_default_str();
  p->add_option("--overrun", plan->settings.overrun_mm, "mm before each reversal")->capture_default_str();
  p->add_option("--runs", plan->settings.runs, "bidirectional runs")->capture_default_str();
  p->add_option("--targets", plan->settings.targets, "targets per diagonal, ends included")->capture_default_str();
  p->add_option("--seed", plan->settings.seed, "of the targets' pseudo-random offsets")->capture_default_str();
  p->add_option("--diagonals", plan->settings.which,
                "all, body (the four body diagonals), face (the six face ones) or none")
      ->capture_default_str();
  p->add_option("--axis-runs", plan->axis_runs, "the ISO 230-2 runs along the linear axes (X, Y, Z; commas) or none")
      ->capture_default_str();
  p->add_option("--circles", plan->circles, "the ISO 230-4 circles' planes (XY, YZ, ZX; commas) or none")
      ->capture_default_str();
  p->add_option("--rtest-steps", plan->rtest_steps,
                "poses per R-test sequence on a machine with two rotary axes (0: no R-test)")
      ->capture_default_str();
  p->add_option("--circle-radius", plan->circle_radius_mm,
                "the ballbar's length, mm (default: the longest of 50, 100, 150, 300 that fits in the volume)");
  p->callback([plan, &exit_code] { exit_code = run_plan(*plan, std::cout); });

  auto sim = std::make_shared<SimulateArgs>();
  CLI::App* s = acceptance->add_subcommand("simulate", "A simulated laser along each planned diagonal and ballbar on each circle, on a true machine");
  s->add_option("DIR", sim->plan_dir, "the plan's folder")->required();
  s->add_option("--true", sim->truth, "the true machine's file (.toml): its real errors")->required();
  s->add_option("--compensation", sim->compensation, "machine file volkins corrects with, or off")->capture_default_str();
  s->add_option("--noise-um", sim->noise_um, "standard deviation of a reading's noise, um")->capture_default_str();
  s->add_option("--reversal-um", sim->reversal_um, "a reversal the runs show: + reads half of it, - minus half, um")
      ->capture_default_str();
  s->add_option("--seed", sim->seed, "of the noise")->capture_default_str();
  s->add_option("-o,--output", sim->output, "folder for the measurements (one CSV per diagonal)")->required();
  s->callback([sim, &exit_code] { exit_code = run_simulate(*sim, std::cout); });

  auto ev = std::make_shared<EvaluateArgs>();
  CLI::App* e = acceptance->add_subcommand("evaluate", "ISO 230-2 figures along each diagonal, ISO 230-4 of each circle, judged, with uncertainty");
  e->add_option("DIR", ev->plan_dir, "the plan's folder")->required();
  e->add_option("--measurements", ev->measurements, "folder of the laser runs, one CSV per diagonal")->required();
  e->add_option("--tolerances", ev->tolerances, "limits (.toml, um): without them figures only, no verdict");
  e->add_option("--laser-uncertainty-um", ev->laser_uncertainty_um, "the laser's standard uncertainty of a reading, um")
      ->capture_default_str();
  e->add_option("--sensor-uncertainty-um", ev->sensor_uncertainty_um,
                "the R-test sensors' standard uncertainty of a reading, um")
      ->capture_default_str();
  e->add_option("--machine", ev->machine, "the machine file whose nominal kinematics the R-test takes (default: the plan's)");
  e->add_option("--ballbar-uncertainty-um", ev->ballbar_uncertainty_um,
                "the ballbar's standard uncertainty of a reading, um")
      ->capture_default_str();
  e->add_option("-o,--output", ev->output, "PREFIX: writes PREFIX.csv and PREFIX.md (default DIR/evaluation)");
  e->callback([ev, &exit_code] { exit_code = run_evaluate(*ev, std::cout); });
}

}  // namespace vc::cli
