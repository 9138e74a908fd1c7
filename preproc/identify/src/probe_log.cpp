#include "vc/identify/probe_log.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "vc/machine/forward.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::identify {

ProbeLog read_probe_log(const std::string& path, const machine::Model& model, double tolerance_mm) {
  std::ifstream in(path);
  if (!in) throw LoadError({path}, "cannot open the probe log");
  ProbeLog log;
  int rotary = 0;
  for (const machine::Axis& a : model.axes) rotary += a.type == machine::AxisType::Rotary;
  const int x = model.joint_of('X'), y = model.joint_of('Y'), z = model.joint_of('Z');
  struct Pose {
    std::vector<double> rotary;
    std::vector<Eigen::Vector3d> points;
    int line = 0;
  };
  std::map<int, Pose> poses;
  int number = 0;
  bool header = false;
  for (std::string text; std::getline(in, text);) {
    ++number;
    std::istringstream words(text);
    std::string first;
    if (!(words >> first)) continue;
    if (first == "#") {
      std::string key, axes;
      while (words >> key) {
        if (key == "sphere_diameter_mm")
          words >> log.sphere_diameter_mm;
        else if (key == "ball_diameter_mm")
          words >> log.ball_diameter_mm;
        else if (key == "probe_length_mm")
          words >> log.probe_length_mm;
        else if (key == "axes")
          words >> axes;
      }
      if (!axes.empty() && axes != model.coordinates())
        throw LoadError({path, number}, "the log is of a machine with axes " + axes + ", " + model.info.name + " has " +
                                            model.coordinates() + ": another machine?");
      header = true;
      continue;
    }
    if (first != "POINT")
      throw LoadError({path, number}, "expected a POINT line (or the '# volcomp probe log' header)");
    if (!header)
      throw LoadError({path, number}, "no '# volcomp probe log' header before the points (not a probe-plan log?)");
    int pose = 0;
    std::vector<double> values;
    double v;
    words >> pose;
    while (words >> v) values.push_back(v);
    if (!words.eof() || pose < 1 || static_cast<int>(values.size()) != rotary + 6)
      throw LoadError({path, number}, "a POINT line is: pose, " + std::to_string(rotary) +
                                          " rotary positions, the trip's X Y Z (#5061-#5063), G54's X Y Z offsets");
    Pose& p = poses[pose];
    const std::vector<double> at(values.begin(), values.begin() + rotary);
    if (p.points.empty()) {
      p.rotary = at;
      p.line = number;
    } else if (p.rotary != at) {
      throw LoadError({path, number}, "pose " + std::to_string(pose) + " changes its rotary positions");
    }
    const auto k = static_cast<std::size_t>(rotary);
    p.points.emplace_back(values[k] + values[k + 3], values[k + 1] + values[k + 4], values[k + 2] + values[k + 5]);
  }
  if (!(log.sphere_diameter_mm > 0) || !(log.ball_diameter_mm >= 0))
    throw LoadError({path}, "the header gives no sphere_diameter_mm and ball_diameter_mm");
  // A calibration sphere and a probe ball are millimetres to a few centimetres: a larger number
  // is a typo (or metres), and it would send the sphere fit far outside the machine.
  constexpr double kLargestDiameterMm = 1000.0;
  if (log.sphere_diameter_mm > kLargestDiameterMm || log.ball_diameter_mm > kLargestDiameterMm)
    throw LoadError({path}, "sphere_diameter_mm " + std::to_string(log.sphere_diameter_mm) + " or ball_diameter_mm " +
                                std::to_string(log.ball_diameter_mm) + " is not a sphere's diameter (at most 1000 mm)");
  const double radius = (log.sphere_diameter_mm + log.ball_diameter_mm) / 2;

  const double length = log.probe_length_mm > 0 ? log.probe_length_mm : model.tool_length_mm;
  const auto joints_at = [&](const Pose& p, const Eigen::Vector3d& xyz) {
    machine::Joints q = machine::Joints::Zero(model.joint_count());
    q[x] = xyz.x(), q[y] = xyz.y(), q[z] = xyz.z();
    int r_index = 0;
    for (int j = 0; j < model.joint_count(); ++j)
      if (model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Rotary)
        q[j] = p.rotary[static_cast<std::size_t>(r_index++)];
    return q;
  };
  const auto tip = [&](const Pose& p, const Eigen::Vector3d& xyz) {
    return machine::tool_pose(model, machine::Machine::Real, joints_at(p, xyz), length).tip_mm;
  };

  for (const auto& [index, p] : poses) {
    if (p.points.size() < 4)
      throw LoadError({path, p.line}, "pose " + std::to_string(index) + " has " + std::to_string(p.points.size()) +
                                          " points: a sphere of known radius needs 4 (the plan probes 5)");
    // The sphere is round where the ball touched it, in the part frame, not in the joints: the
    // trips are carried through the model's real machine (its linear axes' errors bend a 27 mm
    // sphere by up to a few um in joint space), the sphere of the known radius fitted there
    // (Gauss-Newton), and its centre carried back to the joints. The rotary axes' location
    // errors move the trips and the centre rigidly at a pose, so the joints found do not
    // depend on them (they are what identify_from_sphere fits).
    std::vector<Eigen::Vector3d> at;
    for (const Eigen::Vector3d& q : p.points) at.push_back(tip(p, q));
    // Start: below the points' mean in the joints (the plan probes the top and the equator).
    Eigen::Vector3d joint_mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& q : p.points) joint_mean += q;
    joint_mean /= static_cast<double>(p.points.size());
    joint_mean.z() -= radius / 2;
    Eigen::Vector3d c = tip(p, joint_mean);
    Eigen::VectorXd r(static_cast<Eigen::Index>(at.size()));
    for (int step = 0; step < 30; ++step) {
      Eigen::MatrixXd j(static_cast<Eigen::Index>(at.size()), 3);
      for (std::size_t i = 0; i < at.size(); ++i) {
        const Eigen::Vector3d d = at[i] - c;
        r[static_cast<Eigen::Index>(i)] = d.norm() - radius;
        j.row(static_cast<Eigen::Index>(i)) = -d.transpose() / d.norm();
      }
      const Eigen::Vector3d dc = j.colPivHouseholderQr().solve(-r);
      c += dc;
      if (dc.norm() < 1e-10) break;
    }
    if (!c.allFinite())
      throw LoadError({path, p.line}, "pose " + std::to_string(index) + ": no sphere of diameter " +
                                          std::to_string(log.sphere_diameter_mm) + " (+ the ball) fits its points");
    for (std::size_t i = 0; i < at.size(); ++i) {
      const double off = std::abs((at[i] - c).norm() - radius);
      log.largest_residual_um = std::max(log.largest_residual_um, off * 1e3);
      if (off > tolerance_mm)
        throw LoadError({path, p.line},
                        "pose " + std::to_string(index) + ": a point lies " + std::to_string(off * 1e3) +
                            " um off the sphere of diameter " + std::to_string(log.sphere_diameter_mm) +
                            " (+ the ball) through the others: a wrong diameter, another sphere or a bad trip?");
    }
    // The joints X Y Z that put the model's real tip on the centre (Newton on the linear axes).
    Eigen::Vector3d xyz = joint_mean;
    for (int step = 0; step < 20; ++step) {
      const Eigen::Vector3d rr = tip(p, xyz) - c;
      if (rr.norm() < 1e-12) break;
      Eigen::Matrix3d jac;
      for (int i = 0; i < 3; ++i) {
        Eigen::Vector3d h = xyz;
        h[i] += 1e-3;
        jac.col(i) = (tip(p, h) - c - rr) / 1e-3;
      }
      xyz -= jac.lu().solve(rr);
    }
    SpherePose s;
    s.line = p.line;
    s.joints = joints_at(p, xyz);
    log.centres.push_back(s);
  }
  if (log.centres.empty()) throw LoadError({path}, "no points");
  return log;
}

}  // namespace vc::identify
