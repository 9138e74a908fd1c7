#include "vc/predistort/correction_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vc/machine/travel_samples.hpp"
#include "vc/machine/correct.hpp"

namespace vc::predistort {
namespace {

using machine::Joints;

constexpr int kSamples = 150;            // over the travel, and as many again in the pole fade band
constexpr int kBandDraws = 40000;        // tries to find those
constexpr double kStep = 0.25;           // finite differences, mm or deg
constexpr double kMargin = 2.0;          // on the largest slope and curvature sampled
constexpr double kKinkMargin = 1e-3;     // mm or deg, around a piece's corrected joints
constexpr double kStencilMargin = 1e-2;  // around a stencil (the correction moves as it does)

// The correction d(q) = C(q) - q at q, or false where the core cannot correct q. Newton
// starts from q + `near` (a correction nearby), which changes its steps, not its answer.
bool correction_at(const machine::Model& model, const machine::Conditions& conditions, const Joints& q,
                   double tool_length_mm, const Joints& near, Joints& d) {
  const machine::Correction c = machine::correct(model, conditions, q, tool_length_mm, q + near);
  if (c.status != machine::Status::Ok) return false;
  d = c.joints - q;
  return true;
}

}  // namespace

CorrectionBounds::CorrectionBounds(const machine::Model& model, const machine::Conditions& conditions, Shared* shared)
    : model_(model), conditions_(conditions), shared_(shared) {
  for (const machine::BoundTable& bound : model.tables) {
    const auto& grid = bound.table.grid();
    for (std::size_t v = 0; v < grid.size(); ++v) {
      if (bound.joint[v] < 0) continue;  // a temperature: constant while a program is made
      Kinks k{grid[v].periodic ? 360.0 : 0.0, {}};
      if (bound.table.interpolation() == tables::Interpolation::Linear)
        k.at = grid[v].nodes;
      else if (!grid[v].periodic)
        k.at = {grid[v].nodes.front(), grid[v].nodes.back()};
      if (!k.at.empty()) kinks_[static_cast<std::size_t>(bound.joint[v])].push_back(std::move(k));
    }
  }
}

std::size_t CorrectionBounds::Kinks::first_after(double x) const {
  const std::size_t n = at.size();
  if (hint <= n && (hint == 0 || at[hint - 1] <= x) && (hint == n || x < at[hint])) return hint;
  hint = static_cast<std::size_t>(std::upper_bound(at.begin(), at.end(), x) - at.begin());
  return hint;
}

bool CorrectionBounds::kink_near(int joint, double x0, double x1, double margin) const {
  const double lo = std::min(x0, x1) - margin, hi = std::max(x0, x1) + margin;
  for (const Kinks& k : kinks_[static_cast<std::size_t>(joint)]) {
    double from = lo, to = hi;
    if (k.period > 0.0) {
      if (hi - lo >= k.period) return true;
      // Into the period that starts at the first node; the interval may run into the next.
      const double shift = std::floor((lo - k.at.front()) / k.period) * k.period;
      from -= shift;
      to -= shift;
      const std::size_t first_after = k.first_after(from);
      if (first_after < k.at.size() && k.at[first_after] < to) return true;
      if (to > k.at.front() + k.period && k.at.front() + k.period > from) return true;
      continue;
    }
    const std::size_t first_after = k.first_after(from);
    if (first_after < k.at.size() && k.at[first_after] < to) return true;
  }
  return false;
}

bool CorrectionBounds::crosses_kink(const Joints& corrected_a, const Joints& corrected_b) const {
  for (int j = 0; j < model_.joint_count(); ++j)
    if (kink_near(j, corrected_a[j], corrected_b[j], kKinkMargin)) return true;
  return false;
}

CorrectionBounds::Bound CorrectionBounds::slope_bound(const Joints& a, const Joints& b, double tool_length_mm) {
  const Sampled& s = sampled(tool_length_mm);
  Bound bound{0.0, 0.0};
  for (int j = 0; j < model_.joint_count(); ++j) {
    const auto u = static_cast<std::size_t>(j);
    bound.mm += s.slope[u] * std::abs(b[j] - a[j]);
    bound.rad += s.slope_rad[u] * std::abs(b[j] - a[j]);
  }
  return {0.5 * bound.mm, 0.5 * bound.rad};
}

namespace {

// step^T M step, written out: Eigen's product of the dynamic corner and step makes GCC
// warn falsely (maybe-uninitialized) when it optimises with a profile.
template <typename Matrix>
double quadratic_form(const Matrix& m, const Joints& step, int n) {
  double form = 0.0;
  for (int i = 0; i < n; ++i) {
    double row = 0.0;
    for (int j = 0; j < n; ++j) row += m(i, j) * step[j];
    form += step[i] * row;
  }
  return form;
}

}  // namespace

CorrectionBounds::Bound CorrectionBounds::curvature_bound(const Joints& a, const Joints& b, const Joints& corrected_a,
                                                          const Joints& corrected_b, double tool_length_mm) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (crosses_kink(corrected_a, corrected_b)) return {kInfinity, kInfinity};
  const Sampled& s = sampled(tool_length_mm);
  const int n = model_.joint_count();
  const Joints step = (b - a).cwiseAbs();
  // The ends themselves are off by up to the solver's tolerance.
  return {quadratic_form(s.curvature, step, n) / 8.0 + 2 * model_.solver.position_tolerance_mm,
          quadratic_form(s.curvature_rad, step, n) / 8.0 + 2 * model_.solver.direction_tolerance_rad};
}

