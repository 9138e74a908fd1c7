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
    : affine_(model.joint_count() == 3 && model.rotary_count() == 0), full_rad_(model.fade.full_rad) {
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[static_cast<std::size_t>(j)].type == AxisType::Rotary) rotary_[static_cast<std::size_t>(rotary_count_++)] = j;
  kappa_.fill(std::numeric_limits<double>::infinity());
  for (int e = 0; e < kBands; ++e) {
    const double edge = (e == 0 ? 1.0 : kBandEdges[e - 1]) * full_rad_;
    edge_cos_[static_cast<std::size_t>(e)] = std::cos(edge);
    edge_sin_[static_cast<std::size_t>(e)] = std::sin(edge);
  }
  // The full correction's equations are square only with 3 + rotary joints (no bound else).
  if (tool_lengths_mm.empty() || model.joint_count() != 3 + model.rotary_count()) return;
  kappa_.fill(0.0);
  for (double length : tool_lengths_mm) {
    std::array<double, kBands> largest{};
    std::array<int, kBands> count{};
    sample(model, length, over_temperatures, largest, count);
    // Too few samples in all (the travel hardly reaches full correction): no bound.
    const int taken = std::accumulate(count.begin(), count.end(), 0);
    const double overall = taken >= kBandSamples ? *std::max_element(largest.begin(), largest.end())
                                                 : std::numeric_limits<double>::infinity();
    for (std::size_t band = 0; band < kBands; ++band)
      kappa_[band] = std::max(kappa_[band], kMargin * (count[band] >= kBandSamples ? largest[band] : overall));
  }
  shortest_mm_ = *std::min_element(tool_lengths_mm.begin(), tool_lengths_mm.end());
  longest_mm_ = *std::max_element(tool_lengths_mm.begin(), tool_lengths_mm.end());
}

void ContractionBound::sample(const Model& model, double tool_length_mm, bool over_temperatures,
                              std::array<double, kBands>& largest, std::array<int, kBands>& count) const {
  const int n = model.joint_count();
  std::array<int, kMaxAxes> all{};
  std::iota(all.begin(), all.end(), 0);
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxAxes, 1> w = Eigen::VectorXd::Ones(n);
  w.tail(n - 3).setConstant(kDirectionLeverMm);
  Model varied = model;  // its temperatures drawn at each sample (over_temperatures)
  TravelSamples samples(model);
  const int bands = affine_ ? 1 : kBands;
  for (int draw = 0; draw < kMaxDraws; ++draw) {
    if (*std::min_element(count.begin(), count.begin() + bands) >= kBandSamples) break;
    const Joints q = samples.next();
    if (over_temperatures)
      for (TemperatureInput& t : varied.temperatures) t.value_degC = samples.uniform(t.min_degC, t.max_degC);
    PoseDerivatives d;
    const ToolPose ideal = tool_pose(varied, Machine::Ideal, q, tool_length_mm, d);
    const int band = band_at(ideal, d);
    if (band < 0 || count[static_cast<std::size_t>(band)] >= kBandSamples) continue;
    const CorrectionTarget equations = full_target(varied, ideal, d);
    const SquareMatrix b = correction_jacobian(equations, d, all, n);
    const Correction core = correct(varied, q, tool_length_mm);
    if (core.status != Status::Ok) continue;
    PoseDerivatives real;
    tool_pose(varied, Machine::Real, core.joints, tool_length_mm, real);
    const SquareMatrix jacobian = correction_jacobian(equations, real, all, n);
    const SquareMatrix contraction = (b - jacobian) * b.inverse();
    double& l = largest[static_cast<std::size_t>(band)];
    l = std::max(l, (w.asDiagonal() * contraction * w.cwiseInverse().asDiagonal()).norm());
    ++count[static_cast<std::size_t>(band)];
  }
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
    while (beyond < kBands && across * edge_cos_[static_cast<std::size_t>(beyond)] >=
                                  along * edge_sin_[static_cast<std::size_t>(beyond)])
      ++beyond;
    band = std::min(band, beyond);
  }
  return band - 1;
}

}  // namespace vc::machine
