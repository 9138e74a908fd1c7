#include "vc/identify/iso230_2.hpp"

#include "vc/tables/number_text.hpp"
#include "vc/tables/source_error.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace vc::identify {
namespace {

const char* name(Direction d) { return d == Direction::Up ? "+" : "-"; }

// Readings by run and direction, each a map target -> deviation (a target read twice: refused).
std::map<RunKey, std::map<double, double>> by_run(const LaserRuns& runs, const std::set<RunKey>& left_out) {
  std::map<RunKey, std::map<double, double>> out;
  std::map<RunKey, std::map<double, int>> lines;
  for (const Reading& r : runs.readings) {
    const RunKey key{r.run, r.direction};
    if (left_out.count(key)) continue;
    if (const auto [it, fresh] = lines[key].emplace(r.target, r.line); !fresh)
      throw LoadError({runs.path, r.line}, "run " + std::to_string(r.run) + name(r.direction) + " reads target " +
                                               significant_text(r.target, 6) + " again (first on line " +
                                               std::to_string(it->second) + ")");
    out[key][r.target] = r.deviation;
  }
  return out;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double sample_sd(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

}  // namespace

std::vector<SuspiciousRun> suspicious_runs(const LaserRuns& runs) {
  const auto all = by_run(runs, {});
  const double floor = runs.quantity == tables::Quantity::Length ? 0.5e-3 : 0.5e-6;  // 0.5 um or urad
  std::vector<SuspiciousRun> out;
  for (const auto& [key, readings] : all) {
    // The other runs of this direction at this run's targets: their mean and scatter.
    std::vector<double> own, others_mean;
    double scatter = 0;
    int scatter_count = 0;
    for (const auto& [target, x] : readings) {
      std::vector<double> others;
      for (const auto& [k, r] : all)
        if (k != key && k.second == key.second)
          if (const auto it = r.find(target); it != r.end()) others.push_back(it->second);
      if (others.size() < 2) continue;
      own.push_back(x);
      others_mean.push_back(mean(others));
      const double s = sample_sd(others);
      scatter += s * s;
      ++scatter_count;
    }
    if (own.size() < 2) continue;  // too few others to judge by
    const double s_others = std::sqrt(scatter / scatter_count);
    double mm = 0, xm = 0, off = 0;
    for (std::size_t i = 0; i < own.size(); ++i) {
      mm += others_mean[i] * others_mean[i];
      xm += own[i] * others_mean[i];
      off += (own[i] - others_mean[i]) * (own[i] - others_mean[i]);
    }
    const double signal = std::sqrt(mm / static_cast<double>(own.size()));
    const double rms_off = std::sqrt(off / static_cast<double>(own.size()));
    const std::string run = "run " + std::to_string(key.first) + name(key.second);
    if (rms_off <= std::max(4 * s_others, floor)) continue;
    if (signal > std::max(4 * s_others, floor)) {  // the others show a shape this run can be compared with
      const double k = xm / mm;
      if (std::abs(k + 1) < 0.25) {
        out.push_back({key, run + " reads the others' deviations with the sign reversed (scale " + std::to_string(k) +
                                "): the optics or the direction turned round?"});
        continue;
      }
      for (const auto& [factor, what] :
           {std::pair{1000.0, "1000 (um read as nm, or mm as um)"},
            std::pair{1e-3, "1/1000 (nm read as um, or um as mm)"}, std::pair{25.4, "25.4 (inches read as mm)"},
            std::pair{1 / 25.4, "1/25.4 (mm read as inches)"}})
        if (std::abs(k / factor - 1) < 0.2) {
          out.push_back({key, run + " reads the others' deviations times " + std::string(what) + ": another unit?"});
          break;
        }
      if (!out.empty() && out.back().run == key) continue;
    }
    const bool length = runs.quantity == tables::Quantity::Length;
    out.push_back({key, run + " stands off the other runs by " + std::to_string(rms_off * (length ? 1e3 : 1e6)) +
                            (length ? " um" : " urad") + " RMS, " +
                            std::to_string(rms_off / std::max(s_others, 1e-12)) + " times their scatter: disturbed?"});
  }
  return out;
}

Iso230_2 evaluate_iso230_2(const LaserRuns& runs, const std::set<RunKey>& left_out) {
  const auto all = by_run(runs, left_out);
  // The targets: those of the first run; every run must read exactly these.
  if (all.empty()) throw LoadError({runs.path}, "no runs left");
  std::vector<double> targets;
  for (const auto& [t, x] : all.begin()->second) targets.push_back(t);
  for (const auto& [key, readings] : all) {
    for (double t : targets)
      if (!readings.count(t))
        throw LoadError({runs.path}, "run " + std::to_string(key.first) + name(key.second) +
                                         " has no reading at target " + significant_text(t, 6) +
                                         " (every run reads every target)");
    if (readings.size() != targets.size())
      for (const auto& [t, x] : readings)
        if (!std::binary_search(targets.begin(), targets.end(), t))
          throw LoadError({runs.path}, "run " + std::to_string(key.first) + name(key.second) + " reads target " +
                                           significant_text(t, 6) + ", which run " +
                                           std::to_string(all.begin()->first.first) + name(all.begin()->first.second) +
                                           " does not");
  }
  Iso230_2 e;
  for (const auto& [key, r] : all) (key.second == Direction::Up ? e.runs_up : e.runs_down)++;
  if (e.runs_up < 2 || e.runs_down < 2)
    throw LoadError({runs.path}, "ISO 230-2 needs at least 2 runs in each direction (it asks for 5); " +
                                     std::to_string(e.runs_up) + " up and " + std::to_string(e.runs_down) +
                                     " down remain: the repeatability and accuracy would be unsupported");

  double lo_up = INFINITY, hi_up = -INFINITY, lo_down = INFINITY, hi_down = -INFINITY;
  double lo_mean = INFINITY, hi_mean = -INFINITY;
  double a_lo_up = INFINITY, a_hi_up = -INFINITY, a_lo_down = INFINITY, a_hi_down = -INFINITY;
  for (double t : targets) {
    std::vector<double> up, down;
    for (const auto& [key, r] : all) (key.second == Direction::Up ? up : down).push_back(r.at(t));
    TargetStatistics s;
    s.target = t;
    s.mean_up = mean(up);
    s.mean_down = mean(down);
    s.mean = (s.mean_up + s.mean_down) / 2;
    s.s_up = sample_sd(up);
    s.s_down = sample_sd(down);
    s.reversal = s.mean_up - s.mean_down;
    s.r_up = 4 * s.s_up;
    s.r_down = 4 * s.s_down;
    s.r = std::max({2 * s.s_up + 2 * s.s_down + std::abs(s.reversal), s.r_up, s.r_down});
    e.targets.push_back(s);
    e.reversal = std::max(e.reversal, std::abs(s.reversal));
    e.mean_reversal += s.reversal / static_cast<double>(targets.size());
    e.repeatability_up = std::max(e.repeatability_up, s.r_up);
    e.repeatability_down = std::max(e.repeatability_down, s.r_down);
    e.repeatability = std::max(e.repeatability, s.r);
    lo_up = std::min(lo_up, s.mean_up), hi_up = std::max(hi_up, s.mean_up);
    lo_down = std::min(lo_down, s.mean_down), hi_down = std::max(hi_down, s.mean_down);
    lo_mean = std::min(lo_mean, s.mean), hi_mean = std::max(hi_mean, s.mean);
    a_lo_up = std::min(a_lo_up, s.mean_up - 2 * s.s_up), a_hi_up = std::max(a_hi_up, s.mean_up + 2 * s.s_up);
    a_lo_down = std::min(a_lo_down, s.mean_down - 2 * s.s_down);
    a_hi_down = std::max(a_hi_down, s.mean_down + 2 * s.s_down);
  }
  e.systematic_up = hi_up - lo_up;
  e.systematic_down = hi_down - lo_down;
  e.systematic = std::max(hi_up, hi_down) - std::min(lo_up, lo_down);
  e.range = hi_mean - lo_mean;
  e.accuracy_up = a_hi_up - a_lo_up;
  e.accuracy_down = a_hi_down - a_lo_down;
  e.accuracy = std::max(a_hi_up, a_hi_down) - std::min(a_lo_up, a_lo_down);
  return e;
}

}  // namespace vc::identify
