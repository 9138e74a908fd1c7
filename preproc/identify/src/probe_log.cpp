#include "vc/identify/probe_log.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

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
        if (key == "sphere_diameter_mm") words >> log.sphere_diameter_mm;
        else if (key == "ball_diameter_mm") words >> log.ball_diameter_mm;
        else if (key == "probe_length_mm") words >> log.probe_length_mm;
        else if (key == "axes") words >> axes;
      }
      if (!axes.empty() && axes != model.coordinates())
        throw LoadError({path, number}, "the log is of a machine with axes " + axes + ", " + model.info.name + " has " +
                                            model.coordinates() + ": another machine?");
      header = true;
      continue;
    }
    if (first != "POINT") throw LoadError({path, number}, "expected a POINT line (or the '# volcomp probe log' header)");
    if (!header) throw LoadError({path, number}, "no '# volcomp probe log' header before the points (not a probe-plan log?)");
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
  const double radius = (log.sphere_diameter_mm + log.ball_diameter_mm) / 2;

  for (const auto& [index, p] : poses) {
    if (p.points.size() < 4)
      throw LoadError({path, p.line}, "pose " + std::to_string(index) + " has " + std::to_string(p.points.size()) +
                                          " points: a sphere of known radius needs 4 (the plan probes 5)");
    // The centre of the sphere of the known radius through the points (Gauss-Newton).
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& q : p.points) c += q;
    c /= static_cast<double>(p.points.size());
    c.z() -= radius / 2;  // the plan's points are the top and the equator: start below their mean
    Eigen::VectorXd r(static_cast<Eigen::Index>(p.points.size()));
    for (int step = 0; step < 30; ++step) {
      Eigen::MatrixXd j(static_cast<Eigen::Index>(p.points.size()), 3);
      for (std::size_t i = 0; i < p.points.size(); ++i) {
        const Eigen::Vector3d d = p.points[i] - c;
        r[static_cast<Eigen::Index>(i)] = d.norm() - radius;
        j.row(static_cast<Eigen::Index>(i)) = -d.transpose() / d.norm();
      }
      const Eigen::Vector3d dc = j.colPivHouseholderQr().solve(-r);
      c += dc;
      if (dc.norm() < 1e-10) break;
    }
    for (std::size_t i = 0; i < p.points.size(); ++i) {
      const double off = std::abs((p.points[i] - c).norm() - radius);
      log.largest_residual_um = std::max(log.largest_residual_um, off * 1e3);
      if (off > tolerance_mm)
        throw LoadError({path, p.line}, "pose " + std::to_string(index) + ": a point lies " + std::to_string(off * 1e3) +
                                            " um off the sphere of diameter " + std::to_string(log.sphere_diameter_mm) +
                                            " (+ the ball) through the others: a wrong diameter, another sphere or a bad trip?");
    }
    SpherePose s;
    s.line = p.line;
    s.joints = machine::Joints::Zero(model.joint_count());
    s.joints[x] = c.x(), s.joints[y] = c.y(), s.joints[z] = c.z();
    int r_index = 0;
    for (int j = 0; j < model.joint_count(); ++j)
      if (model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Rotary) s.joints[j] = p.rotary[static_cast<std::size_t>(r_index++)];
    log.centres.push_back(s);
  }
  if (log.centres.empty()) throw LoadError({path}, "no points");
  return log;
}

}  // namespace vc::identify
