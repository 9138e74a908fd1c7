#include "vc/shop/machined_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vc::shop {
namespace {

constexpr double kFar = std::numeric_limits<double>::infinity();

// Signed distance of p to one tool (tip t, unit axis a, radius r, cutting length l):
// negative inside. Exact for the flat cylinder and the ball-ended one.
double tool_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t, const Eigen::Vector3d& a, double r, double l,
                     ToolEnd end) {
  if (end == ToolEnd::Ball) {
    const Eigen::Vector3d w = p - (t + r * a);  // from the ball centre
    const double h = w.dot(a);
    if (h >= 0) return std::max((w - h * a).norm() - r, h - (l - r));
    return w.norm() - r;
  }
  const Eigen::Vector3d w = p - t;
  const double h = w.dot(a);
  const double rho = (w - h * a).norm();
  // Outside distances to the side (rho - r) and to the end faces (below the tip, above l).
  const double side = rho - r, bottom = -h, top = h - l;
  const double ends = std::max(bottom, top);
  if (side <= 0 && ends <= 0) return std::max(side, ends);
  if (side <= 0) return ends;
  if (ends <= 0) return side;
  return std::hypot(side, ends);
}

long key_of(long i, long j, long k) { return (i * 73856093L) ^ (j * 19349663L) ^ (k * 83492791L); }

}  // namespace

MachinedSurface::MachinedSurface(const ToolPath& path, SurfaceOptions options) : path_(path), options_(options) {
  // Each cutting segment goes into every cell its tool can reach (its bounding box).
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const PathSample& a = path[i];
    const PathSample& b = path[i + 1];
    if (a.move != b.move || !a.cutting) continue;
    const double grow = a.radius_mm + options_.reach_mm + 1.0;
    Eigen::Vector3d lo = a.tip.cwiseMin(b.tip), hi = a.tip.cwiseMax(b.tip);
    for (const Eigen::Vector3d& q : {Eigen::Vector3d(a.tip + options_.flute_length_mm * a.axis),
                                     Eigen::Vector3d(b.tip + options_.flute_length_mm * b.axis)}) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    lo.array() -= grow;
    hi.array() += grow;
    const Eigen::Vector3d clo = (lo / cell_mm_).array().floor(), chi = (hi / cell_mm_).array().floor();
    for (long x = static_cast<long>(clo.x()); x <= static_cast<long>(chi.x()); ++x)
      for (long y = static_cast<long>(clo.y()); y <= static_cast<long>(chi.y()); ++y)
        for (long z = static_cast<long>(clo.z()); z <= static_cast<long>(chi.z()); ++z)
          cells_[key_of(x, y, z)].push_back(static_cast<int>(i));
  }
}

long MachinedSurface::cell_key(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d c = (p / cell_mm_).array().floor();
  return key_of(static_cast<long>(c.x()), static_cast<long>(c.y()), static_cast<long>(c.z()));
}

// The tool between two samples: at the fraction u where it passes p most closely across its
// axis (for a plunge along the axis, the deeper end), and at both ends.
double MachinedSurface::segment_distance(int i, const Eigen::Vector3d& p, double& u) const {
  const PathSample& a = path_[static_cast<std::size_t>(i)];
  const PathSample& b = path_[static_cast<std::size_t>(i) + 1];
  const Eigen::Vector3d axis = (a.axis + b.axis).normalized();
  const Eigen::Vector3d d = b.tip - a.tip, w = p - a.tip;
  const Eigen::Vector3d d_across = d - d.dot(axis) * axis, w_across = w - w.dot(axis) * axis;
  const double dd = d_across.squaredNorm();
  double candidates[3] = {0.0, 1.0, dd > 1e-18 ? std::clamp(w_across.dot(d_across) / dd, 0.0, 1.0) : 0.0};
  double best = kFar;
  for (double c : candidates) {
    const Eigen::Vector3d tip = a.tip + c * d;
    const Eigen::Vector3d tool_axis = ((1 - c) * a.axis + c * b.axis).normalized();
    const double distance = tool_distance(p, tip, tool_axis, a.radius_mm, options_.flute_length_mm, a.end);
    if (distance < best) {
      best = distance;
      u = c;
    }
  }
  return best;
}

