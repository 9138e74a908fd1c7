#include "vc/machine/contraction_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "vc/machine/correct.hpp"
#include "vc/machine/correction_equations.hpp"
#include "vc/machine/travel_samples.hpp"

namespace vc::machine {
namespace {

constexpr double kMargin = 2.0;
// Bands of the pole angle, from the angle of full correction (fade = 1) outward: B^-1, and
// with it kappa, grows towards the pole. Each band is sampled until it has kBandSamples
// points (or the draws run out: a band the travel hardly reaches takes the largest kappa
// of all bands).
constexpr double kBandEdges[] = {1.5, 2.0, 3.0};  // x the full-correction angle
constexpr int kBandSamples = 100, kMaxDraws = 6000;

}  // namespace

ContractionBound::ContractionBound(const Model& model, const std::vector<double>& tool_lengths_mm,
                                   bool over_temperatures)
    : affine_(model.joint_count() == 3 && model.rotary_count() == 0),
      full_rad_(model.fade.full_rad),
      fade_start_rad_(model.fade.start_rad),
      position_kappa_(std::numeric_limits<double>::infinity()),
      fade_band_kappa_sin_(std::numeric_limits<double>::infinity()) {
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[static_cast<std::size_t>(j)].type == AxisType::Rotary)
      rotary_[static_cast<std::size_t>(rotary_count_++)] = j;
  kappa_.fill(std::numeric_limits<double>::infinity());
  for (int e = 0; e < kBands; ++e) {
    const double edge = (e == 0 ? 1.0 : kBandEdges[e - 1]) * full_rad_;
    edge_cos_[static_cast<std::size_t>(e)] = std::cos(edge);
    edge_sin_[static_cast<std::size_t>(e)] = std::sin(edge);
  }
  // The full correction's equations are square only with 3 + rotary joints (no bound else).
  if (tool_lengths_mm.empty() || model.joint_count() != 3 + model.rotary_count()) return;
  kappa_.fill(0.0);
  double position = 0.0, fade_band = 0.0;
  for (double length : tool_lengths_mm) {
    const Largest largest = sample(model, length, over_temperatures);
    // Too few samples in all (the travel hardly reaches full correction): no bound.
    const int taken = std::accumulate(largest.count.begin(), largest.count.end(), 0);
    const double overall = taken >= kBandSamples ? *std::max_element(largest.band.begin(), largest.band.end())
                                                 : std::numeric_limits<double>::infinity();
    for (std::size_t band = 0; band < kBands; ++band)
      kappa_[band] =
          std::max(kappa_[band], kMargin * (largest.count[band] >= kBandSamples ? largest.band[band] : overall));
    position = std::max(position, largest.position_count >= kBandSamples ? kMargin * largest.position
                                                                         : std::numeric_limits<double>::infinity());
    fade_band = std::max(fade_band, largest.fade_band_count >= kBandSamples ? kMargin * largest.fade_band
                                                                            : std::numeric_limits<double>::infinity());
  }
  if (rotary_count_ > 0) {
    position_kappa_ = position;
    fade_band_kappa_sin_ = fade_band;
  }
  shortest_mm_ = *std::min_element(tool_lengths_mm.begin(), tool_lengths_mm.end());
  longest_mm_ = *std::max_element(tool_lengths_mm.begin(), tool_lengths_mm.end());
}

