#include "vc/machine/correct.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace vc::machine {
namespace {

using Eigen::Vector3d;
using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxAxes, kMaxAxes>;
using FreeJoints = std::array<bool, kMaxAxes>;

// What the real machine must reach: the ideal tool tip, and the components of the direction
// error k* x k that must vanish (along each basis vector).
struct Target {
  Vector3d tip_mm;
  Vector3d direction;
  std::array<Vector3d, 2> basis;
  int direction_equations = 0;
};

// Residual of the equations: tip position (mm), then direction components (rad).
Joints residual_of(const Target& target, const ToolPose& pose, int equations) {
  Joints r(equations);
  r.head(3) = pose.tip_mm - target.tip_mm;
  const Vector3d dir_error = target.direction.cross(pose.direction);
  for (int m = 0; m < target.direction_equations; ++m) r[3 + m] = target.basis[m].dot(dir_error);
  return r;
}

// d residual / d q of the free joints, from pose derivatives.
Square jacobian_of(const Target& target, const PoseDerivatives& d, const std::array<int, kMaxAxes>& index,
                   int unknowns) {
  Square jacobian(unknowns, unknowns);
  for (int c = 0; c < unknowns; ++c) {
    const int j = index[c];
    jacobian.block(0, c, 3, 1) = d.tip.col(j);
    const Vector3d ddir = target.direction.cross(d.direction.col(j));
    for (int m = 0; m < target.direction_equations; ++m) jacobian(3 + m, c) = target.basis[m].dot(ddir);
  }
  return jacobian;
}

// Newton on the real machine for the free joints; the others stay fixed. It starts with the
// ideal machine's Jacobian (`ideal`, already computed for the target): the real one differs
// by the error slopes, ~1e-4, so each step still gains about four digits. Where a step gains
// less than two, the exact Jacobian of the real machine (table slopes included) replaces it.
// `pose` returns the real pose at the final joints.
Status newton(const Model& model, const Target& target, double tool_length_mm, const FreeJoints& free,
              const PoseDerivatives& ideal, Joints& q, int& iterations, ToolPose& pose) noexcept {
  const SolverOptions& opt = model.solver;
  int unknowns = 0;
  std::array<int, kMaxAxes> index{};
  for (int j = 0; j < model.joint_count(); ++j)
    if (free[j]) index[unknowns++] = j;
  Eigen::PartialPivLU<Square> lu(jacobian_of(target, ideal, index, unknowns));
  constexpr double kLeverMm = 1000.0;  // weighs direction residuals against position ones
  double previous_norm = std::numeric_limits<double>::infinity();
  for (int step = 0;; ++step) {
    pose = tool_pose(model, Machine::Real, q, tool_length_mm);
    const Joints residual = residual_of(target, pose, unknowns);
    if (!residual.allFinite()) return Status::NonFinite;
    const double position = residual.head(3).norm();
    const double direction = residual.tail(unknowns - 3).norm();
    if (position <= opt.position_tolerance_mm && direction <= opt.direction_tolerance_rad) return Status::Ok;
    if (step == opt.max_iterations) return Status::NotConverged;
    const double norm = position + kLeverMm * direction;
    if (norm > 1e-2 * previous_norm) {
      PoseDerivatives exact;
      tool_pose(model, Machine::Real, q, tool_length_mm, exact);
      lu.compute(jacobian_of(target, exact, index, unknowns));
    }
    previous_norm = norm;
    if (!(std::abs(lu.determinant()) > 0.0)) return Status::Singular;
    const Joints step_vector = lu.solve(-residual);
    if (!step_vector.allFinite()) return Status::Singular;
    for (int c = 0; c < unknowns; ++c) q[index[c]] += step_vector[c];
    ++iterations;
  }
}

// Two unit vectors perpendicular to k (and to each other).
std::array<Vector3d, 2> perpendicular_basis(const Vector3d& k) {
  Eigen::Index smallest;
  k.cwiseAbs().minCoeff(&smallest);
  const Vector3d b1 = k.cross(Vector3d::Unit(smallest)).normalized();
  return {b1, k.cross(b1)};
}

double line_angle(const Vector3d& line, const Vector3d& k) {
  return std::atan2(line.cross(k).norm(), std::abs(line.dot(k)));
}

double pole_angle_at(const Model& model, const ToolPose& ideal, const PoseDerivatives& d) {
  double phi = 0.5 * 3.14159265358979323846;
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[j].type == AxisType::Rotary)
      phi = std::min(phi, line_angle(d.axis_line.col(j).normalized(), ideal.direction));
  return phi;
}

}  // namespace