double MachinedSurface::removed(const Eigen::Vector3d& p) const {
  const auto it = cells_.find(cell_key(p));
  if (it == cells_.end()) return kFar;
  double nearest = kFar, u = 0;
  for (int i : it->second) nearest = std::min(nearest, segment_distance(i, p, u));
  return nearest;
}

std::vector<Contact> MachinedSurface::contacts(const Eigen::Vector3d& p, double within_mm) const {
  std::vector<Contact> found;
  const auto it = cells_.find(cell_key(p));
  if (it == cells_.end()) return found;
  for (int i : it->second) {
    Contact c{i, 0.0, 0.0};
    c.depth_mm = segment_distance(i, p, c.u);
    found.push_back(c);
  }
  std::sort(found.begin(), found.end(), [](const Contact& a, const Contact& b) { return a.depth_mm < b.depth_mm; });
  if (found.empty() || !(std::abs(found.front().depth_mm) <= options_.reach_mm)) return {};
  const double limit = found.front().depth_mm + within_mm;
  found.erase(std::find_if(found.begin(), found.end(), [&](const Contact& c) { return c.depth_mm > limit; }),
              found.end());
  return found;
}

std::optional<double> MachinedSurface::deviation(const Eigen::Vector3d& p, const Eigen::Vector3d& n) const {
  // Root of f(t) = removed(p + t n). f falls with slope -1 where the tool's surface faces n:
  // the first step takes that slope, the next ones secants (the slope where it is steep
  // enough to trust, -1 otherwise).
  constexpr double kExact = 1e-10;
  double t0 = 0.0, f0 = removed(p);
  if (!(std::abs(f0) <= options_.reach_mm)) return std::nullopt;
  if (std::abs(f0) <= kExact) return 0.0;
  double t1 = f0, f1 = removed(p + t1 * n);
  for (int k = 0; k < 40; ++k) {
    if (!std::isfinite(f1)) return std::nullopt;
    if (std::abs(f1) <= kExact) return t1;
    const double slope = (f1 - f0) / (t1 - t0);
    const double t2 =
        std::clamp(slope < -0.05 ? t1 - f1 / slope : t1 + f1, -2 * options_.reach_mm, 2 * options_.reach_mm);
    if (t2 == t1) break;
    t0 = t1, f0 = f1;
    t1 = t2, f1 = removed(p + t1 * n);
  }
  // A point on the edge of a wall parallel to n stays within round-off of a tool's side
  // (f flat near 0): the surface is then where the iteration stopped, to 1 nm.
  if (std::abs(f1) <= 1e-6) return t1;
  // The secants can bounce between two tools whose surfaces meet near p (a floor under the
  // edge of one flat end and the middle of the next): then the sign change of f nearest p
  // within the reach, halved down.
  constexpr int kSteps = 64;
  std::optional<double> found;
  double t_prev = -2 * options_.reach_mm, f_prev = removed(p + t_prev * n);
  for (int k = 1; k <= kSteps; ++k) {
    const double t = -2 * options_.reach_mm + 4 * options_.reach_mm * k / kSteps, f = removed(p + t * n);
    if (std::isfinite(f) && std::isfinite(f_prev) && (f_prev > 0) != (f > 0)) {
      double lo = t_prev, hi = t, f_lo = f_prev;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi), f_mid = removed(p + mid * n);
        ((f_mid > 0) == (f_lo > 0) ? lo : hi) = mid;
        if ((f_mid > 0) == (f_lo > 0)) f_lo = f_mid;
      }
      const double root = 0.5 * (lo + hi);
      if (std::abs(removed(p + root * n)) <= 1e-6 && (!found || std::abs(root) < std::abs(*found))) found = root;
    }
    t_prev = t, f_prev = f;
  }
  if (found && std::abs(*found) <= options_.reach_mm) return found;
  return std::nullopt;
}

}  // namespace vc::shop
