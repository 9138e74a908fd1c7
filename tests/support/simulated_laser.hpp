// A simulated laser on a line, for the tests (issue 48): what an instrument reads on a model,
// written out here and not identify's code path (preproc/identify/README.md, "What each
// instrument reads"): the tool-side optic against the part, real machine against ideal, part
// frame; along the axis's own ideal motion for its positioning (readings grow with +X, +C),
// along the part frame's axes otherwise; rotations from the rotation matrices' skew parts.
#pragma once

#include <Eigen/Geometry>
#include <cctype>
#include <fstream>
#include <string>
#include <vector>

#include "vc/machine/forward.hpp"
#include "vc/machine/model.hpp"
#include "vc/tables/symbols.hpp"

namespace vc::test {

struct LaserLine {
  int joint;
  tables::ErrorSymbol error;
  machine::Joints at;     // where every joint stands (the moving one's value unused)
  Eigen::Vector3d point;  // the tool-side optic in the spindle frame, from the gauge point
};

// The small rotation of `a` against `b`: the skew part of a b^T (first order, exact to 1e-10
// relative for micro-radians).
inline Eigen::Vector3d small_turn(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::Matrix3d r = a * b.transpose();
  return 0.5 * Eigen::Vector3d(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1));
}

// What the instrument reads on `model` at `target`: the optic's displacement against the part
// (translations) or the tool's turn against it (rotations), real against ideal, part frame.
inline double simulated_reading(const machine::Model& model, const LaserLine& line, double target) {
  machine::Joints q = line.at;
  q[line.joint] = target;
  const auto at = [&](machine::Machine m, double shift) {
    machine::Joints p = q;
    p[line.joint] += shift;
    return machine::part_T_tool(model, m, p, 0.0);
  };
  const Eigen::Isometry3d real = at(machine::Machine::Real, 0), ideal = at(machine::Machine::Ideal, 0);
  const bool translation = line.error.component < 3;
  const Eigen::Vector3d e =
      translation ? Eigen::Vector3d(real * line.point - ideal * line.point) : small_turn(real.linear(), ideal.linear());
  Eigen::Vector3d along = Eigen::Vector3d::Unit(line.error.component % 3);
  const char own = model.axes[static_cast<std::size_t>(line.joint)].letter;
  if (std::string("XYZABC")[static_cast<std::size_t>(line.error.component)] == own) {
    const Eigen::Isometry3d before = at(machine::Machine::Ideal, -0.01), after = at(machine::Machine::Ideal, 0.01);
    along = (translation ? Eigen::Vector3d(after * line.point - before * line.point)
                         : small_turn(after.linear(), before.linear()))
                .normalized();
  }
  return along.dot(e);
}

// The long layout of `volcomp identify laser`, `runs` runs each way with no noise and no
// reversal, with the runs' "# at:" and "# tool_point_mm:".
inline void write_laser_runs(const std::string& path, const machine::Model& model, const LaserLine& line,
                             const std::vector<double>& targets, int runs = 5) {
  std::ofstream out(path);
  out << "# instrument: simulated (tests/support/simulated_laser.hpp)\n# at: ";
  for (int j = 0; j < model.joint_count(); ++j)
    out << (j ? ", " : "") << static_cast<char>(std::tolower(model.axes[static_cast<std::size_t>(j)].letter)) << "="
        << line.at[j];
  out << "\n# tool_point_mm: " << line.point.x() << ", " << line.point.y() << ", " << line.point.z() << "\n";
  const bool rotary = model.axes[static_cast<std::size_t>(line.joint)].type == machine::AxisType::Rotary;
  const bool length = line.error.component < 3;
  out << "target[" << (rotary ? "deg" : "mm") << "],run,direction,deviation[" << (length ? "um" : "urad") << "]\n";
  out.precision(12);
  for (int r = 1; r <= runs; ++r)
    for (const char* direction : {"+", "-"})
      for (std::size_t k = 0; k < targets.size(); ++k) {
        const double t = targets[direction[0] == '+' ? k : targets.size() - 1 - k];
        out << t << "," << r << "," << direction << "," << simulated_reading(model, line, t) * (length ? 1e3 : 1e6)
            << "\n";
      }
}

}  // namespace vc::test
