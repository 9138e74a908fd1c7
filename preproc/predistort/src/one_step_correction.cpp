#include "vc/predistort/one_step_correction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "travel_samples.hpp"
#include "vc/machine/correct.hpp"

namespace vc::predistort {
namespace {

using machine::Joints;
using machine::Machine;
using machine::SquareMatrix;

constexpr double kMargin = 2.0;
// Bands of the pole angle, from the angle of full correction (fade = 1) outward: B^-1, and
// with it kappa, grows towards the pole. Each band is sampled until it has kBandSamples
// points (or the draws run out: a band the travel hardly reaches takes the largest kappa
// of all bands).
constexpr double kBandEdges[] = {1.5, 2.0, 3.0};  // x the full-correction angle
constexpr int kBandSamples = 100, kMaxDraws = 6000;
constexpr int kMaxSteps = 3;

}  // namespace

OneStepCorrection::OneStepCorrection(const machine::Model& model)
    : model_(model),
      applies_(model.joint_count() == 3 + model.rotary_count()),
      affine_(model.joint_count() == 3 && model.rotary_count() == 0) {
  if (applies_ && !affine_ && model.rotary_count() <= 2) blocks_.emplace(model);
  for (int e = 0; e < kBands; ++e) {
    const double edge = (e == 0 ? 1.0 : kBandEdges[e - 1]) * model.fade.full_rad;
    edge_cos_[e] = std::cos(edge);
    edge_sin_[e] = std::sin(edge);
  }
  for (int j = 0; j < machine::kMaxAxes; ++j) all_joints_[j] = j;
}

// |W r|: direction rows weighed by the lever, so the bound is one number in mm.
double OneStepCorrection::weighted_norm(const Joints& residual) const {
  return std::sqrt(residual.head(3).squaredNorm() +
                   machine::kDirectionLeverMm * machine::kDirectionLeverMm * machine::direction_squared_norm(residual));
}

// Without atan2: the angle between a rotary axis line l and the tool direction k is at least
// theta (in [0, pi/2]) where |l x k| cos(theta) >= |l . k| sin(theta).
int OneStepCorrection::pole_band(const machine::ToolPose& ideal, const machine::PoseDerivatives& d) const {
  int band = kBands;  // the number of edges every line is beyond, less one
  for (int j = 0; j < model_.joint_count(); ++j) {
    if (model_.axes[static_cast<std::size_t>(j)].type != machine::AxisType::Rotary) continue;
    const Eigen::Vector3d line = d.axis_line.col(j);
    const double across = line.cross(ideal.direction).norm(), along = std::abs(line.dot(ideal.direction));
    int beyond = 0;
    while (beyond < kBands && across * edge_cos_[beyond] >= along * edge_sin_[beyond]) ++beyond;
    band = std::min(band, beyond);
  }
  return band - 1;
}

int OneStepCorrection::band_of(double pole_angle_rad) const {
  if (affine_) return 0;
  int band = 0;
  for (double edge : kBandEdges) band += pole_angle_rad >= edge * model_.fade.full_rad;
  return band;
}

bool OneStepCorrection::equations_at(const PerTool& tool, const Joints& target, machine::CorrectionTarget& equations,
                                     SquareMatrix& b, int& band) const {
  band = 0;
  if (affine_) {
    equations = machine::position_target({tool.jacobian * target.head<3>() + tool.tip_at_zero, Eigen::Vector3d::UnitZ()});
    b = tool.jacobian;
    return true;
  }
  machine::PoseDerivatives d;
  const machine::ToolPose ideal = machine::tool_pose(model_, Machine::Ideal, target, tool.tool_length_mm, d);
  band = pole_band(ideal, d);
  if (band < 0) return false;
  equations = machine::full_target(model_, ideal, d);
  b = machine::correction_jacobian(equations, d, all_joints_, model_.joint_count());
  return true;
}

OneStepCorrection::PerTool& OneStepCorrection::for_tool(double tool_length_mm) {
  for (PerTool& t : per_tool_)
    if (t.tool_length_mm == tool_length_mm) return t;
  const int n = model_.joint_count();
  PerTool t;
  t.tool_length_mm = tool_length_mm;
  if (affine_) {
    const Joints zero = Joints::Zero(3);
    machine::PoseDerivatives d;
    t.tip_at_zero = machine::tool_pose(model_, Machine::Ideal, zero, tool_length_mm, d).tip_mm;
    t.jacobian = d.tip.leftCols<3>();
    t.lu.compute(SquareMatrix(t.jacobian));
  }
  // kappa: the largest slope of the real machine's equations against B, seen through B^-1,
  // over the travel where this applies (W: the weights of weighted_norm).
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, machine::kMaxAxes, 1> w = Eigen::VectorXd::Ones(n);
  w.tail(n - 3).setConstant(machine::kDirectionLeverMm);
  TravelSamples samples(model_);
  const int bands = affine_ ? 1 : kBands;
  std::array<int, kBands> count{};
  std::array<double, kBands> largest{};
  for (int draw = 0; draw < kMaxDraws; ++draw) {
    if (*std::min_element(count.begin(), count.begin() + bands) >= kBandSamples) break;
    const Joints q = samples.next();
    machine::CorrectionTarget equations;
    SquareMatrix b;
    int band;
    if (!equations_at(t, q, equations, b, band) || count[band] >= kBandSamples) continue;
    const machine::Correction core = machine::correct(model_, q, tool_length_mm);
    if (core.status != machine::Status::Ok) continue;
    machine::PoseDerivatives real;
    machine::tool_pose(model_, Machine::Real, core.joints, tool_length_mm, real);
    const SquareMatrix jacobian = machine::correction_jacobian(equations, real, all_joints_, n);
    const SquareMatrix contraction = (b - jacobian) * b.inverse();
    largest[band] = std::max(largest[band], (w.asDiagonal() * contraction * w.cwiseInverse().asDiagonal()).norm());
    ++count[band];
  }
  // Too few samples in all (the travel hardly reaches full correction): no bound, so no
  // unverified step (correct() declines).
  const int samples_taken = std::accumulate(count.begin(), count.end(), 0);
  const double overall = samples_taken >= kBandSamples ? *std::max_element(largest.begin(), largest.end())
                                                        : std::numeric_limits<double>::infinity();
  for (int band = 0; band < kBands; ++band)
    t.kappa[band] = kMargin * (count[band] >= kBandSamples ? largest[band] : overall);
  per_tool_.push_back(t);
  return per_tool_.back();
}

bool OneStepCorrection::factorize(const PerTool& tool, const SquareMatrix& b) {
  if (affine_) return std::abs(tool.lu.determinant()) > 0.0;
  blocks_used_ = blocks_ && blocks_->factorize(b);
  if (blocks_used_) return true;
  point_lu_.compute(b);
  return std::abs(point_lu_.determinant()) > 0.0;
}

Joints OneStepCorrection::solve(const PerTool& tool, const Joints& residual) const {
  if (affine_) return tool.lu.solve(residual);
  return blocks_used_ ? blocks_->solve(residual) : Joints(point_lu_.solve(residual));
}

bool OneStepCorrection::correct(const Joints& target, double tool_length_mm, const Joints& seed, Joints& corrected) {
  if (!applies_ || !target.allFinite() || !seed.allFinite()) return false;
  const PerTool& t = for_tool(tool_length_mm);
  machine::CorrectionTarget equations;
  SquareMatrix b;
  int band;
  if (!equations_at(t, target, equations, b, band)) return false;
  const double kappa = t.kappa[band];
  if (!(kappa < 1e-2) || !factorize(t, b)) return false;
  const machine::SolverOptions& opt = model_.solver;
  const int n = model_.joint_count();
  corrected = seed;
  double previous = std::numeric_limits<double>::infinity();
  for (int step = 0; step <= kMaxSteps; ++step) {
    const Joints residual = machine::correction_residual(
        equations, machine::tool_pose(model_, Machine::Real, corrected, tool_length_mm), n);
    const double norm = weighted_norm(residual);
    if (!std::isfinite(norm)) return false;
    if (residual.head(3).norm() <= opt.position_tolerance_mm &&
        std::sqrt(machine::direction_squared_norm(residual)) <= opt.direction_tolerance_rad)
      return true;
    if (step == kMaxSteps || norm > 1e-2 * previous) return false;
    previous = norm;
    corrected -= solve(t, residual);
    if (kappa * norm <= kAcceptedResidualMm) return true;  // the residual is now below that
  }
  return false;
}

}  // namespace vc::predistort
