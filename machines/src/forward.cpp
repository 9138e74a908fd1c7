#include "vc/machine/forward.hpp"

#include <array>
#include <cmath>

#include "vc/machine/term_types.hpp"
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
// K^2 = u u^T - I written out (no matrix product). The angle in deg: a rotary joint's position.
Matrix3d rotation_about(const Vector3d& u, double angle_deg) {
  double s, c;
  sin_cos_deg(angle_deg, s, c);
  const double v = 1.0 - c;
  const double x = u.x(), y = u.y(), z = u.z();
  Matrix3d r;
  r << 1.0 + v * (x * x - 1.0), -s * z + v * (x * y), s * y + v * (x * z), s * z + v * (x * y), 1.0 + v * (y * y - 1.0),
      -s * x + v * (y * z), -s * y + v * (x * z), s * x + v * (y * z), 1.0 + v * (z * z - 1.0);
  return r;
}

// dst = src, column by column: a matrix a product has just written is read back the way
// it was written (a plain copy reads across its columns' stores and waits for them).
void copy_by_columns(const Matrix3d& src, Matrix3d& dst) noexcept {
  for (int c = 0; c < 3; ++c) dst.col(c) = src.col(c);
}

// The real placement of an axis line, T(o + d0) R(e0), with each location error scaled by its
// type's gain (term_types.hpp): the model's own where every type is on, else made in `scaled`.
const Isometry3d& real_base(const Axis& axis, const Conditions& conditions, Isometry3d& scaled) noexcept {
  if (conditions.all_types_on()) return axis.real_base;
  Vector3d d0, e0;
  for (int k = 0; k < 3; ++k) {
    d0[k] = type_gain(conditions, location_type(axis, k)) * axis.location_mm[k];
    e0[k] = type_gain(conditions, location_type(axis, k + 3)) * axis.location_rad[k];
  }
  scaled = line_placement(axis.pole_mm, d0, e0);
  return scaled;
}

// The spindle line's, its location errors L-SPEC.
const Isometry3d& real_spindle(const Spindle& spindle, const Conditions& conditions, Isometry3d& scaled) noexcept {
  const double gain = type_gain(conditions, BasicType::LSpec);
  if (gain == 1.0) return spindle.real;
  scaled = line_placement(spindle.gauge_point_mm, gain * spindle.location_mm, gain * spindle.location_rad);
  return scaled;
}

// A placement in the bed frame: bed_T_frame as rotation and origin (cheaper than 4x4 products).
struct Frame {
  Matrix3d rotation = Matrix3d::Identity();
  Vector3d origin = Vector3d::Zero();

  Frame then(const Isometry3d& t) const { return {rotation * t.linear(), origin + rotation * t.translation()}; }
  Isometry3d isometry() const {
    Isometry3d t = Isometry3d::Identity();
    t.linear() = rotation;
    t.translation() = origin;
    return t;
  }
};

// The ideal machine's frames: its axis lines are placed by the pole alone, T(o), and carry
// no errors.
Frame walk_ideal_chain(const Model& model, const std::vector<int>& chain, const Joints& q) noexcept {
  Frame parent;
  for (int i : chain) {
    const Axis& axis = model.axes[i];
    parent.origin += parent.rotation * axis.pole_mm;
    if (axis.type == AxisType::Linear) {
      parent.origin += parent.rotation * (q[i] * axis.direction);
    } else {
      const Matrix3d turned = parent.rotation * rotation_about(axis.direction, q[i]);
      copy_by_columns(turned, parent.rotation);
    }
  }
  return parent;
}