ContractionBound::Largest ContractionBound::sample(const Model& model, double tool_length_mm,
                                                   bool over_temperatures) const {
  Largest largest;
  const int n = model.joint_count();
  std::array<int, kMaxAxes> all{}, linear{};
  std::iota(all.begin(), all.end(), 0);
  for (int j = 0, c = 0; j < n; ++j)
    if (model.axes[static_cast<std::size_t>(j)].type == AxisType::Linear) linear[static_cast<std::size_t>(c++)] = j;
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxAxes, 1> w = Eigen::VectorXd::Ones(n);
  w.tail(n - 3).setConstant(kDirectionLeverMm);
  Conditions conditions = model.reference_conditions();  // temperatures drawn at each sample (over_temperatures)
  TravelSamples samples(model);
  const int bands = affine_ ? 1 : kBands;
  const bool positions = rotary_count_ > 0;  // (on three linear axes they are the bands' equations)
  for (int draw = 0; draw < kMaxDraws; ++draw) {
    const bool bands_full = *std::min_element(largest.count.begin(), largest.count.begin() + bands) >= kBandSamples;
    const bool positions_full = !positions || largest.position_count >= kBandSamples;
    const bool fade_band_full = rotary_count_ == 0 || largest.fade_band_count >= kBandSamples;
    if (bands_full && positions_full && fade_band_full) break;
    const Joints q = samples.next();
    if (over_temperatures)
      for (std::size_t i = 0; i < model.temperatures.size(); ++i)
        conditions.temperature_degC[i] =
            samples.uniform(model.temperatures[i].min_degC, model.temperatures[i].max_degC);
    PoseDerivatives d;
    const ToolPose ideal = tool_pose(model, Machine::Ideal, q, tool_length_mm, d);
    const int band = band_at(ideal, d);
    const bool band_wanted = band >= 0 && largest.count[static_cast<std::size_t>(band)] < kBandSamples;
    const double phi = band < 0 && !fade_band_full ? pole_angle_at(model, ideal, d) : 0.0;
    const bool fade_band_wanted = band < 0 && !fade_band_full && phi >= fade_start_rad_;
    if (!band_wanted && !fade_band_wanted && positions_full) continue;
    const Correction core = correct(model, conditions, q, tool_length_mm);
    if (core.status != Status::Ok) continue;
    PoseDerivatives real;
    tool_pose(model, conditions, Machine::Real, core.joints, tool_length_mm, real);
    // |W (B - J_real) B^-1 W^-1| of the full correction's equations, J_real at `joints`.
    auto full_contraction = [&](const PoseDerivatives& at_joints) {
      const CorrectionTarget equations = full_target(model, ideal, d);
      const SquareMatrix b = correction_jacobian(equations, d, all, n);
      const SquareMatrix contraction = (b - correction_jacobian(equations, at_joints, all, n)) * b.inverse();
      return (w.asDiagonal() * contraction * w.cwiseInverse().asDiagonal()).norm();
    };
    if (band_wanted) {
      double& l = largest.band[static_cast<std::size_t>(band)];
      l = std::max(l, full_contraction(real));
      ++largest.count[static_cast<std::size_t>(band)];
    }
    if (fade_band_wanted && core.full_joints.size() > 0) {  // (at phi = start exactly the fade is 0: none)
      PoseDerivatives real_full;                            // where the full correction's Newton ends
      tool_pose(model, conditions, Machine::Real, core.full_joints, tool_length_mm, real_full);
      largest.fade_band = std::max(largest.fade_band, full_contraction(real_full) * std::sin(phi));
      ++largest.fade_band_count;
    }
    if (!positions_full) {
      const CorrectionTarget equations = position_target(ideal);
      const SquareMatrix b = correction_jacobian(equations, d, linear, 3);
      const SquareMatrix contraction = (b - correction_jacobian(equations, real, linear, 3)) * b.inverse();
      largest.position = std::max(largest.position, contraction.norm());
      ++largest.position_count;
    }
  }
  return largest;
}

double ContractionBound::fade_band_kappa(double pole_angle_rad) const {
  if (!(pole_angle_rad >= fade_start_rad_)) return std::numeric_limits<double>::infinity();
  return fade_band_kappa_sin_ / std::sin(pole_angle_rad);
}

int ContractionBound::band_of(double pole_angle_rad) const {
  if (affine_) return 0;
  if (pole_angle_rad < full_rad_) return -1;
  int band = 0;
  for (double edge : kBandEdges) band += pole_angle_rad >= edge * full_rad_;
  return band;
}

// The angle between a rotary axis line l and the tool direction k is at least theta (in
// [0, pi/2]) where |l x k| cos(theta) >= |l . k| sin(theta).
int ContractionBound::band_at(const ToolPose& ideal, const PoseDerivatives& d) const {
  if (affine_) return 0;
  int band = kBands;  // the number of edges every line is beyond, less one
  for (int r = 0; r < rotary_count_; ++r) {
    const Eigen::Vector3d line = d.axis_line.col(rotary_[static_cast<std::size_t>(r)]);
    const double across = line.cross(ideal.direction).norm(), along = std::abs(line.dot(ideal.direction));
    int beyond = 0;
    while (beyond < kBands &&
           across * edge_cos_[static_cast<std::size_t>(beyond)] >= along * edge_sin_[static_cast<std::size_t>(beyond)])
      ++beyond;
    band = std::min(band, beyond);
  }
  return band - 1;
}

}  // namespace vc::machine
