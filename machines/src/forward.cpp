#include "vc/machine/forward.hpp"

#include <cmath>

#include "vc/tables/units.hpp"

namespace vc::machine {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Twists = Eigen::Matrix<double, 3, kMaxAxes>;

// How a chain moves when each joint moves: the velocity of the point at the bed origin and
// the angular velocity, both in the bed frame, per unit of joint j (screw at the origin).
struct ChainMotion {
  Twists linear = Twists::Zero();
  Twists angular = Twists::Zero();
  Twists axis_line = Twists::Zero();  // rotary joints of this chain: line direction in bed
};

// Rot(u, angle), Rodrigues' formula (u unit).
Matrix3d rotation_about(const Vector3d& u, double angle) {
  double s, c;
  sin_cos(angle, s, c);
  Matrix3d k;
  k << 0.0, -u.z(), u.y(), u.z(), 0.0, -u.x(), -u.y(), u.x(), 0.0;
  return Matrix3d::Identity() + s * k + (1.0 - c) * (k * k);
}

// Walks one chain bed outward; returns bed_T_last and, if asked, the chain's motion.
Isometry3d walk_chain(const Model& model, Machine machine, const std::vector<int>& chain,
                      const Joints& q, ChainMotion* motion) noexcept {
  Isometry3d bed_T_parent = Isometry3d::Identity();
  AxisErrors err;
  for (int i : chain) {
    const Axis& axis = model.axes[i];
    const bool real = machine == Machine::Real;
    const Isometry3d& base = real ? axis.real_base : axis.ideal_base;
    const double qi = q[i];
    Vector3d delta = Vector3d::Zero(), eps = Vector3d::Zero();
    if (real && !axis.tables.empty()) {
      axis_errors(model, i, q, err);
      delta = err.delta_mm;
      eps = err.eps_rad;
    }
    Matrix3d r_eps = Matrix3d::Identity(), eps_rate = Matrix3d::Zero();
    if (real) rotation_xyz(eps, r_eps, eps_rate);
    Isometry3d motion_part = Isometry3d::Identity();  // T(q u) T(delta) R(eps) [Rot(u, q)]
    if (axis.type == AxisType::Linear) {
      motion_part.translation() = qi * axis.direction + delta;
      motion_part.linear() = r_eps;
    } else {
      motion_part.translation() = delta;
      motion_part.linear() = r_eps * rotation_about(axis.direction, qi * tables::kDegToRad);
    }
    if (motion) {
      // Child origin and the rotation into bed coordinates of the frame after `base`.
      const Isometry3d bed_T_base = bed_T_parent * base;
      const Vector3d child_origin = bed_T_base * motion_part.translation();
      const Matrix3d to_bed = bed_T_base.linear();
      for (int j = 0; j < model.joint_count(); ++j) {
        if (!((axis.moved_by >> j) & 1u)) continue;
        Vector3d v = Vector3d::Zero(), w = Vector3d::Zero();
        if (real && !axis.tables.empty()) {
          v = err.slope.block<3, 1>(0, j);
          w = eps_rate * err.slope.block<3, 1>(3, j);
        }
        if (j == i) {
          if (axis.type == AxisType::Linear)
            v += axis.direction;
          else
            w += r_eps * axis.direction * tables::kDegToRad;
        }
        const Vector3d w_bed = to_bed * w;
        motion->linear.col(j) += to_bed * v - w_bed.cross(child_origin);
        motion->angular.col(j) += w_bed;
      }
      if (axis.type == AxisType::Rotary) motion->axis_line.col(i) = to_bed * r_eps * axis.direction;
    }
    bed_T_parent = bed_T_parent * base * motion_part;
  }
  return bed_T_parent;
}

Isometry3d tool_offset(double tool_length_mm) {
  Isometry3d t = Isometry3d::Identity();
  t.translation() = Vector3d(0.0, 0.0, -tool_length_mm);
  return t;
}

ToolPose evaluate(const Model& model, Machine machine, const Joints& q, double tool_length_mm,
                  PoseDerivatives* d) noexcept {
  const bool real = machine == Machine::Real;
  ChainMotion tool_motion, part_motion;
  const Isometry3d bed_T_tool =
      walk_chain(model, machine, model.tool_chain, q, d ? &tool_motion : nullptr) *
      (real ? model.spindle.real : model.spindle.ideal) * tool_offset(tool_length_mm);
  const Isometry3d bed_T_part =
      walk_chain(model, machine, model.workpiece_chain, q, d ? &part_motion : nullptr) *
      model.fixture;
  const Vector3d tip_bed = bed_T_tool.translation();
  const Vector3d k_bed = bed_T_tool.linear().col(2);
  const Matrix3d part_R_bed = bed_T_part.linear().transpose();
  ToolPose pose{part_R_bed * (tip_bed - bed_T_part.translation()), part_R_bed * k_bed};
  if (d) {
    // Relative motion of the tool against the part, seen in the part frame.
    for (int j = 0; j < model.joint_count(); ++j) {
      const Vector3d v_rel = (tool_motion.linear.col(j) + tool_motion.angular.col(j).cross(tip_bed)) -
                             (part_motion.linear.col(j) + part_motion.angular.col(j).cross(tip_bed));
      const Vector3d w_rel = tool_motion.angular.col(j) - part_motion.angular.col(j);
      d->tip.col(j) = part_R_bed * v_rel;
      d->direction.col(j) = part_R_bed * w_rel.cross(k_bed);
      d->axis_line.col(j) = part_R_bed * (tool_motion.axis_line.col(j) + part_motion.axis_line.col(j));
    }
  }
  return pose;
}

}  // namespace

