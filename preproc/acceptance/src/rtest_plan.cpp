#include "vc/acceptance/rtest_plan.hpp"

#include <cmath>
#include <stdexcept>

#include "vc/acceptance/diagonals.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/kinematics.hpp"

namespace vc::acceptance {
namespace {

// `steps` positions over the axis's travel: ends included, or a full turn less a step for a
// travel of 360 deg or more.
std::vector<double> positions(const machine::Axis& a, int steps) {
  const double span = a.travel_max - a.travel_min;
  const bool turn = span >= 360 - 1e-9;
  const double low = turn ? -180.0 : a.travel_min;
  const double step = turn ? 360.0 / steps : span / (steps - 1);
  std::vector<double> out;
  for (int k = 0; k < steps; ++k) out.push_back(low + k * step);
  return out;
}

bool inside(const machine::Model& model, const machine::Joints& q) {
  for (int j = 0; j < model.joint_count(); ++j) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
    if (q[j] < a.travel_min - 1e-9 || q[j] > a.travel_max + 1e-9) return false;
  }
  return true;
}

}  // namespace

RTestPlan plan_rtest(const machine::Model& model, const WorkVolume& volume, double nest_length_mm, int steps) {
  RTestPlan plan;
  std::vector<int> rotary;
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Rotary) rotary.push_back(j);
  if (rotary.size() != 2 || steps == 0) return plan;
  if (steps < 3) throw std::runtime_error("--rtest-steps: at least 3 poses per sequence (0: no R-test)");
  plan.sphere_joints_mm = volume.centre();
  const machine::Joints rest = joints_at(model, machine::Joints::Zero(model.joint_count()), plan.sphere_joints_mm);
  plan.sphere_mm = machine::tool_pose(model, machine::Machine::Ideal, rest, nest_length_mm).tip_mm;
  const machine::Axis &a1 = model.axes[static_cast<std::size_t>(rotary[0])],
                      &a2 = model.axes[static_cast<std::size_t>(rotary[1])];
  const double tilt = std::abs(a1.travel_min) > std::abs(a1.travel_max) ? a1.travel_min / 2 : a1.travel_max / 2;
  const auto sequence = [&](const std::string& name, const std::vector<std::pair<double, double>>& angles) {
    RTestSequence s;
    s.name = name;
    for (const auto& [first, second] : angles) {
      machine::Joints world(model.joint_count());
      world.setZero();
      world[model.joint_of('X')] = plan.sphere_mm.x();
      world[model.joint_of('Y')] = plan.sphere_mm.y();
      world[model.joint_of('Z')] = plan.sphere_mm.z();
      world[rotary[0]] = first;
      world[rotary[1]] = second;
      // The retract: the ideal machine's joints for a nest kRTestRetractMm longer on the same point.
      machine::Joints q, back;
      if (machine::nominal_inverse(model, machine::WorldConvention::Tcp, world, nest_length_mm, q) == machine::Status::Ok &&
          machine::nominal_inverse(model, machine::WorldConvention::Tcp, world, nest_length_mm + kRTestRetractMm, back) ==
              machine::Status::Ok &&
          inside(model, q) && inside(model, back)) {
        s.poses.push_back(q);
        s.retracts.push_back(back);
      } else {
        ++s.left_out;
      }
    }
    if (s.poses.size() < 3)
      throw std::runtime_error(name + ": fewer than 3 of its poses keep the joints in the travel with the sphere at X Y Z " +
                               std::to_string(plan.sphere_joints_mm.x()) + ", " + std::to_string(plan.sphere_joints_mm.y()) +
                               ", " + std::to_string(plan.sphere_joints_mm.z()) + " mm: another --volume");
    plan.sequences.push_back(s);
  };
  std::vector<std::pair<double, double>> first, second, both;
  for (double v : positions(a1, steps)) first.push_back({v, 0.0});
  for (double v : positions(a2, steps)) second.push_back({0.0, v}), both.push_back({tilt, v});
  const std::string l1(1, a1.letter), l2(1, a2.letter);
  sequence("rtest-" + l1, first);
  sequence("rtest-" + l2, second);
  sequence("rtest-" + l1 + l2, both);
  return plan;
}

}  // namespace vc::acceptance