const CorrectionBounds::Sampled& CorrectionBounds::sampled(double tool_length_mm) {
  for (const Sampled& s : sampled_)
    if (s.tool_length_mm == tool_length_mm) return s;
  Shared alone;  // no other corrector: this one takes every part
  Sampled out = (shared_ ? *shared_ : alone).sampled(*this, tool_length_mm);
  for (double& k : out.slope) k *= kMargin;
  for (double& k : out.slope_rad) k *= kMargin;
  out.curvature *= kMargin;
  out.curvature_rad *= kMargin;
  sampled_.push_back(out);
  return sampled_.back();
}

void CorrectionBounds::merge(Sampled& into, const Sampled& part) {
  for (std::size_t j = 0; j < into.slope.size(); ++j) {
    into.slope[j] = std::max(into.slope[j], part.slope[j]);
    into.slope_rad[j] = std::max(into.slope_rad[j], part.slope_rad[j]);
  }
  into.curvature = into.curvature.cwiseMax(part.curvature);
  into.curvature_rad = into.curvature_rad.cwiseMax(part.curvature_rad);
}

CorrectionBounds::Sampled CorrectionBounds::Shared::sampled(const CorrectionBounds& bounds, double tool_length_mm) {
  std::unique_lock lock(mutex_);
  auto it = std::find_if(entries_.begin(), entries_.end(),
                         [&](const Entry& e) { return e.tool_length_mm == tool_length_mm; });
  Entry& entry = it != entries_.end() ? *it : entries_.emplace_back(Entry{tool_length_mm});
  while (entry.taken < kParts) {
    const int part = entry.taken++;
    lock.unlock();
    Sampled result;
    std::exception_ptr error;
    try {
      result = bounds.sample_part(tool_length_mm, part);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error && !entry.error) entry.error = error;
    if (entry.done == 0)
      entry.result = result;
    else
      merge(entry.result, result);
    if (++entry.done == kParts) finished_.notify_all();
  }
  finished_.wait(lock, [&] { return entry.done == kParts; });
  if (entry.error) std::rethrow_exception(entry.error);
  return entry.result;
}

