// The tests' own solver for "where must X, Y, Z stand": the linear joints that put a machine's tip
// (real or ideal, tool length L) on a point of the part frame, the other joints as given. A
// Newton with a finite-difference Jacobian, independent of the core's solvers (correct.hpp,
// kinematics.hpp), so that tests can check those against it.
#pragma once

#include <Eigen/Dense>

#include "vc/machine/forward.hpp"

namespace vc::test {

inline machine::Joints tip_on_point(const machine::Model& m, machine::Machine which, machine::Joints q,
                                    const Eigen::Vector3d& point, double length_mm) {
  const int lin[3] = {m.joint_of('X'), m.joint_of('Y'), m.joint_of('Z')};
  for (int step = 0; step < 20; ++step) {
    const Eigen::Vector3d r = machine::tool_pose(m, which, q, length_mm).tip_mm - point;
    if (r.norm() < 1e-12) break;
    Eigen::Matrix3d j;
    for (int i = 0; i < 3; ++i) {
      machine::Joints h = q;
      h[lin[i]] += 1e-3;
      j.col(i) = (machine::tool_pose(m, which, h, length_mm).tip_mm - point - r) / 1e-3;
    }
    const Eigen::Vector3d dq = j.lu().solve(-r);
    for (int i = 0; i < 3; ++i) q[lin[i]] += dq[i];
  }
  return q;
}

}  // namespace vc::test
