#include "vc/predistort/linear_correction.hpp"

#include <cmath>
#include <limits>

#include "travel_samples.hpp"
#include "vc/machine/forward.hpp"

namespace vc::predistort {
namespace {

using machine::Joints;
using machine::Machine;

constexpr int kSamples = 400;
constexpr double kMargin = 2.0;

}  // namespace

LinearCorrection::LinearCorrection(const machine::Model& model)
    : model_(model), applies_(model.joint_count() == 3 && model.rotary_count() == 0) {}

LinearCorrection::PerTool& LinearCorrection::for_tool(double tool_length_mm) {
  for (PerTool& t : per_tool_)
    if (t.tool_length_mm == tool_length_mm) return t;
  PerTool t;
  t.tool_length_mm = tool_length_mm;
  const Joints zero = Joints::Zero(3);
  machine::PoseDerivatives d;
  t.tip_at_zero = machine::tool_pose(model_, Machine::Ideal, zero, tool_length_mm, d).tip_mm;
  t.jacobian = d.tip.leftCols<3>();
  t.lu.compute(t.jacobian);
  const Eigen::Matrix3d inverse = t.lu.inverse();
  // kappa: the largest slope of the volumetric error seen through A^-1, over the travel.
  TravelSamples samples(model_);
  double kappa = 0.0;
  for (int sample = 0; sample < kSamples; ++sample) {
    const Joints q = samples.next();
    machine::PoseDerivatives real;
    machine::tool_pose(model_, Machine::Real, q, tool_length_mm, real);
    kappa = std::max(kappa, ((real.tip.leftCols<3>() - t.jacobian) * inverse).norm());
  }
  t.kappa = kMargin * kappa;
  per_tool_.push_back(t);
  return per_tool_.back();
}

bool LinearCorrection::correct(const Joints& target, double tool_length_mm, const Joints& seed, Joints& corrected) {
  if (!applies_ || !target.allFinite() || !seed.allFinite()) return false;
  const PerTool& t = for_tool(tool_length_mm);
  if (!(std::abs(t.lu.determinant()) > 0.0) || !(t.kappa < 1e-2)) return false;
  const Eigen::Vector3d ideal = t.jacobian * target.head<3>() + t.tip_at_zero;
  const machine::SolverOptions& opt = model_.solver;
  corrected = seed;
  double previous = std::numeric_limits<double>::infinity();
  for (int step = 0; step <= 3; ++step) {
    const Eigen::Vector3d residual =
        machine::tool_pose(model_, Machine::Real, corrected, tool_length_mm).tip_mm - ideal;
    const double norm = residual.norm();
    if (!std::isfinite(norm)) return false;
    if (norm <= opt.position_tolerance_mm) return true;
    if (step == 3 || norm > 1e-2 * previous) return false;
    previous = norm;
    corrected -= t.lu.solve(residual);
    if (t.kappa * norm <= kAcceptedResidualMm) return true;  // the residual is now below that
  }
  return false;
}

}  // namespace vc::predistort
