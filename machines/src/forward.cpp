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
  Twists linear, angular;
  Twists axis_line;  // rotary joints of this chain: line direction in bed
  // Zeroed with vector stores (a memset of this size is slower here than the walk itself).
  ChainMotion() noexcept {
    for (Twists* t : {&linear, &angular, &axis_line})
      for (int c = 0; c < kMaxAxes; ++c) t->col(c) = Eigen::Vector3d::Zero();
  }
};

// Rot(u, angle), Rodrigues' formula (u unit): I + s K + (1 - c) K^2, K = [u]x, with
// K^2 = u u^T - I written out (no matrix product).
Matrix3d rotation_about(const Vector3d& u, double angle) {
  double s, c;
  sin_cos(angle, s, c);
  const double v = 1.0 - c;
  const double x = u.x(), y = u.y(), z = u.z();
  Matrix3d r;
  r << 1.0 + v * (x * x - 1.0), -s * z + v * (x * y), s * y + v * (x * z),
       s * z + v * (x * y), 1.0 + v * (y * y - 1.0), -s * x + v * (y * z),
       -s * y + v * (x * z), s * x + v * (y * z), 1.0 + v * (z * z - 1.0);
  return r;
}

// dst = src, column by column: a matrix a product has just written is read back the way
// it was written (a plain copy reads across its columns' stores and waits for them).
void copy_by_columns(const Matrix3d& src, Matrix3d& dst) noexcept {
  for (int c = 0; c < 3; ++c) dst.col(c) = src.col(c);
}

// A placement in the bed frame: bed_T_frame as rotation and origin (cheaper than 4x4 products).
struct Frame {
  Matrix3d rotation = Matrix3d::Identity();
  Vector3d origin = Vector3d::Zero();

  Frame then(const Isometry3d& t) const {
    return {rotation * t.linear(), origin + rotation * t.translation()};
  }
  Isometry3d isometry() const {
    Isometry3d t = Isometry3d::Identity();
    t.linear() = rotation;
    t.translation() = origin;
    return t;
  }
};

// The ideal machine: its axis lines are placed by the pole alone, T(o), and carry no errors,
// so each joint moves the chain about its own line only. The products are those the real
// walk below would make with zero errors and T(o) bases, in the same order (bit-identical).
Frame walk_ideal_chain(const Model& model, const std::vector<int>& chain, const Joints& q,
                       ChainMotion* motion) noexcept {
  Frame parent;
  for (int i : chain) {
    const Axis& axis = model.axes[i];
    parent.origin += parent.rotation * axis.pole_mm;
    if (axis.type == AxisType::Linear) {
      if (motion) motion->linear.col(i) += parent.rotation * axis.direction;
      parent.origin += parent.rotation * (q[i] * axis.direction);
    } else {
      if (motion) {
        const Vector3d w_bed = parent.rotation * (axis.direction * tables::kDegToRad);
        motion->linear.col(i) -= w_bed.cross(parent.origin);
        motion->angular.col(i) += w_bed;
        motion->axis_line.col(i) = parent.rotation * axis.direction;
      }
      const Matrix3d turned = parent.rotation * rotation_about(axis.direction, q[i] * tables::kDegToRad);
      copy_by_columns(turned, parent.rotation);
    }
  }
  return parent;
}

