#include "vc/fit_tables/usual_practice.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vc/machine/deviations.hpp"
#include "vc/machine/forward.hpp"

namespace vc::fit_tables {
namespace {

// The output joint's correction that cancels `only`'s tip error at q (mm or deg).
double cancelling_correction(const machine::Model& only, const machine::Joints& q, int output, double tool_length_mm) {
  const Eigen::Vector3d target = machine::tool_pose(only, machine::Machine::Ideal, q, tool_length_mm).tip_mm;
  double c = 0.0;
  machine::PoseDerivatives d;
  for (int it = 0; it < 8; ++it) {
    machine::Joints moved = q;
    moved[output] += c;
    const Eigen::Vector3d r =
        machine::tool_pose(only, machine::Machine::Real, moved, tool_length_mm, d).tip_mm - target;
    const Eigen::Vector3d column = d.tip.col(output);
    if (column.squaredNorm() < 1e-12)
      throw std::runtime_error("the usual practice: joint " +
                               std::string(1, only.axes[static_cast<std::size_t>(output)].letter) +
                               " does not move the tool tip at the reference pose");
    const double step = -column.dot(r) / column.squaredNorm();
    c += step;
    if (std::abs(step) < 1e-13) break;
  }
  return c;
}

}  // namespace

machine::Joints reference_pose(const machine::Model& model, int output) {
  machine::Joints best = reference_pose(model);
  if (model.axes[static_cast<std::size_t>(output)].type == machine::AxisType::Linear) return best;
  // A rotary joint moves the tip in proportion to its distance from the axis line: of the
  // linear joints at 1/4, 1/2, 3/4 of their travels, the pose where it moves the tip most.
  std::vector<int> linear;
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Linear) linear.push_back(j);
  double largest = -1;
  const double fractions[3] = {0.5, 0.25, 0.75};
  machine::PoseDerivatives d;
  std::vector<int> level(linear.size(), 0);
  while (true) {
    machine::Joints q = reference_pose(model);
    for (std::size_t k = 0; k < linear.size(); ++k) {
      const machine::Axis& a = model.axes[static_cast<std::size_t>(linear[k])];
      q[linear[k]] = a.travel_min + (a.travel_max - a.travel_min) * fractions[level[k]];
    }
    machine::tool_pose(model, machine::Machine::Ideal, q, model.tool_length_mm, d);
    const double moves = d.tip.col(output).norm();
    if (moves > largest + 1e-9) {  // (the middle pose first: kept unless another is better)
      largest = moves;
      best = q;
    }
    std::size_t k = 0;
    while (k < level.size() && ++level[k] == 3) level[k++] = 0;
    if (k == level.size()) break;
  }
  return best;
}

machine::Joints reference_pose(const machine::Model& model) {
  machine::Joints q(model.joint_count());
  for (int j = 0; j < model.joint_count(); ++j) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
    q[j] = a.type == machine::AxisType::Linear ? 0.5 * (a.travel_min + a.travel_max)
                                               : std::clamp(0.0, a.travel_min, a.travel_max);
  }
  return q;
}

Eigen::VectorXd usual_practice(const machine::Model& model, const TableSet& set) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(set.unknowns);
  const double length = model.tool_length_mm;
  for (const Table& t : set.tables) {
    if (t.own_deviations.empty()) continue;  // no deviation of its own in the model's terms: left at 0
    const machine::Joints reference = reference_pose(model, t.output);
    const machine::Model only = machine::keep_only(model, t.own_deviations);
    if (t.kind == TableKind::Squareness) {
      // The slope of the cancelling corrections over the input's travel.
      const machine::Axis& in = model.axes[static_cast<std::size_t>(t.input)];
      const int samples = 11;
      double sp = 0, sc = 0, spp = 0, spc = 0;
      for (int k = 0; k < samples; ++k) {
        machine::Joints q = reference;
        q[t.input] = in.travel_min + (in.travel_max - in.travel_min) * k / (samples - 1);
        const double c = cancelling_correction(only, q, t.output, length);
        sp += q[t.input];
        sc += c;
        spp += q[t.input] * q[t.input];
        spc += q[t.input] * c;
      }
      x[t.first_unknown] = (samples * spc - sp * sc) / (samples * spp - sp * sp);
      continue;
    }
    for (int k = 0; k < t.unknowns(); ++k) {
      machine::Joints q = reference;
      q[t.input] = t.nodes[static_cast<std::size_t>(k)];
      x[t.first_unknown + k] = cancelling_correction(only, q, t.output, length);
    }
  }
  return x;
}

}  // namespace vc::fit_tables
