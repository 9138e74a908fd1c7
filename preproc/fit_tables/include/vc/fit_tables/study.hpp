// The whole modified method for one machine and one controller: resolve the controller's
// tables, fill them the usual way and by the fit, refit once on the worst fresh poses, and
// judge four compensations on the nonlinear model, per tool length, on the fitted grid and on
// fresh poses:
//   (1) none, (2) the usual practice, (3) the modified method (the fit), (4) the full
//   correction (volkins: vc::machine::correct), the bound no table set beats.
//
// Three pose sets: the grid (fitted); a probe set of fresh poses whose worst ones (those above
// the grid's M) are added to the fit once (minimax on a fixed set underestimates M elsewhere);
// a check set of other fresh poses, never fitted, for the out-of-sample figures.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "vc/fit_tables/evaluate.hpp"
#include "vc/fit_tables/fit.hpp"

namespace vc::fit_tables {

struct StudyOptions {
  std::optional<int> nodes;                    // per table; default: the controller's
  std::optional<int> levels;                   // grid positions per joint; default: the tables' node count
  std::map<char, std::vector<double>> rotary;  // rotary grid positions (deg), replacing the default
  std::vector<double> tool_lengths_mm;         // fitted; default: the machine file's tool_length_mm
  // Judged but not fitted; default: the midpoints of the fitted ones and their largest + 50 mm.
  std::optional<std::vector<double>> check_tool_lengths_mm;
  // Poses of the user's part programs (nominal joints, the L of the tool each move uses):
  // fitted with the grid, or with programs_only alone (the grid and the fresh poses then only
  // judged: on the MC-300 at L = 100 mm the sample part's M falls from 29 to 13 um, and the
  // volume's rises from 38 to 300 um: such tables are for that part only); judged as the set
  // "programs" per tool length.
  std::vector<Pose> program_poses;
  bool programs_only = false;
  int fresh_poses = 2000;     // per tool length, in each of the probe and check sets
  int refit_max_poses = 200;  // worst probe poses added to the fit, at most
  FitOptions fit;
};

struct ReportRow {
  double tool_length_mm = 0.0;
  bool fitted_length = false;  // a tool length the tables were fitted at
  std::string set;             // "grid", "fresh" or "programs"
  Figures none, usual, modified, full;
};

struct Study {
  TableSet set;
  Eigen::VectorXd usual;     // the usual practice's values, rounded to the controller's resolution
  Eigen::VectorXd modified;  // the fit's values, rounded likewise
  FitResult fit;             // the final fit (after the refit)
  int levels = 0;
  int grid_poses = 0;     // all tool lengths
  int program_poses = 0;  // of the part programs, fitted (with the grid unless programs_only)
  int added_poses = 0;    // probe poses added by the refit
  std::vector<double> fitted_lengths_mm, check_lengths_mm;
  std::vector<ReportRow> rows;  // per tool length (fitted ones first, ascending), grid then fresh
};

// `truth` (optional): judge on this machine instead of `model` (tables and full correction are
// still made from `model`). Throws std::invalid_argument for bad options.
Study run_study(const machine::Model& model, const Controller& controller, const StudyOptions& options,
                const machine::Model* truth = nullptr);

}  // namespace vc::fit_tables
