// Forward model: the pose of the tool relative to the part for nominal joint positions q.
//
//     F_tool(q) = A_1(q_1) * ... * A_n(q_n) * T_spindle * T(0, 0, -L)     (tool chain)
//     F_part(q) = A_1(q_1) * ... * A_m(q_m) * T_fixture                     (workpiece chain)
//     P(q)      = F_part(q)^-1 * F_tool(q)                                  (model.md)
//
// The real machine evaluates every error table and location error; the ideal machine is the
// same chain with every error zero. All functions here are real-time safe: no allocation, no
// locks, no exceptions, a fixed amount of work.
#pragma once

#include "vc/machine/model.hpp"

namespace vc::machine {

enum class Machine { Real, Ideal };

// Tool tip and tool axis (unit vector pointing from the tip into the spindle, P * e_z),
// both in the part frame.
struct ToolPose {
  Eigen::Vector3d tip_mm;
  Eigen::Vector3d direction;
};

// Derivatives of a ToolPose by each joint (per mm or per deg), including the slopes of the
// error tables, and the rotary axis lines in the part frame.
struct PoseDerivatives {
  Eigen::Matrix<double, 3, kMaxAxes> tip;        // d tip_mm / d q_j
  Eigen::Matrix<double, 3, kMaxAxes> direction;  // d direction / d q_j
  Eigen::Matrix<double, 3, kMaxAxes> axis_line;  // rotary joint j: its line direction
};

// Volumetric error at q (model.md): position e_p = pos P(q) - pos P'(q) in the part frame,
// tool direction e_k = k' x k (rad).
struct VolumetricError {
  Eigen::Vector3d position_mm;
  Eigen::Vector3d direction_rad;
};

// Each at the machine's `conditions` (its temperatures: model.hpp); the forms without them at
// the machine file's (Model::reference_conditions()).
ToolPose tool_pose(const Model& model, const Conditions& conditions, Machine machine, const Joints& q,
                   double tool_length_mm) noexcept;
ToolPose tool_pose(const Model& model, const Conditions& conditions, Machine machine, const Joints& q,
                   double tool_length_mm, PoseDerivatives& derivatives) noexcept;

// part_T_tool = F_part^-1 * F_tool, the full pose (tool frame in the part frame).
Eigen::Isometry3d part_T_tool(const Model& model, const Conditions& conditions, Machine machine, const Joints& q,
                              double tool_length_mm) noexcept;

VolumetricError volumetric_error(const Model& model, const Conditions& conditions, const Joints& q,
                                 double tool_length_mm) noexcept;

inline ToolPose tool_pose(const Model& model, Machine machine, const Joints& q, double tool_length_mm) noexcept {
  return tool_pose(model, model.reference_conditions(), machine, q, tool_length_mm);
}
inline ToolPose tool_pose(const Model& model, Machine machine, const Joints& q, double tool_length_mm,
                          PoseDerivatives& derivatives) noexcept {
  return tool_pose(model, model.reference_conditions(), machine, q, tool_length_mm, derivatives);
}
inline Eigen::Isometry3d part_T_tool(const Model& model, Machine machine, const Joints& q,
                                     double tool_length_mm) noexcept {
  return part_T_tool(model, model.reference_conditions(), machine, q, tool_length_mm);
}
inline VolumetricError volumetric_error(const Model& model, const Joints& q, double tool_length_mm) noexcept {
  return volumetric_error(model, model.reference_conditions(), q, tool_length_mm);
}

// Component errors of one axis at q (the sum of its tables): delta (mm), eps (rad) and, if
// asked, their slopes by each joint (per mm or per deg).
struct AxisErrors {
  Eigen::Vector3d delta_mm;
  Eigen::Vector3d eps_rad;
  Eigen::Matrix<double, 6, kMaxAxes> slope;  // rows: delta x y z, eps a b c
};
void axis_errors(const Model& model, const Conditions& conditions, int joint, const Joints& q, AxisErrors& out,
                 bool with_slopes = true) noexcept;
inline void axis_errors(const Model& model, int joint, const Joints& q, AxisErrors& out,
                        bool with_slopes = true) noexcept {
  axis_errors(model, model.reference_conditions(), joint, q, out, with_slopes);
}

}  // namespace vc::machine