// The real machine's pose and its motion (error slopes included).
Frame walk_real_chain(const Model& model, const Conditions& conditions, const std::vector<int>& chain, const Joints& q,
                      ChainMotion& motion) noexcept {
  Frame parent;
  AxisErrors err;
  for (int i : chain) {
    const Axis& axis = model.axes[i];
    const bool has_errors = axis.has_component_errors();
    if (has_errors) axis_errors(model, conditions, i, q, err, true);
    const Vector3d delta = has_errors ? err.delta_mm : Vector3d::Zero();
    Matrix3d r_eps = Matrix3d::Identity(), eps_rate = Matrix3d::Zero();
    if (has_errors) rotation_xyz(err.eps_rad, r_eps, eps_rate);
    // The motion part of A(q): T(q u) T(delta) R(eps) for a linear axis,
    // T(delta) R(eps) Rot(u, q) for a rotary one (model.md, One axis).
    const bool linear = axis.type == AxisType::Linear;
    const Vector3d motion_origin = linear ? Vector3d(q[i] * axis.direction + delta) : delta;
    const Matrix3d motion_rotation = linear ? r_eps : Matrix3d(r_eps * rotation_about(axis.direction, q[i]));
    // Frame after `base` (the fixed placement of the axis line), then the child frame.
    Isometry3d scaled;
    const Frame base = parent.then(real_base(axis, conditions, scaled));
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

// Walks one chain bed outward; returns bed_T_last and, if asked, the chain's motion (the
// real machine's: the ideal machine's derivatives come from carried_ideal_rates()).
Frame walk_chain(const Model& model, const Conditions& conditions, Machine machine, const std::vector<int>& chain,
                 const Joints& q, ChainMotion* motion) noexcept {
  if (machine == Machine::Ideal) return walk_ideal_chain(model, chain, q);  // frames only
  if (motion) return walk_real_chain(model, conditions, chain, q, *motion);
  ChainMotion unused;  // the frames alone (part_T_tool): the pose goes through carried_pose()
  return walk_real_chain(model, conditions, chain, q, unused);
}

// bed_T_tool (tip) and bed_T_part.
Frame tool_frame(const Model& model, const Conditions& conditions, Machine machine, const Joints& q,
                 double tool_length_mm, ChainMotion* motion) noexcept {
  Isometry3d scaled;
  const Isometry3d& spindle =
      machine == Machine::Real ? real_spindle(model.spindle, conditions, scaled) : model.spindle.ideal;
  Frame tool = walk_chain(model, conditions, machine, model.tool_chain, q, motion).then(spindle);
  tool.origin += tool.rotation.col(2) * -tool_length_mm;  // the tip, L down the spindle's z
  return tool;
}

Frame part_frame(const Model& model, const Conditions& conditions, Machine machine, const Joints& q,
                 ChainMotion* motion) noexcept {
  return walk_chain(model, conditions, machine, model.workpiece_chain, q, motion).then(model.fixture);
}

// The tool tip and direction (bed_T_tool's origin and z axis) seen in the part frame.
ToolPose in_part_frame(const Frame& tool, const Frame& part) {
  const auto part_R_bed = part.rotation.transpose();  // an expression: read where the product wrote it
  return {part_R_bed * (tool.origin - part.origin), part_R_bed * tool.rotation.col(2)};
}

// The pose alone, without the chains' frames: the tool chain carries the tip and the tool
// direction from the spindle back to the bed (each placement applied to two vectors, not
// multiplied onto a frame), the workpiece chain takes them from the bed out to the part
// (inverse placements: transposed rotations). Per axis, four rotations of a vector instead of
// three frame products.
class CarriedPose {
 public:
  CarriedPose(const Vector3d& tip, const Vector3d& direction) : tip_(tip), direction_(direction) {}

  // Through an axis's placement A = T(base) T(motion) R(motion) (base: its line), outward in
  // (forward) or inward out (inverse).
  void through(const Model& model, const Conditions& conditions, Machine machine, int i, const Joints& q,
               bool inverse) {
    const Axis& axis = model.axes[i];
    const bool real = machine == Machine::Real;
    Vector3d motion_origin = axis.type == AxisType::Linear ? Vector3d(q[i] * axis.direction) : Vector3d::Zero();
    Matrix3d motion_rotation;
    bool turns = false;  // else the rotation is the identity
    if (real && axis.has_component_errors()) {
      AxisErrors err;
      axis_errors(model, conditions, i, q, err, false);
      motion_origin += err.delta_mm;
      motion_rotation = rotation_xyz(err.eps_rad);
      turns = true;
    }
    if (axis.type == AxisType::Rotary) {
      const Matrix3d turn = rotation_about(axis.direction, q[i]);
      if (turns)
        motion_rotation = motion_rotation * turn;
      else
        motion_rotation = turn;
      turns = true;
    }
    Isometry3d scaled;
    const Isometry3d& base = real ? real_base(axis, conditions, scaled) : axis.real_base;
    const Vector3d& base_origin = real ? base.translation() : axis.pole_mm;
    const bool base_turns = real && !axis.location_rad.isZero(0.0);  // R(e0), else the identity
    if (inverse) {
      to_child(base_origin, base.linear(), base_turns);
      to_child(motion_origin, motion_rotation, turns);
    } else {
      to_parent(motion_origin, motion_rotation, turns);
      to_parent(base_origin, base.linear(), base_turns);
    }
  }
  // p -> origin + rotation p (the child's point in the parent frame)
  void to_parent(const Vector3d& origin, const Matrix3d& rotation, bool turns) {
    if (turns) {
      tip_ = rotation * tip_;
      direction_ = rotation * direction_;
    }
    tip_ += origin;
  }
  // p -> rotation^T (p - origin)
  void to_child(const Vector3d& origin, const Matrix3d& rotation, bool turns) {
    tip_ -= origin;
    if (turns) {
      tip_ = rotation.transpose() * tip_;
      direction_ = rotation.transpose() * direction_;
    }
  }
  ToolPose pose() const { return {tip_, direction_}; }

 private:
  Vector3d tip_, direction_;
};

ToolPose carried_pose(const Model& model, const Conditions& conditions, Machine machine, const Joints& q,
                      double tool_length_mm) noexcept {
  Isometry3d scaled;
  const Isometry3d& spindle =
      machine == Machine::Real ? real_spindle(model.spindle, conditions, scaled) : model.spindle.ideal;
  const Vector3d direction = spindle.linear().col(2);
  CarriedPose carried(spindle.translation() - tool_length_mm * direction, direction);
  for (auto i = model.tool_chain.rbegin(); i != model.tool_chain.rend(); ++i)
    carried.through(model, conditions, machine, *i, q, false);
  for (int i : model.workpiece_chain) carried.through(model, conditions, machine, i, q, true);
  carried.to_child(model.fixture.translation(), model.fixture.linear(), true);
  return carried.pose();
}

// The ideal machine's pose and its derivatives, carried as CarriedPose carries the pose: its
// placements are the pole and the joint's own motion, T(o) T(q u) or T(o) Rot(u, q). Each
// joint's rates (of the tip and the tool direction per mm or per deg, and a rotary joint's
// line) are made where the joint acts, in its axis frame, and carried from there with the
// tip out to the part frame: no frames, no motion screws.
class CarriedIdealRates {
  static constexpr int kNone = -1;

 public:
  CarriedIdealRates(const Vector3d& tip, const Vector3d& direction) {
    v_.col(kTip) = tip;
    v_.col(kDirection) = direction;
    tip_rate_.fill(kNone);
    direction_rate_.fill(kNone);
    line_.fill(kNone);
  }

  // A tool-chain axis, child frame to parent (the tool moves with joint i).
  void tool_axis(const Axis& axis, int i, double q) {
    if (axis.type == AxisType::Linear) {
      v_.col(kTip) += q * axis.direction;
      tip_rate_[i] = add(axis.direction);
    } else {
      turn(rotation_about(axis.direction, q));
      add_rotary_rates(axis, i, 1.0);
    }
    v_.col(kTip) += axis.pole_mm;
  }
  // A workpiece-chain axis, parent frame to child (the part moves with joint i: the tip and
  // the direction move the other way in the part).
  void workpiece_axis(const Axis& axis, int i, double q) {
    v_.col(kTip) -= axis.pole_mm;
    if (axis.type == AxisType::Linear) {
      v_.col(kTip) -= q * axis.direction;
      tip_rate_[i] = add(-axis.direction);
    } else {
      turn(rotation_about(axis.direction, q).transpose());
      add_rotary_rates(axis, i, -1.0);
    }
  }
  // The fixture, last workpiece-chain frame to the part.
  void fixture(const Isometry3d& fixture) {
    v_.col(kTip) -= fixture.translation();
    if (!(fixture.linear().array() == Matrix3d::Identity().array()).all()) turn(fixture.linear().transpose());
  }

  ToolPose pose(int joints, PoseDerivatives& d) const {
    for (int j = 0; j < joints; ++j) {
      d.tip.col(j) = column(tip_rate_[j]);
      d.direction.col(j) = column(direction_rate_[j]);
      d.axis_line.col(j) = column(line_[j]);
    }
    return {v_.col(kTip), v_.col(kDirection)};
  }

 private:
  static constexpr int kTip = 0, kDirection = 1;
  // Rotary joint i about its line through this frame's origin: the tip turns by w x tip, the
  // direction by w x direction, w the line per deg (sign -1: the part turns).
  void add_rotary_rates(const Axis& axis, int i, double sign) {
    const Vector3d w = (sign * tables::kDegToRad) * axis.direction;
    tip_rate_[i] = add(w.cross(v_.col(kTip)));
    direction_rate_[i] = add(w.cross(v_.col(kDirection)));
    line_[i] = add(axis.direction);
  }
  int add(const Vector3d& v) {
    v_.col(used_) = v;
    return used_++;
  }
  void turn(const Matrix3d& rotation) {
    for (int c = 0; c < used_; ++c) v_.col(c) = rotation * v_.col(c);
  }
  Vector3d column(int c) const { return c == kNone ? Vector3d::Zero() : Vector3d(v_.col(c)); }

  // The tip, the direction, then the rates and lines in the order the joints add them.
  Eigen::Matrix<double, 3, 2 + 3 * kMaxAxes> v_;
  int used_ = 2;
  std::array<int, kMaxAxes> tip_rate_, direction_rate_, line_;  // column of joint j, or kNone
};

ToolPose carried_ideal_rates(const Model& model, const Joints& q, double tool_length_mm, PoseDerivatives& d) noexcept {
  const Vector3d direction = model.spindle.ideal.linear().col(2);
  CarriedIdealRates carried(model.spindle.ideal.translation() - tool_length_mm * direction, direction);
  for (auto i = model.tool_chain.rbegin(); i != model.tool_chain.rend(); ++i)
    carried.tool_axis(model.axes[*i], *i, q[*i]);
  for (int i : model.workpiece_chain) carried.workpiece_axis(model.axes[i], i, q[i]);
  carried.fixture(model.fixture);
  return carried.pose(model.joint_count(), d);
}

ToolPose evaluate(const Model& model, const Conditions& conditions, Machine machine, const Joints& q,
                  double tool_length_mm, PoseDerivatives* d) noexcept {
  if (!d) return carried_pose(model, conditions, machine, q, tool_length_mm);
  if (machine == Machine::Ideal) return carried_ideal_rates(model, q, tool_length_mm, *d);
  ChainMotion tool_motion, part_motion;
  const Frame tool = tool_frame(model, conditions, machine, q, tool_length_mm, &tool_motion);
  const Frame part = part_frame(model, conditions, machine, q, &part_motion);
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

void axis_errors(const Model& model, const Conditions& conditions, int joint, const Joints& q, AxisErrors& out,
                 bool with_slopes) noexcept {
  std::array<double, tables::ErrorTable::kMaxColumns> sum{};  // components X Y Z A B C
  if (with_slopes) out.slope.setZero();
  tables::ErrorTable::Sample sample;
  const Axis& axis = model.axes[joint];
  const bool switched = !conditions.all_types_on();  // some type off or ramping: columns scaled
  for (int t : axis.tables) {
    const BoundTable& bound = model.tables[t];
    const auto& grid = bound.table.grid();
    // Grid variables: joint positions, or temperatures at their current (volkins: filtered) value.
    std::array<double, tables::ErrorTable::kMaxVariables> at{};
    for (std::size_t v = 0; v < grid.size(); ++v)
      at[v] = bound.joint[v] >= 0 ? q[bound.joint[v]]
                                  : conditions.temperature_degC[static_cast<std::size_t>(bound.input[v])];
    if (!with_slopes && !switched) {  // the pose alone: the table adds its values by component
      bound.table.add_components(at.data(), sum);
      continue;
    }
    bound.table.evaluate(at.data(), sample, with_slopes);
    const auto& columns = bound.table.columns();
    // A cross-axis table is switched by L-SPEC (R-SPEC) too (term_types.hpp).
    const double cross =
        switched && crosses_axes(model, bound, axis)
            ? type_gain(conditions, axis.type == AxisType::Linear ? BasicType::LSpec : BasicType::RSpec)
            : 1.0;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const int component = columns[c].symbol.component;
      const double gain = switched ? cross * type_gain(conditions, column_type(axis, component)) : 1.0;
      sum[static_cast<std::size_t>(component)] += gain * sample.value[c];
      if (with_slopes)
        for (std::size_t v = 0; v < grid.size(); ++v)
          if (bound.joint[v] >= 0) out.slope(component, bound.joint[v]) += gain * sample.slope[c][v];
    }
  }
  // Thermal expansion of a linear axis: it travels (1 + strain) times as far from its reference
  // point, along its own direction u (a table axis then carries the part the other way).
  const LinearThermal& thermal = axis.thermal;
  if (thermal.input >= 0) {
    const auto input = static_cast<std::size_t>(thermal.input);
    const double strain =
        thermal.expansion_per_K * (conditions.temperature_degC[input] - model.temperatures[input].reference_degC);
    const Eigen::Vector3d& u = axis.direction;
    for (int c = 0; c < 3; ++c) {
      sum[static_cast<std::size_t>(c)] += strain * (q[joint] - thermal.reference_mm) * u[c];
      if (with_slopes) out.slope(c, joint) += strain * u[c];
    }
  }
  out.delta_mm = {sum[0], sum[1], sum[2]};
  out.eps_rad = {sum[3], sum[4], sum[5]};
}

ToolPose tool_pose(const Model& model, const Conditions& conditions, Machine machine, const Joints& q,
                   double tool_length_mm) noexcept {
  return evaluate(model, conditions, machine, q, tool_length_mm, nullptr);
}

ToolPose tool_pose(const Model& model, const Conditions& conditions, Machine machine, const Joints& q,
                   double tool_length_mm, PoseDerivatives& derivatives) noexcept {
  return evaluate(model, conditions, machine, q, tool_length_mm, &derivatives);
}

Isometry3d part_T_tool(const Model& model, const Conditions& conditions, Machine machine, const Joints& q,
                       double tool_length_mm) noexcept {
  const Frame tool = tool_frame(model, conditions, machine, q, tool_length_mm, nullptr);
  return part_frame(model, conditions, machine, q, nullptr).isometry().inverse() * tool.isometry();
}

VolumetricError volumetric_error(const Model& model, const Conditions& conditions, const Joints& q,
                                 double tool_length_mm) noexcept {
  const ToolPose real = tool_pose(model, conditions, Machine::Real, q, tool_length_mm);
  const ToolPose ideal = tool_pose(model, conditions, Machine::Ideal, q, tool_length_mm);
  return {real.tip_mm - ideal.tip_mm, ideal.direction.cross(real.direction)};
}

}  // namespace vc::machine