double fade_factor(const PoleFade& fade, double phi) noexcept {
  const double s = std::clamp((phi - fade.start_rad) / (fade.full_rad - fade.start_rad), 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

double pole_angle(const Model& model, const Joints& nominal, double tool_length_mm) noexcept {
  PoseDerivatives d;
  const ToolPose ideal = tool_pose(model, Machine::Ideal, nominal, tool_length_mm, d);
  return pole_angle_at(model, ideal, d);
}

Correction correct(const Model& model, const Joints& nominal, double tool_length_mm) noexcept {
  return correct(model, nominal, tool_length_mm, nominal);
}

Correction correct(const Model& model, const Joints& nominal, double tool_length_mm,
                   const Joints& seed) noexcept {
  Correction out;
  out.nominal = nominal;
  out.joints = seed;
  if (!nominal.allFinite() || !seed.allFinite() || !std::isfinite(tool_length_mm)) {
    out.status = Status::NonFinite;
    return out;
  }
  const int n = model.joint_count();
  PoseDerivatives d;
  const ToolPose ideal = tool_pose(model, Machine::Ideal, nominal, tool_length_mm, d);
  Target target{ideal.tip_mm, ideal.direction, {}, 0};
  ToolPose real = ideal;  // the real pose at the final joints, set by newton()

  FreeJoints linear{}, all{};
  for (int j = 0; j < n; ++j) {
    linear[j] = model.axes[j].type == AxisType::Linear;
    all[j] = true;
  }
  const int rotary = model.rotary_count();
  if (rotary > 0) {
    out.pole_angle_rad = pole_angle_at(model, ideal, d);
    out.fade = fade_factor(model.fade, out.pole_angle_rad);
  }
  if (rotary > 0 && out.fade > 0.0) {
    // Full correction: position and tool direction.
    target.direction_equations = rotary;
    if (rotary == 2) {
      target.basis = perpendicular_basis(ideal.direction);
    } else {
      for (int j = 0; j < n; ++j)
        if (!linear[j]) target.basis[0] = d.axis_line.col(j).normalized();
    }
    out.status = newton(model, target, tool_length_mm, all, d, out.joints, out.iterations, real);
    if (out.status != Status::Ok) return out;
    target.direction_equations = 0;
  }
  if (rotary > 0 && out.fade < 1.0) {
    // Rotary joints take f of their full correction; linear joints make the position exact.
    for (int j = 0; j < n; ++j)
      if (!linear[j]) out.joints[j] = nominal[j] + out.fade * (out.joints[j] - nominal[j]);
  }
  if (rotary == 0 || out.fade < 1.0)
    out.status = newton(model, target, tool_length_mm, linear, d, out.joints, out.iterations, real);
  out.residual_mm = (real.tip_mm - ideal.tip_mm).norm();
  out.residual_rad = ideal.direction.cross(real.direction).norm();
  return out;
}

Uncorrection uncorrect(const Model& model, const Joints& corrected, double tool_length_mm) noexcept {
  return uncorrect(model, corrected, tool_length_mm, 1.0, corrected);
}

Uncorrection uncorrect(const Model& model, const Joints& corrected, double tool_length_mm, double gain,
                       const Joints& nominal_seed) noexcept {
  Uncorrection out;
  out.nominal = corrected;
  if (!corrected.allFinite() || !nominal_seed.allFinite() || !std::isfinite(gain)) {
    out.status = Status::NonFinite;
    return out;
  }
  if (gain == 0.0) return out;  // nothing applied: the joints are the nominal ones
  out.nominal = nominal_seed;
  Joints correction_seed = corrected;  // where the correction of the current guess lands
  for (out.iterations = 1; out.iterations <= model.solver.max_iterations; ++out.iterations) {
    const Correction c = correct(model, out.nominal, tool_length_mm, correction_seed);
    if (c.status != Status::Ok) {
      out.status = c.status;
      return out;
    }
    const Joints applied = out.nominal + gain * (c.joints - out.nominal);
    const Joints difference = applied - corrected;
    out.nominal -= difference;
    correction_seed = c.joints - difference;
    if (difference.cwiseAbs().maxCoeff() <= model.solver.position_tolerance_mm) return out;
  }
  out.status = Status::NotConverged;
  out.iterations = model.solver.max_iterations;
  return out;
}

}  // namespace vc::machine