void axis_errors(const Model& model, int joint, const Joints& q, AxisErrors& out) noexcept {
  out.delta_mm.setZero();
  out.eps_rad.setZero();
  out.slope.setZero();
  tables::ErrorTable::Sample sample;
  for (int t : model.axes[joint].tables) {
    const BoundTable& bound = model.tables[t];
    const auto& grid = bound.table.grid();
    std::array<double, tables::ErrorTable::kMaxVariables> at{};
    for (std::size_t v = 0; v < grid.size(); ++v) at[v] = q[bound.joint[v]];
    bound.table.evaluate(at.data(), sample);
    const auto& columns = bound.table.columns();
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const int k = columns[c].symbol.component;
      (k < 3 ? out.delta_mm[k] : out.eps_rad[k - 3]) += sample.value[c];
      for (std::size_t v = 0; v < grid.size(); ++v) out.slope(k, bound.joint[v]) += sample.slope[c][v];
    }
  }
}

ToolPose tool_pose(const Model& model, Machine machine, const Joints& q,
                   double tool_length_mm) noexcept {
  return evaluate(model, machine, q, tool_length_mm, nullptr);
}

ToolPose tool_pose(const Model& model, Machine machine, const Joints& q, double tool_length_mm,
                   PoseDerivatives& derivatives) noexcept {
  return evaluate(model, machine, q, tool_length_mm, &derivatives);
}

Isometry3d part_T_tool(const Model& model, Machine machine, const Joints& q,
                       double tool_length_mm) noexcept {
  const bool real = machine == Machine::Real;
  const Isometry3d bed_T_tool = walk_chain(model, machine, model.tool_chain, q, nullptr) *
                                (real ? model.spindle.real : model.spindle.ideal) *
                                tool_offset(tool_length_mm);
  const Isometry3d bed_T_part =
      walk_chain(model, machine, model.workpiece_chain, q, nullptr) * model.fixture;
  return bed_T_part.inverse() * bed_T_tool;
}

VolumetricError volumetric_error(const Model& model, const Joints& q,
                                 double tool_length_mm) noexcept {
  const ToolPose real = tool_pose(model, Machine::Real, q, tool_length_mm);
  const ToolPose ideal = tool_pose(model, Machine::Ideal, q, tool_length_mm);
  return {real.tip_mm - ideal.tip_mm, ideal.direction.cross(real.direction)};
}

}  // namespace vc::machine
