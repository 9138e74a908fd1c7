#include "vc/shop/first_part.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vc::shop {
namespace {

constexpr double kSameFace = 0.985;  // cos 10 deg: normals of one face
constexpr double kShapedWithin = 0.05;  // mm: cuts this close to the deepest also shaped the surface

std::string where(const CmmPoint& p) { return "point " + p.id + " (report line " + std::to_string(p.line) + ")"; }

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// Gaussian low-pass of the measured deviations over the points of the same face (normal
// within 10 deg) within the cut-off, leaving out outliers.
void low_pass(std::vector<MatchedPoint>& points, double cutoff_mm) {
  const double sigma = cutoff_mm / 2;
  for (MatchedPoint& a : points) {
    double sum = 0, weight = 0;
    for (const MatchedPoint& b : points) {
      if (b.outlier || a.point.normal.dot(b.point.normal) < kSameFace) continue;
      const double d = (a.point.nominal - b.point.nominal).norm();
      if (d > cutoff_mm) continue;
      const double w = std::exp(-0.5 * (d / sigma) * (d / sigma));
      sum += w * *b.point.deviation_mm;
      weight += w;
    }
    a.filtered_mm = weight > 0 ? sum / weight : *a.point.deviation_mm;
    a.short_wave_mm = *a.point.deviation_mm - a.filtered_mm;
  }
}

}  // namespace

FormError form_error(const std::vector<CmmPoint>& points) {
  FormError f;
  for (const CmmPoint& p : points) {
    const double d = p.deviation_mm.value_or(0.0);
    f.largest_mm = std::max(f.largest_mm, std::abs(d));
    f.rms_mm += d * d;
  }
  if (!points.empty()) f.rms_mm = std::sqrt(f.rms_mm / static_cast<double>(points.size()));
  return f;
}

FirstPart analyse_first_part(const machine::Model& model, std::istream& program, const interpreter::Setup& setup,
                             const std::vector<CmmPoint>& report, const FirstPartOptions& options) {
  FirstPart part;
  simulate(model, program, setup, options.simulation, [&](const PathSample& s) { part.path.push_back(s); });
  const MachinedSurface surface(part.path, options.surface);

  for (const CmmPoint& p : report) {
    if (!p.deviation_mm) throw std::runtime_error(where(p) + " has no deviation");
    if (std::abs(*p.deviation_mm) > options.largest_deviation_mm)
      throw std::runtime_error(where(p) + " deviates " + std::to_string(*p.deviation_mm) + " mm: more than " +
                               std::to_string(options.largest_deviation_mm) +
                               " mm is not a machine error to tune; is the unit in the report's header right?");
    MatchedPoint m;
    m.point = p;
    m.cuts = surface.contacts(p.nominal, kShapedWithin);
    const std::optional<double> predicted = surface.deviation(p.nominal, p.normal);
    if (m.cuts.empty() || !predicted)
      throw std::runtime_error(where(p) + " is not on a surface " + setup.file + " cuts (no cut within " +
                               std::to_string(options.surface.reach_mm) +
                               " mm): is the report for this program, in the part frame, in the right units?");
    m.predicted_mm = *predicted;
    part.points.push_back(std::move(m));
  }

  // Short waves and outliers: filter, flag what stands out, filter again without it.
  low_pass(part.points, options.cutoff_mm);
  std::vector<double> short_waves;
  for (const MatchedPoint& m : part.points) short_waves.push_back(m.short_wave_mm);
  const double centre = median(short_waves);
  for (double& s : short_waves) s = std::abs(s - centre);
  part.robust_sigma_mm = 1.4826 * median(short_waves);
  const double limit = std::max(options.outlier_sigmas * part.robust_sigma_mm, options.outlier_floor_mm);
  for (MatchedPoint& m : part.points)
    if (std::abs(m.short_wave_mm - centre) > limit) {
      m.outlier = true;
      ++part.outliers;
    }
  low_pass(part.points, options.cutoff_mm);
  double sum = 0;
  int kept = 0;
  for (const MatchedPoint& m : part.points)
    if (!m.outlier) {
      sum += m.short_wave_mm * m.short_wave_mm;
      ++kept;
    }
  part.short_wave_rms_mm = kept ? std::sqrt(sum / kept) : 0.0;
  return part;
}

}  // namespace vc::shop
