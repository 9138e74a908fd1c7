// Self-tuning, model strategy: the measured deviations identify corrections to the machine's
// error tables, which then serve every part (the one measured and the next, different one).
//
// Unknowns: for each tuned component error (EXX, EYX, ... of each axis) its values at
// `nodes` equally spaced positions over the axis's travel, linearly interpolated (a low-order
// shape; a linear shape of a straightness is a squareness; a full turn is periodic), and the
// location errors of the rotary axes' lines (EX0C ... EC0C). Each kept report point k, cut at
// joints q_k, gives one equation
//     n_k . (d tip(q_k) / d p) dp = filtered deviation_k - deviation the current model predicts
// (the model predicts no deviation for a program pre-distorted with it). Least squares with
// columns scaled to unit norm, a ridge (regularisation) for what the part cannot see, and a
// penalty on second differences along each table (smoothness).
// The result is one table per axis, "selftune_<axis>.csv", summed with the measured tables
// (an earlier tuning of the same name is carried over and added to), and the new location
// values. How much of each deviation the part determines is the resolution matrix's diagonal
// (1: the points fix it, 0: only the ridge and the smoothness do).
#pragma once

#include <string>
#include <vector>

#include "vc/shop/first_part.hpp"
#include "vc/shop/machine_file_writer.hpp"

namespace vc::shop {

struct ModelOptions {
  // Deviations to tune, e.g. EXX,EYX,EX0C; empty: the six component errors of every axis and
  // the location errors of every rotary axis.
  std::vector<std::string> deviations;
  int nodes = 5;
  double regularisation = 1e-3;
  double smoothness = 1e-2;
};

struct ModelFit {
  std::vector<ExtraTable> tables;
  std::vector<LocationValue> locations;  // tuned location errors: the model's plus the change
  struct Seen {
    std::string symbol;  // EXX, EX0C, ...
    double share;        // 0..1: how much of it the part determines (resolution)
  };
  std::vector<Seen> seen;  // best seen first
  int points = 0, parameters = 0, unobservable = 0;
  double rms_before_mm = 0.0, rms_after_mm = 0.0;  // of the equations' right-hand side and residual
  // What the fit spends of the points: the trace of its influence matrix (= the resolutions'
  // sum), between 0 and min(points, parameters).
  double effective_unknowns = 0.0;
  // The scatter the tuned model leaves per point (the CMM's noise and what the model cannot
  // represent), |residual| / sqrt(points - effective_unknowns); -1 where no freedom is left.
  double scatter_mm = -1.0;
  // That scatter carried into the tuned model's prediction at the measured points (1 sigma,
  // as if independent per point): median and largest; -1 with the scatter.
  double carried_median_mm = -1.0, carried_largest_mm = -1.0;
  // The same at the points of another part (fit_tables' `next`): what the tuned tables carry
  // there, before it is cut.
  int next_points = 0;
  double next_carried_median_mm = -1.0, next_carried_largest_mm = -1.0;
  // What this part cannot see and the next part feels: per deviation, how far its part the fit
  // could not determine (I - resolution) moves the next part's points, at most, per um (length)
  // or urad (angle) of it; largest first. The size of that part is not known from this part's
  // points: a sensitivity, not a bound.
  struct Unseen {
    std::string symbol;
    bool angle = false;
    double largest_mm_per_unit = 0.0;
  };
  std::vector<Unseen> next_unseen;
  double largest_change_mm = 0.0, largest_change_rad = 0.0;
};

// Throws std::invalid_argument for a deviation symbol the machine does not have. `next`: the
// points of another part matched to its program's cuts (analyse_first_part of its plan), for
// the noise the tuned tables carry there.
ModelFit fit_model(const machine::Model& model, const FirstPart& part, const ModelOptions& options,
                   const FirstPart* next = nullptr);

// The file name of an axis's tuning table.
std::string tuning_table_name(char axis);

}  // namespace vc::shop