// The real machine's pose alone: the products of walk_real_chain below without the motion,
// in the same order (bit-identical; a product with the identity, on a linear axis without
// tables, left out), with no rate of R(eps) and no slopes.
Frame walk_real_pose(const Model& model, const std::vector<int>& chain, const Joints& q) noexcept {
  Frame parent;
  AxisErrors err;
  for (int i : chain) {
    const Axis& axis = model.axes[i];
    const bool linear = axis.type == AxisType::Linear, has_errors = !axis.tables.empty();
    if (has_errors) axis_errors(model, i, q, err, false);
    Vector3d motion_origin = linear ? Vector3d(q[i] * axis.direction) : Vector3d::Zero();
    if (has_errors) motion_origin += err.delta_mm;
    const Matrix3d base_rotation = parent.rotation * axis.real_base.linear();
    parent.origin += parent.rotation * axis.real_base.translation();
    parent.origin += base_rotation * motion_origin;
    // Products written straight into the frame (noalias: no temporary copied over, whose
    // mixed scalar and packet stores the next product would wait for).
    if (linear) {  // R(eps)
      if (has_errors)
        parent.rotation.noalias() = base_rotation * rotation_xyz(err.eps_rad);
      else
        parent.rotation = base_rotation;
    } else {  // R(eps) Rot(u, q)
      const Matrix3d turn = rotation_about(axis.direction, q[i] * tables::kDegToRad);
      if (has_errors) {
        const Matrix3d motion_rotation = rotation_xyz(err.eps_rad) * turn;
        parent.rotation.noalias() = base_rotation * motion_rotation;
      } else {
        parent.rotation.noalias() = base_rotation * turn;
      }
    }
  }
  return parent;
}

// The real machine's pose and its motion (error slopes included).
Frame walk_real_chain(const Model& model, const std::vector<int>& chain, const Joints& q,
                      ChainMotion& motion) noexcept {
  Frame parent;
  AxisErrors err;
  for (int i : chain) {
    const Axis& axis = model.axes[i];
    const bool has_errors = !axis.tables.empty();
    if (has_errors) axis_errors(model, i, q, err, true);
    const Vector3d delta = has_errors ? err.delta_mm : Vector3d::Zero();
    Matrix3d r_eps = Matrix3d::Identity(), eps_rate = Matrix3d::Zero();
    if (has_errors) rotation_xyz(err.eps_rad, r_eps, eps_rate);
    // The motion part of A(q): T(q u) T(delta) R(eps) for a linear axis,
    // T(delta) R(eps) Rot(u, q) for a rotary one (model.md, One axis).
    const bool linear = axis.type == AxisType::Linear;
    const Vector3d motion_origin = linear ? Vector3d(q[i] * axis.direction + delta) : delta;
    const Matrix3d motion_rotation =
        linear ? r_eps : Matrix3d(r_eps * rotation_about(axis.direction, q[i] * tables::kDegToRad));
    // Frame after `base` (the fixed placement of the axis line), then the child frame.
    const Frame base = parent.then(axis.real_base);
    const Vector3d child_origin = base.origin + base.rotation * motion_origin;
    for (int j = 0; j < model.joint_count(); ++j) {
      if (!((axis.moved_by >> j) & 1u)) continue;
      Vector3d v = Vector3d::Zero(), w = Vector3d::Zero();
      if (has_errors) {
        v = err.slope.block<3, 1>(0, j);
        w = eps_rate * err.slope.block<3, 1>(3, j);
      }
      if (j == i) {
        if (linear)
          v += axis.direction;
        else
          w += r_eps * axis.direction * tables::kDegToRad;
      }
      const Vector3d w_bed = base.rotation * w;
      motion.linear.col(j) += base.rotation * v - w_bed.cross(child_origin);
      motion.angular.col(j) += w_bed;
    }
    if (!linear) motion.axis_line.col(i) = base.rotation * r_eps * axis.direction;
    parent.rotation.noalias() = base.rotation * motion_rotation;
    parent.origin = child_origin;
  }
  return parent;
}

// Walks one chain bed outward; returns bed_T_last and, if asked, the chain's motion.
Frame walk_chain(const Model& model, Machine machine, const std::vector<int>& chain, const Joints& q,
                 ChainMotion* motion) noexcept {
  if (machine == Machine::Ideal) return walk_ideal_chain(model, chain, q, motion);
  return motion ? walk_real_chain(model, chain, q, *motion) : walk_real_pose(model, chain, q);
}

