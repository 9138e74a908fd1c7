#include "vc/acceptance/diagonals.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

#include "vc/tables/number_text.hpp"

namespace vc::acceptance {
namespace {

double round_um(double mm) { return std::round(mm * 1e3) / 1e3; }

// A corner's coordinate: 'N' the low end, 'P' the high end of axis i.
double corner(const WorkVolume& v, int i, char end) { return end == 'N' ? v.low_mm[i] : v.high_mm[i]; }

std::vector<double> targets_along(double length, int count, std::mt19937& generator) {
  std::vector<double> t(static_cast<std::size_t>(count));
  const double p = length / (count - 1);
  for (int i = 0; i < count; ++i) {
    // mt19937's raw output is the same everywhere (the distributions of <random> are not).
    const double u = static_cast<double>(generator()) / 4294967296.0;  // [0, 1)
    const double offset = (i == 0 || i == count - 1) ? 0.0 : (u - 0.5) * p / 2;
    t[static_cast<std::size_t>(i)] = round_um(i == count - 1 ? length : i * p + offset);
  }
  return t;
}

// Each line's targets (its generator seeded by its place, `first` + k, among the plan's lines),
// and its overruns checked against the travel.
void place_targets(const machine::Model& model, const DiagonalSettings& s, std::vector<Diagonal>& out, unsigned first) {
  const LinearJoints j = linear_joints(model);
  for (std::size_t k = 0; k < out.size(); ++k) {
    Diagonal& d = out[k];
    std::mt19937 generator(s.seed * 1000u + first + static_cast<unsigned>(k));
    d.targets_mm = targets_along(d.length_mm(), s.targets, generator);
    // The overrun points must lie inside the travel.
    for (const Eigen::Vector3d& p : {d.at(-s.overrun_mm), d.at(d.length_mm() + s.overrun_mm)})
      for (int i = 0; i < 3; ++i) {
        const machine::Axis& a = model.axes[static_cast<std::size_t>(j[i])];
        if (p[i] < a.travel_min - 1e-9 || p[i] > a.travel_max + 1e-9)
          throw std::runtime_error(d.name + ": the overrun of " + number_text(s.overrun_mm) + " mm takes " +
                                   a.letter + " to " + fixed_text(p[i], 3) + " mm, outside its travel " +
                                   number_text(a.travel_min) + ":" + number_text(a.travel_max) +
                                   " mm: a smaller --volume or --overrun");
      }
  }
}

// The settings every line needs.
void check_line_settings(const DiagonalSettings& s) {
  if (s.targets < 5) throw std::runtime_error("--targets: at least 5 per diagonal (ISO 230-2)");
  if (s.runs < 2) throw std::runtime_error("--runs: at least 2 bidirectional runs (ISO 230-2 asks for 5)");
  if (!(s.feed_mm_per_min > 0)) throw std::runtime_error("--feed must be > 0 mm/min");
  if (!(s.dwell_s > 0)) throw std::runtime_error("--dwell must be > 0 s (the laser reads at rest)");
  if (!(s.overrun_mm >= 0)) throw std::runtime_error("--overrun must be >= 0 mm");
}

}  // namespace

machine::Joints joints_at(const machine::Model& model, const machine::Joints& rest, const Eigen::Vector3d& xyz_mm) {
  const LinearJoints j = linear_joints(model);
  machine::Joints q = rest;
  for (int i = 0; i < 3; ++i) q[j[i]] = xyz_mm[i];
  return q;
}

machine::Joints rest_joints(const machine::Model& model, const WorkVolume& volume) {
  machine::Joints q = machine::Joints::Zero(model.joint_count());
  for (int k = 0; k < model.joint_count(); ++k) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(k)];
    if (a.type == machine::AxisType::Rotary && (a.travel_min > 0 || a.travel_max < 0))
      throw std::runtime_error(std::string("rotary axis ") + a.letter + "'s travel " + number_text(a.travel_min) +
                               ":" + number_text(a.travel_max) + " deg excludes 0, where the diagonals hold it");
  }
  return joints_at(model, q, volume.centre());
}

std::vector<Diagonal> plan_axis_runs(const machine::Model& model, const DiagonalSettings& s, const std::string& axes) {
  std::vector<Diagonal> out;
  if (axes == "none") return out;
  check_line_settings(s);
  std::istringstream list(axes);
  for (std::string axis; std::getline(list, axis, ',');) {
    if (axis != "X" && axis != "Y" && axis != "Z")
      throw std::runtime_error("--axis-runs " + axes + ": X, Y and Z, separated by commas, or none");
    for (const Diagonal& d : out)
      if (d.name == "axis-" + axis) throw std::runtime_error("--axis-runs " + axes + ": " + axis + " twice");
    const int i = axis[0] - 'X';
    Diagonal d;
    d.name = "axis-" + axis;
    d.kind = "axis " + axis;
    d.start_mm = d.end_mm = s.volume.centre();
    d.start_mm[i] = s.volume.low_mm[i];
    d.end_mm[i] = s.volume.high_mm[i];
    out.push_back(d);
  }
  if (out.empty()) throw std::runtime_error("--axis-runs: X, Y and Z, separated by commas, or none");
  place_targets(model, s, out, 10);  // after the 10 diagonals' generators
  return out;
}

std::vector<Diagonal> plan_diagonals(const machine::Model& model, const DiagonalSettings& s) {
  check_line_settings(s);
  if (s.which != "all" && s.which != "body" && s.which != "face" && s.which != "none")
    throw std::runtime_error("--diagonals " + s.which + ": all, body, face or none");
  if (s.which == "none") return {};
  const WorkVolume& v = s.volume;
  const Eigen::Vector3d c = v.centre();
  std::vector<Diagonal> out;
  // Body diagonals: ISO 230-6's four, each from a corner at the low end of X.
  for (const char* corners : {"NNN-PPP", "NNP-PPN", "NPN-PNP", "NPP-PNN"}) {
    Diagonal d;
    d.name = std::string("body-") + corners;
    d.kind = "body";
    for (int i = 0; i < 3; ++i) {
      d.start_mm[i] = corner(v, i, corners[i]);
      d.end_mm[i] = corner(v, i, corners[4 + i]);
    }
    out.push_back(d);
  }
  // Face diagonals through the centre: the face's axes (a, b), the third at the centre.
  struct Face {
    const char* name;
    int a, b;
  };
  for (const Face f : {Face{"XY", 0, 1}, Face{"YZ", 1, 2}, Face{"ZX", 2, 0}})
    for (const char* corners : {"NN-PP", "NP-PN"}) {
      Diagonal d;
      d.name = std::string("face-") + f.name + "-" + corners;
      d.kind = std::string("face ") + f.name;
      d.start_mm = d.end_mm = c;
      d.start_mm[f.a] = corner(v, f.a, corners[0]);
      d.start_mm[f.b] = corner(v, f.b, corners[1]);
      d.end_mm[f.a] = corner(v, f.a, corners[3]);
      d.end_mm[f.b] = corner(v, f.b, corners[4]);
      out.push_back(d);
    }
  place_targets(model, s, out, 0);
  // The subset keeps each diagonal's targets (their generator's seed is its place among all 10).
  if (s.which != "all")
    out.erase(std::remove_if(out.begin(), out.end(), [&](const Diagonal& d) { return (d.kind == "body") != (s.which == "body"); }),
              out.end());
  return out;
}

}  // namespace vc::acceptance
