#include "vc/shop/first_part.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace vc::shop {
namespace {

constexpr double kSameFace = 0.985;     // cos 10 deg: normals of one face
constexpr double kShapedWithin = 0.05;  // mm: cuts this close to the deepest also shaped the surface

std::string where(const CmmPoint& p) { return "point " + p.id + " (report line " + std::to_string(p.line) + ")"; }

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// Weighted mean of the measured deviations of the points of a's face (normal within 10 deg)
// within `reach`, leaving out outliers (and `a` itself if asked); nothing if there are none.
template <typename Weight>
std::optional<double> face_mean(const MatchedPoint& a, const std::vector<MatchedPoint>& points, double reach,
                                bool without_a, Weight weight) {
  double sum = 0, total = 0;
  for (const MatchedPoint& b : points) {
    if (b.outlier || (without_a && &b == &a) || a.point.normal.dot(b.point.normal) < kSameFace) continue;
    const double d = (a.point.nominal - b.point.nominal).norm();
    if (d > reach) continue;
    const double w = weight(d);
    sum += w * *b.point.deviation_mm;
    total += w;
  }
  if (total <= 0) return std::nullopt;
  return sum / total;
}

// Gaussian low-pass over each face with the weighting function of ISO 16610-21,
// exp(-pi (d / (alpha lc))^2), alpha = sqrt(ln 2 / pi): a wave of the cut-off length lc
// keeps half its amplitude, longer ones nearly all, shorter ones little.
void low_pass(std::vector<MatchedPoint>& points, double cutoff_mm) {
  const double width = std::sqrt(std::log(2.0) / M_PI) * cutoff_mm;
  for (MatchedPoint& a : points) {
    a.filtered_mm = face_mean(a, points, cutoff_mm, false, [&](double d) {
                      return std::exp(-M_PI * (d / width) * (d / width));
                    }).value_or(*a.point.deviation_mm);
    a.short_wave_mm = *a.point.deviation_mm - a.filtered_mm;
  }
}

// Flags the points that stand out from their face's neighbours (within `reach`, themselves
// left out) by more than the limit; returns the robust sigma of those differences.
double flag_outliers(std::vector<MatchedPoint>& points, double reach, double sigmas, double floor_mm) {
  std::vector<double> differences(points.size(), 0.0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto around = face_mean(points[k], points, reach, true, [](double) { return 1.0; });
    differences[k] = around ? *points[k].point.deviation_mm - *around : 0.0;
  }
  std::vector<double> spread = differences;
  const double centre = median(spread);
  for (double& s : spread) s = std::abs(s - centre);
  const double sigma = 1.4826 * median(spread);
  const double limit = std::max(sigmas * sigma, floor_mm);
  for (std::size_t k = 0; k < points.size(); ++k)
    if (std::abs(differences[k] - centre) > limit) points[k].outlier = true;
  return sigma;
}

// Why no report point might lie on a cut surface, for the whole report: each likely cause
// tested in turn (the program cuts nothing, the tool has no diameter, the report's unit: most
// of its points on cut surfaces once scaled). Nothing if none of them holds.
std::optional<std::string> report_wide_cause(const std::vector<CmmPoint>& report, const MachinedSurface& surface) {
  const ToolPath& path = surface.path();
  const auto cutting = [](const PathSample& s) { return s.cutting; };
  if (std::none_of(path.begin(), path.end(), cutting))
    return "the program cuts nothing: no feed move runs with the spindle on (M3 or M4 before the cuts)";
  if (std::none_of(path.begin(), path.end(), [](const PathSample& s) { return s.cutting && s.radius_mm > 0; }))
    return "the tool has no diameter: give the program's T word and a tool table with its D (--tool-table)";
  const auto share_on_cuts = [&](double scale) {
    const auto on = std::count_if(report.begin(), report.end(), [&](const CmmPoint& q) {
      return !surface.contacts(q.nominal * scale, kShapedWithin).empty();
    });
    return static_cast<double>(on) / static_cast<double>(report.size());
  };
  const double as_given = share_on_cuts(1.0);
  for (const auto& [scale, unit] : {std::pair{25.4, "inches"}, std::pair{1 / 25.4, "millimetres"}})
    if (const double share = share_on_cuts(scale); share >= 0.8 && share > as_given + 0.3)
      return "read as " + std::string(unit) + ", " + std::to_string(static_cast<int>(share * 100)) +
             " % of the report's points lie on cut surfaces (as given: " +
             std::to_string(static_cast<int>(as_given * 100)) + " %): is the report's unit right?";
  return std::nullopt;
}

// Why this point lies on no cut surface, when the report as a whole fits the program.
std::string point_cause(const CmmPoint& p, const MachinedSurface& surface, bool near_cut) {
  if (near_cut)
    return "a cut passes within reach, but the line along the point's normal meets no cut surface: on an edge, or "
           "the normal is not the face's";
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (const PathSample& s : surface.path())
    if (s.cutting) {
      low = low.cwiseMin(s.tip - Eigen::Vector3d::Constant(s.radius_mm));
      high = high.cwiseMax(s.tip + Eigen::Vector3d::Constant(s.radius_mm));
    }
  if ((p.nominal.array() < low.array() - 1.0).any() || (p.nominal.array() > high.array() + 1.0).any())
    return "outside the region the program cuts: is the report in the part frame (the work offset the program runs "
           "in), and for this program?";
  return "no cut reaches it: is the report for this program?";
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

  std::optional<std::optional<std::string>> whole_report;  // report_wide_cause, once asked
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
    if (m.cuts.empty() || !predicted) {
      if (!whole_report) whole_report = report_wide_cause(report, surface);
      if (*whole_report)
        throw std::runtime_error(where(p) + " is not on a surface " + setup.file + " cuts: " + **whole_report);
      part.left_out.push_back({p, point_cause(p, surface, !m.cuts.empty())});
      continue;
    }
    m.predicted_mm = *predicted;
    part.points.push_back(std::move(m));
  }
  // Points on no cut surface are left out, with the reason; too many of them say that the
  // report does not belong to the program.
  const auto total = static_cast<double>(report.size());
  const auto needed = std::max<std::size_t>(options.minimum_points,
                                            static_cast<std::size_t>(std::ceil(options.minimum_matched_share * total)));
  if (part.points.size() < needed) {
    std::string message = "only " + std::to_string(part.points.size()) + " of " + std::to_string(report.size()) +
                          " report points lie on a surface " + setup.file + " cuts (needed: " + std::to_string(needed) +
                          ", " + std::to_string(static_cast<int>(options.minimum_matched_share * 100)) +
                          " % of the report and at least " + std::to_string(options.minimum_points) + "); not on one:";
    const std::size_t shown = std::min<std::size_t>(part.left_out.size(), 5);
    for (std::size_t k = 0; k < shown; ++k)
      message += "\n  " + where(part.left_out[k].point) + ": " + part.left_out[k].reason;
    if (part.left_out.size() > shown)
      message += "\n  ... and " + std::to_string(part.left_out.size() - shown) + " more";
    // report_wide_cause found none of these for the report as a whole.
    message +=
        "\n  tested and not the cause: the program cuts (feed moves with the spindle on), its tool has a "
        "diameter, the report's unit (read as inches or millimetres no more of its points lie on cuts)";
    throw std::runtime_error(message);
  }

  // Outliers first (against their neighbours, twice: a first outlier hides the next one),
  // then the low-pass of what is left.
  for (int pass = 0; pass < 2; ++pass)
    part.robust_sigma_mm =
        flag_outliers(part.points, options.outlier_reach_mm, options.outlier_sigmas, options.outlier_floor_mm);
  low_pass(part.points, options.cutoff_mm);
  double sum = 0;
  int kept = 0;
  for (const MatchedPoint& m : part.points) {
    if (m.outlier) {
      ++part.outliers;
      continue;
    }
    sum += m.short_wave_mm * m.short_wave_mm;
    ++kept;
  }
  part.short_wave_rms_mm = kept ? std::sqrt(sum / kept) : 0.0;
  return part;
}

}  // namespace vc::shop
