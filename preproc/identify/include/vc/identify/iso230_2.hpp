// ISO 230-2 evaluation of laser runs (seed 000, section 3.1, ISO 230-2;
// GOST 27843 is the same standard): for each target P_i and direction (up, down), with the
// positional deviations x_ij = actual - target of runs j = 1..n:
//   mean unidirectional deviation      x_i_up = mean_j x_ij_up            (x_i_down likewise)
//   reversal value                     B_i = x_i_up - x_i_down
//   unidirectional standard uncertainty s_i_up = sqrt(sum_j (x_ij_up - x_i_up)^2 / (n - 1))
//   unidirectional repeatability       R_i_up = 4 s_i_up
//   bidirectional repeatability        R_i = max(2 s_i_up + 2 s_i_down + |B_i|, R_i_up, R_i_down)
//   mean bidirectional deviation       x_i = (x_i_up + x_i_down) / 2
// and for the axis: B = max |B_i|, mean reversal = mean B_i, R = max R_i (R_up, R_down),
// systematic deviation E = max(x_i_up, x_i_down) - min(x_i_up, x_i_down) (E_up, E_down),
// range of the mean bidirectional deviation M = max x_i - min x_i, accuracy
// A = max(x_i_up + 2 s_i_up, x_i_down + 2 s_i_down) - min(x_i_up - 2 s_i_up, x_i_down - 2 s_i_down)
// (A_up, A_down). Values in core units (mm or rad).
//
// Runs that disagree with the others of their direction are found first (suspicious_runs):
// one whose readings are the others' scaled by about -1 (a reversed sign), by 1000, 25.4
// or their inverses (another unit), or that stands off them by more than 4 times their
// scatter (an outlier: a disturbed run).
#pragma once

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "vc/identify/laser_runs.hpp"

namespace vc::identify {

struct TargetStatistics {
  double target = 0.0;
  double mean_up = 0.0, mean_down = 0.0, mean = 0.0;  // x_i_up, x_i_down, x_i
  double s_up = 0.0, s_down = 0.0;
  double reversal = 0.0;                     // B_i
  double r_up = 0.0, r_down = 0.0, r = 0.0;  // R_i_up, R_i_down, R_i
};

struct Iso230_2 {
  int runs_up = 0, runs_down = 0;
  std::vector<TargetStatistics> targets;                                         // ascending
  double reversal = 0.0, mean_reversal = 0.0;                                    // B, mean B_i
  double repeatability_up = 0.0, repeatability_down = 0.0, repeatability = 0.0;  // R_up, R_down, R
  double systematic_up = 0.0, systematic_down = 0.0, systematic = 0.0;           // E_up, E_down, E
  double accuracy_up = 0.0, accuracy_down = 0.0, accuracy = 0.0;                 // A_up, A_down, A
  double range = 0.0;                                                            // M
};

using RunKey = std::pair<int, Direction>;  // run number, direction

struct SuspiciousRun {
  RunKey run;
  std::string reason;
};

std::vector<SuspiciousRun> suspicious_runs(const LaserRuns& runs);

// The evaluation without the runs in `left_out`. Throws std::runtime_error (with the file and
// line) when it cannot be made: a run that misses a target or reads one twice, fewer than two
// runs in a direction, targets that differ between runs.
Iso230_2 evaluate_iso230_2(const LaserRuns& runs, const std::set<RunKey>& left_out = {});

}  // namespace vc::identify