CorrectionBounds::Sampled CorrectionBounds::sample_part(double tool_length_mm, int part) const {
  Sampled out{tool_length_mm, {}, PerJoint::Zero(), {}, PerJoint::Zero()};
  const int n = model_.joint_count();
  machine::TravelSamples samples(model_);
  const double h = kStep;
  // Where the orientation correction fades in, the correction bends the most: that band,
  // a thin shell of the travel, gets samples of its own.
  auto in_fade_band = [&](const Joints& q) {
    const double phi = machine::pole_angle(model_, q, tool_length_mm);
    return phi >= conditions_.fade.start_rad && phi <= conditions_.fade.full_rad;
  };
  const bool has_band = model_.rotary_count() > 0 && conditions_.fade.full_rad > 0.0;
  int band_draws = 0;
  for (int sample = 0; sample < (has_band ? 2 : 1) * kSamples; ++sample) {
    // Every part draws every sample (the draws are cheap), and evaluates its own.
    Joints q = samples.next();
    if (sample >= kSamples) {
      while (!in_fade_band(q) && ++band_draws < kBandDraws) q = samples.next();
      if (band_draws >= kBandDraws) break;
    }
    if (sample % kParts != part) continue;
    machine::PoseDerivatives derivatives;
    machine::tool_pose(model_, machine::Machine::Ideal, q, tool_length_mm, derivatives);
    const auto tip = [&](const Joints& joint_change) { return (derivatives.tip.leftCols(n) * joint_change).norm(); };
    const auto direction = [&](const Joints& joint_change) {
      return (derivatives.direction.leftCols(n) * joint_change).norm();
    };
    Joints centre;
    if (!correction_at(model_, conditions_, q, tool_length_mm, Joints::Zero(n), centre)) continue;
    // d at q +- h e_i, and whether a kink lies within h of q along joint i.
    std::array<Joints, machine::kMaxAxes> up, down;
    std::array<bool, machine::kMaxAxes> ok{}, smooth{};
    for (int i = 0; i < n; ++i) {
      Joints qu = q, qd = q;
      qu[i] += h;
      qd[i] -= h;
      const auto u = static_cast<std::size_t>(i);
      ok[u] = correction_at(model_, conditions_, qu, tool_length_mm, centre, up[u]) &&
              correction_at(model_, conditions_, qd, tool_length_mm, centre, down[u]);
      smooth[u] = !kink_near(i, q[i] + centre[i] - h, q[i] + centre[i] + h, kStencilMargin);
      if (!ok[u]) continue;
      out.slope[u] = std::max(out.slope[u], tip((up[u] - down[u]) / (2 * h)));
      out.slope_rad[u] = std::max(out.slope_rad[u], direction((up[u] - down[u]) / (2 * h)));
      if (smooth[u]) {
        const Joints second = (up[u] - 2 * centre + down[u]) / (h * h);
        out.curvature(i, i) = std::max(out.curvature(i, i), tip(second));
        out.curvature_rad(i, i) = std::max(out.curvature_rad(i, i), direction(second));
      }
    }
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        if (!smooth[static_cast<std::size_t>(i)] || !smooth[static_cast<std::size_t>(j)]) continue;
        Joints corner[4];
        bool all = true;
        for (int c = 0; c < 4 && all; ++c) {
          Joints p = q;
          p[i] += (c & 1) ? h : -h;
          p[j] += (c & 2) ? h : -h;
          all = correction_at(model_, conditions_, p, tool_length_mm, centre, corner[c]);
        }
        if (!all) continue;
        const Joints mixed = (corner[3] - corner[2] - corner[1] + corner[0]) / (4 * h * h);
        out.curvature(i, j) = out.curvature(j, i) = std::max(out.curvature(i, j), tip(mixed));
        out.curvature_rad(i, j) = out.curvature_rad(j, i) = std::max(out.curvature_rad(i, j), direction(mixed));
      }
    }
  }
  return out;
}

}  // namespace vc::predistort
