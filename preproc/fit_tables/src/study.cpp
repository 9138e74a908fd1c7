#include "vc/fit_tables/study.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "vc/fit_tables/usual_practice.hpp"

namespace vc::fit_tables {
namespace {

std::vector<double> default_check_lengths(std::vector<double> fitted) {
  std::sort(fitted.begin(), fitted.end());
  std::vector<double> out;
  for (std::size_t k = 1; k < fitted.size(); ++k) out.push_back(0.5 * (fitted[k - 1] + fitted[k]));
  out.push_back(fitted.back() + 50.0);
  return out;
}

std::vector<Pose> at_length(const std::vector<Pose>& poses, double length) {
  std::vector<Pose> out;
  for (const Pose& p : poses)
    if (p.tool_length_mm == length) out.push_back(p);
  return out;
}

ReportRow judge(const machine::Model& model, const machine::Model& truth, const Study& s,
                const std::vector<Pose>& poses) {
  ReportRow row;
  row.none = figures(uncompensated_errors(truth, poses));
  row.usual = figures(table_errors(truth, s.set, s.usual, poses));
  row.modified = figures(table_errors(truth, s.set, s.modified, poses));
  row.full = figures(full_correction_errors(model, truth, poses));
  return row;
}

}  // namespace

Study run_study(const machine::Model& model, const Controller& controller, const StudyOptions& o,
                const machine::Model* truth_or_null) {
  const machine::Model& truth = truth_or_null ? *truth_or_null : model;
  if (o.fresh_poses < 1) throw std::invalid_argument("--fresh must be at least 1");
  Study s;
  s.set = resolve_tables(controller, model, o.nodes);
  s.fitted_lengths_mm = o.tool_lengths_mm.empty() ? std::vector<double>{model.tool_length_mm} : o.tool_lengths_mm;
  for (double l : s.fitted_lengths_mm)
    if (!std::isfinite(l) || l < 0) throw std::invalid_argument("tool lengths must be numbers >= 0 mm");
  std::sort(s.fitted_lengths_mm.begin(), s.fitted_lengths_mm.end());
  s.fitted_lengths_mm.erase(std::unique(s.fitted_lengths_mm.begin(), s.fitted_lengths_mm.end()),
                            s.fitted_lengths_mm.end());
  s.check_lengths_mm = o.check_tool_lengths_mm.value_or(default_check_lengths(s.fitted_lengths_mm));
  for (double l : s.check_lengths_mm)
    if (!std::isfinite(l) || l < 0) throw std::invalid_argument("tool lengths must be numbers >= 0 mm");
  std::sort(s.check_lengths_mm.begin(), s.check_lengths_mm.end());
  s.check_lengths_mm.erase(std::remove_if(s.check_lengths_mm.begin(), s.check_lengths_mm.end(),
                                          [&](double l) {
                                            return std::find(s.fitted_lengths_mm.begin(), s.fitted_lengths_mm.end(),
                                                             l) != s.fitted_lengths_mm.end();
                                          }),
                           s.check_lengths_mm.end());
  s.check_lengths_mm.erase(std::unique(s.check_lengths_mm.begin(), s.check_lengths_mm.end()), s.check_lengths_mm.end());

  // The grid: by default as many positions per joint as the tables have nodes, on the nodes.
  int node_count = 2;
  bool modulo = false;
  for (const Table& t : s.set.tables) {
    node_count = std::max(node_count, static_cast<int>(t.nodes.size()));
    modulo = modulo || t.modulo;
  }
  s.levels = o.levels.value_or(node_count);
  GridSpec grid;
  grid.levels = s.levels;
  grid.rotary = o.rotary;
  grid.full_turn_once = modulo;
  grid.tool_lengths_mm = s.fitted_lengths_mm;
  const std::vector<Pose> grid_set = grid_poses(model, grid);
  s.grid_poses = static_cast<int>(grid_set.size());
  s.program_poses = static_cast<int>(o.program_poses.size());
  // What is fitted: the volume (the grid) with the part programs' poses, or (programs_only)
  // those alone, the grid then only judged.
  const bool for_programs = o.programs_only && !o.program_poses.empty();
  std::vector<Pose> fitted = for_programs ? std::vector<Pose>{} : grid_set;
  fitted.insert(fitted.end(), o.program_poses.begin(), o.program_poses.end());

  FreshPoses fresh(model);
  const std::vector<Pose> probe = fresh.next(o.fresh_poses, s.fitted_lengths_mm);
  std::vector<double> all_lengths = s.fitted_lengths_mm;
  all_lengths.insert(all_lengths.end(), s.check_lengths_mm.begin(), s.check_lengths_mm.end());
  const std::vector<Pose> check = fresh.next(o.fresh_poses, all_lengths);

  s.usual = rounded(s.set, usual_practice(model, s.set));

  // The fit, then (for the volume) once more with the probe poses worse than the grid's M added.
  LinearSystem system = linearise(model, s.set, fitted);
  s.fit = fit(system, s.set, o.fit, s.usual);
  if (!for_programs) {
    const Eigen::VectorXd x = rounded(s.set, s.fit.x);
    const double grid_max = figures(table_errors(model, s.set, x, fitted)).max_um;
    const std::vector<double> probe_errors = table_errors(model, s.set, x, probe);
    std::vector<std::size_t> order(probe.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return probe_errors[a] > probe_errors[b]; });
    std::vector<Pose> worst;
    for (std::size_t k : order) {
      if (probe_errors[k] <= grid_max || static_cast<int>(worst.size()) >= o.refit_max_poses) break;
      worst.push_back(probe[k]);
    }
    s.added_poses = static_cast<int>(worst.size());
    if (!worst.empty()) {
      system.append(linearise(model, s.set, worst));
      s.fit = fit(system, s.set, o.fit, s.usual);
    }
  }
  s.modified = rounded(s.set, s.fit.x);

  // The figures, per tool length: the grid (fitted at a fitted length) and the check set.
  GridSpec unfitted = grid;
  unfitted.tool_lengths_mm = s.check_lengths_mm;
  const std::vector<Pose> unfitted_grid =
      s.check_lengths_mm.empty() ? std::vector<Pose>{} : grid_poses(model, unfitted);
  for (double l : all_lengths) {
    const bool is_fitted =
        std::find(s.fitted_lengths_mm.begin(), s.fitted_lengths_mm.end(), l) != s.fitted_lengths_mm.end();
    for (const char* which : {"grid", "fresh"}) {
      const std::vector<Pose> poses =
          std::string(which) == "fresh" ? at_length(check, l) : at_length(is_fitted ? grid_set : unfitted_grid, l);
      ReportRow row = judge(model, truth, s, poses);
      row.tool_length_mm = l;
      row.fitted_length = is_fitted;
      row.set = which;
      s.rows.push_back(row);
    }
  }
  // The part programs' poses (all fitted), per tool length they use.
  std::vector<double> program_lengths;
  for (const Pose& p : o.program_poses) program_lengths.push_back(p.tool_length_mm);
  std::sort(program_lengths.begin(), program_lengths.end());
  program_lengths.erase(std::unique(program_lengths.begin(), program_lengths.end()), program_lengths.end());
  for (double l : program_lengths) {
    ReportRow row = judge(model, truth, s, at_length(o.program_poses, l));
    row.tool_length_mm = l;
    row.fitted_length = true;
    row.set = "programs";
    s.rows.push_back(row);
  }
  return s;
}

}  // namespace vc::fit_tables
