// The R-test of a machine with two rotary axes (ISO 10791-6; ISO 230-1 11.3.5.3): a precision
// sphere on the table, a nest of three displacement sensors in the spindle (L below the gauge
// point: the nest's centre), the sphere's centre followed through rotary moves. Three sequences,
// each a set of poses at which the ideal machine puts the nest's centre on the sphere's:
//   rtest-A1: the first rotary axis alone over its travel (the second at 0);
//   rtest-A2: the second alone over its travel (the first at 0);
//   rtest-A1A2: both, the first at half its travel's larger end, the second over its travel
// (A1, A2 named by the axes' letters: rtest-B, rtest-C, rtest-BC). `steps` poses per
// sequence, evenly over the travel (a continuous axis: a full turn less one step). A pose whose
// joints leave the travel is left out and said so on the sheet. The joints are the nominal
// machine's (axes world: what the program commands); volkins corrects them when compensating.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "vc/acceptance/work_volume.hpp"
#include "vc/machine/model.hpp"

namespace vc::acceptance {

// How far the program backs the nest off the sphere along the tool between poses.
inline constexpr double kRTestRetractMm = 50;

struct RTestSequence {
  std::string name;                     // rtest-B, rtest-C, rtest-BC
  std::vector<machine::Joints> poses;     // commanded joints (mm, deg): the nest on the sphere
  std::vector<machine::Joints> retracts;  // the same pose, the nest kRTestRetractMm back along the tool
  int left_out = 0;                     // poses outside the travel
};

struct RTestPlan {
  Eigen::Vector3d sphere_joints_mm;  // X, Y, Z where the nest sits on the sphere, rotary axes at 0
  Eigen::Vector3d sphere_mm;         // the sphere's centre in the part frame (the ideal machine)
  std::vector<RTestSequence> sequences;
  bool empty() const { return sequences.empty(); }
};

// No R-test (empty) for a machine without exactly two rotary axes, or `steps` 0. Throws
// std::runtime_error for fewer than 3 steps or a sphere position the nest cannot reach.
RTestPlan plan_rtest(const machine::Model& model, const WorkVolume& volume, double nest_length_mm, int steps);

}  // namespace vc::acceptance