// bed_T_tool (tip) and bed_T_part.
Frame tool_frame(const Model& model, Machine machine, const Joints& q, double tool_length_mm,
                 ChainMotion* motion) noexcept {
  const Isometry3d& spindle = machine == Machine::Real ? model.spindle.real : model.spindle.ideal;
  Frame tool = walk_chain(model, machine, model.tool_chain, q, motion).then(spindle);
  tool.origin += tool.rotation.col(2) * -tool_length_mm;  // the tip, L down the spindle's z
  return tool;
}

Frame part_frame(const Model& model, Machine machine, const Joints& q, ChainMotion* motion) noexcept {
  return walk_chain(model, machine, model.workpiece_chain, q, motion).then(model.fixture);
}

// The tool tip and direction (bed_T_tool's origin and z axis) seen in the part frame.
ToolPose in_part_frame(const Frame& tool, const Frame& part) {
  const auto part_R_bed = part.rotation.transpose();  // an expression: read where the product wrote it
  return {part_R_bed * (tool.origin - part.origin), part_R_bed * tool.rotation.col(2)};
}

ToolPose evaluate(const Model& model, Machine machine, const Joints& q, double tool_length_mm,
                  PoseDerivatives* d) noexcept {
  if (!d)  // no ChainMotion to fill: the common, cheaper case
    return in_part_frame(tool_frame(model, machine, q, tool_length_mm, nullptr),
                         part_frame(model, machine, q, nullptr));
  ChainMotion tool_motion, part_motion;
  const Frame tool = tool_frame(model, machine, q, tool_length_mm, &tool_motion);
  const Frame part = part_frame(model, machine, q, &part_motion);
  const Vector3d& tip_bed = tool.origin;
  const Vector3d k_bed = tool.rotation.col(2);
  const Matrix3d part_R_bed = part.rotation.transpose();
  // Relative motion of the tool against the part, seen in the part frame.
  for (int j = 0; j < model.joint_count(); ++j) {
    const Vector3d v_rel = (tool_motion.linear.col(j) + tool_motion.angular.col(j).cross(tip_bed)) -
                           (part_motion.linear.col(j) + part_motion.angular.col(j).cross(tip_bed));
    const Vector3d w_rel = tool_motion.angular.col(j) - part_motion.angular.col(j);
    d->tip.col(j) = part_R_bed * v_rel;
    d->direction.col(j) = part_R_bed * w_rel.cross(k_bed);
    d->axis_line.col(j) = part_R_bed * (tool_motion.axis_line.col(j) + part_motion.axis_line.col(j));
  }
  return in_part_frame(tool, part);
}

}  // namespace

void axis_errors(const Model& model, int joint, const Joints& q, AxisErrors& out,
                 bool with_slopes) noexcept {
  out.delta_mm.setZero();
  out.eps_rad.setZero();
  if (with_slopes) out.slope.setZero();
  tables::ErrorTable::Sample sample;
  for (int t : model.axes[joint].tables) {
    const BoundTable& bound = model.tables[t];
    const auto& grid = bound.table.grid();
    std::array<double, tables::ErrorTable::kMaxVariables> at{};
    for (std::size_t v = 0; v < grid.size(); ++v) at[v] = q[bound.joint[v]];
    bound.table.evaluate(at.data(), sample, with_slopes);
    const auto& columns = bound.table.columns();
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const int k = columns[c].symbol.component;
      (k < 3 ? out.delta_mm[k] : out.eps_rad[k - 3]) += sample.value[c];
      if (with_slopes)
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
  const Frame tool = tool_frame(model, machine, q, tool_length_mm, nullptr);
  return part_frame(model, machine, q, nullptr).isometry().inverse() * tool.isometry();
}

VolumetricError volumetric_error(const Model& model, const Joints& q,
                                 double tool_length_mm) noexcept {
  const ToolPose real = tool_pose(model, Machine::Real, q, tool_length_mm);
  const ToolPose ideal = tool_pose(model, Machine::Ideal, q, tool_length_mm);
  return {real.tip_mm - ideal.tip_mm, ideal.direction.cross(real.direction)};
}

}  // namespace vc::machine
