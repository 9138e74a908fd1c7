// Points of a move in the machine: LinuxCNC's world coordinates in joint order, the joints
// of the ideal machine there, and its tool tip (shared by the simulation and the path shift).
#pragma once

#include <string>

#include "vc/interpreter/move.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/predistort/joint_axes.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::shop {

class ProgramPoints {
 public:
  // `file`: the program, for messages.
  ProgramPoints(const machine::Model& model, machine::WorldConvention world, std::string file)
      : model_(model), world_(world), file_(std::move(file)), axes_(model) {}

  machine::Joints world(const interpreter::Move& m, const interpreter::Position& program) const {
    return axes_.joints_of(m.frame.world(program));
  }
  // Throws vc::LoadError at the move's line if no joint position reaches the point.
  machine::Joints nominal(const interpreter::Move& m, const machine::Joints& world) const {
    machine::Joints q;
    if (machine::nominal_inverse(model_, world_, world, model_.correction_length(m.tool_offset_mm), q) !=
        machine::Status::Ok)
      throw LoadError({file_, m.line}, "no joint position reaches this point of the move");
    return q;
  }
  Eigen::Vector3d ideal_tip(const interpreter::Move& m, const interpreter::Position& program) const {
    return machine::tool_pose(model_, machine::Machine::Ideal, nominal(m, world(m, program)),
                              model_.correction_length(m.tool_offset_mm))
        .tip_mm;
  }
  // The ideal machine's tool frame in the part frame (z: the tool axis, tip into the spindle).
  Eigen::Isometry3d ideal_pose(const interpreter::Move& m, const interpreter::Position& program) const {
    return machine::part_T_tool(model_, machine::Machine::Ideal, nominal(m, world(m, program)),
                                model_.correction_length(m.tool_offset_mm));
  }

 private:
  const machine::Model& model_;
  machine::WorldConvention world_;
  std::string file_;
  predistort::JointAxes axes_;
};

}  // namespace vc::shop
