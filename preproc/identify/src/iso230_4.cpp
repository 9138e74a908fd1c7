#include "vc/identify/iso230_4.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "instrument_csv.hpp"
#include "vc/machine/deviations.hpp"
#include "vc/machine/forward.hpp"
#include "vc/tables/source_error.hpp"
#include "vc/tables/symbols.hpp"

namespace vc::identify {
namespace {

constexpr double kDeg = M_PI / 180.0;

double wrapped(double a) {  // into [0, 2 pi)
  a = std::fmod(a, 2 * M_PI);
  return a < 0 ? a + 2 * M_PI : a;
}

// dR at `angle` by linear interpolation round the circle.
double at_angle(const CircleRun& run, double angle) {
  const auto& p = run.points;
  const auto upper = std::lower_bound(p.begin(), p.end(), angle, [](const auto& q, double a) { return q.first < a; });
  const auto& b = upper == p.end() ? p.front() : *upper;
  const auto& a = upper == p.begin() ? p.back() : *(upper - 1);
  double span = b.first - a.first, into = angle - a.first;
  if (span <= 0) span += 2 * M_PI;
  if (into < 0) into += 2 * M_PI;
  return span > 0 ? a.second + (b.second - a.second) * into / span : a.second;
}

CircleFit fit(const CircleRun& run, double radius) {
  const auto n = static_cast<Eigen::Index>(run.points.size());
  if (n < 12) throw std::runtime_error("a circle needs at least 12 points in each direction");
  double largest_gap = 0;
  for (std::size_t k = 0; k < run.points.size(); ++k) {
    const double next = k + 1 < run.points.size() ? run.points[k + 1].first : run.points.front().first + 2 * M_PI;
    largest_gap = std::max(largest_gap, next - run.points[k].first);
  }
  if (largest_gap > 30 * kDeg)
    throw std::runtime_error("the " + std::string(run.ccw ? "ccw" : "cw") + " run leaves a gap of " +
                             std::to_string(largest_gap / kDeg) +
                             " deg: the squareness needs the whole turn (a gap under 30 deg)");
  // dR = a0 + a1 cos + b1 sin + a2 cos 2phi + b2 sin 2phi, then the model's parameters.
  Eigen::MatrixXd a(n, 5);
  Eigen::VectorXd b(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double phi = run.points[static_cast<std::size_t>(k)].first;
    a.row(k) << 1, std::cos(phi), std::sin(phi), std::cos(2 * phi), std::sin(2 * phi);
    b[k] = run.points[static_cast<std::size_t>(k)].second;
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  CircleFit f;
  f.ccw = run.ccw;
  f.centre_first_mm = -c[1];
  f.centre_second_mm = -c[2];
  // R (ex cos^2 + ey sin^2) = R (ex + ey) / 2 + R (ex - ey) / 2 cos 2phi; R theta sin cos = R theta / 2 sin 2phi.
  f.mean_scale = c[0] / radius;
  f.scale_mismatch = 2 * c[3] / radius;
  f.squareness_rad = 2 * c[4] / radius;
  // G about the least-squares centre (the first harmonic taken off), F about the nominal one.
  double lo = INFINITY, hi = -INFINITY, sum = 0;
  std::vector<double> residual(static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) {
    const double phi = run.points[static_cast<std::size_t>(k)].first, d = b[k];
    const double about_centre = d - c[1] * std::cos(phi) - c[2] * std::sin(phi);
    lo = std::min(lo, about_centre), hi = std::max(hi, about_centre);
    f.radial_deviation_mm = std::max(f.radial_deviation_mm, std::abs(d));
    residual[static_cast<std::size_t>(k)] = d - a.row(k).dot(c);
    sum += residual[static_cast<std::size_t>(k)] * residual[static_cast<std::size_t>(k)];
  }
  f.circular_deviation_mm = hi - lo;
  f.residual_rms_mm = std::sqrt(sum / static_cast<double>(n));
  // Reversal spikes: the residual's peak within 6 deg of each quadrant point, above the median
  // residual 6-20 deg from it.
  for (double q : {0.0, 90.0, 180.0, 270.0}) {
    double peak = -INFINITY;
    std::vector<double> around;
    for (std::size_t k = 0; k < residual.size(); ++k) {
      double d = std::abs(run.points[k].first / kDeg - q);
      d = std::min(d, 360 - d);
      if (d <= 6)
        peak = std::max(peak, residual[k]);
      else if (d <= 20)
        around.push_back(residual[k]);
    }
    if (!std::isfinite(peak) || around.empty()) continue;
    std::nth_element(around.begin(), around.begin() + static_cast<long>(around.size() / 2), around.end());
    f.spikes.emplace_back(q, peak - around[around.size() / 2]);
  }
  return f;
}

}  // namespace

CircularTest read_circular_test(const std::string& path) {
  CircularTest t;
  t.path = path;
  const std::vector<tables::CsvRow> rows = tables::read_csv_rows(path, "circular test");
  if (rows.empty())
    throw LoadError({path}, "no header: angle[deg],direction,deviation[um] (or angle[deg],ccw[um],cw[um])");
  std::vector<int> metadata_lines;
  t.metadata = read_metadata(path, &metadata_lines);
  for (std::size_t i = 0; i < t.metadata.size(); ++i) {
    const auto& [key, value] = t.metadata[i];
    if (lower(key) == "plane") {
      t.plane = value;
      for (char& c : t.plane) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      if (t.plane != "XY" && t.plane != "YZ" && t.plane != "ZX")
        throw LoadError({path, metadata_lines[i]}, "plane '" + value + "': XY, YZ or ZX");
    }
    if (lower(key) == "radius_mm") {
      char* end = nullptr;
      t.radius_mm = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0' || !(t.radius_mm > 0) || !std::isfinite(t.radius_mm))
        throw LoadError({path, metadata_lines[i]},
                        "radius_mm '" + value + "': the ballbar's nominal radius, a positive number of mm");
    }
  }
  const tables::CsvRow& header = rows.front();
  const Header columns_read = read_header(path, header);
  const std::vector<HeaderCell>& cells = columns_read.cells;
  const auto find = [&](const std::string& name) { return columns_read.column(name); };
  const int angle = find("angle");
  if (angle < 0 || cells[static_cast<std::size_t>(angle)].unit_name != "deg")
    throw LoadError({path, header.line}, "missing column angle[deg]");
  auto length_unit = [&](int i) {
    const HeaderCell& h = cells[static_cast<std::size_t>(i)];
    if (!h.unit || h.unit->quantity != tables::Quantity::Length)
      throw LoadError({path, header.line, header.cells[static_cast<std::size_t>(i)].column},
                      "a radius deviation in mm, um or nm, e.g. deviation[um]");
    return h.unit->to_core;
  };
  CircleRun ccw{true, {}}, cw{false, {}};
  const int deviation = find("deviation"), direction = find("direction"), ccw_col = find("ccw"), cw_col = find("cw");
  if (deviation >= 0 && direction < 0)
    throw LoadError({path, header.line}, "the long layout needs a direction column (ccw or cw)");
  if (deviation < 0 && ccw_col < 0 && cw_col < 0)
    throw LoadError({path, header.line}, "no deviations: deviation[um] with direction, or ccw[um] and cw[um]");
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const tables::CsvRow& row = rows[r];
    if (row.cells.size() != header.cells.size())
      throw LoadError({path, row.line}, std::to_string(row.cells.size()) + " cells, the header has " +
                                            std::to_string(header.cells.size()));
    const double phi = wrapped(tables::csv_number(path, row.line, row.cells[static_cast<std::size_t>(angle)]) * kDeg);
    auto add = [&](CircleRun& run, int column) {
      const tables::CsvCell& cell = row.cells[static_cast<std::size_t>(column)];
      if (!cell.text.empty())
        run.points.emplace_back(phi, tables::csv_number(path, row.line, cell) * length_unit(column));
    };
    if (deviation >= 0) {
      const tables::CsvCell& way = row.cells[static_cast<std::size_t>(direction)];
      const std::string w = lower(way.text);
      if (w == "ccw" || w == "+")
        add(ccw, deviation);
      else if (w == "cw" || w == "-")
        add(cw, deviation);
      else
        throw LoadError({path, row.line, way.column}, "direction '" + way.text + "': ccw or cw (+ or -)");
    } else {
      if (ccw_col >= 0) add(ccw, ccw_col);
      if (cw_col >= 0) add(cw, cw_col);
    }
  }
  for (CircleRun* run : {&ccw, &cw}) {
    if (run->points.empty()) continue;
    std::sort(run->points.begin(), run->points.end());
    t.runs.push_back(std::move(*run));
  }
  if (t.runs.empty()) throw LoadError({path}, "no readings");
  return t;
}

CircularEvaluation evaluate_circular_test(const CircularTest& test) {
  if (!(test.radius_mm > 0))
    throw LoadError({test.path}, "the circle's radius is not known: a '# radius_mm: 150' line, or --radius");
  if (test.plane != "XY" && test.plane != "YZ" && test.plane != "ZX")
    throw std::runtime_error(test.path + ": plane '" + test.plane + "': XY, YZ or ZX");
  CircularEvaluation e;
  double lo = INFINITY, hi = -INFINITY;
  for (const CircleRun& run : test.runs) {
    try {
      e.fits.push_back(fit(run, test.radius_mm));
    } catch (const std::runtime_error& err) {
      throw LoadError({test.path}, err.what());
    }
    e.squareness_rad += e.fits.back().squareness_rad / static_cast<double>(test.runs.size());
    e.scale_mismatch += e.fits.back().scale_mismatch / static_cast<double>(test.runs.size());
  }
  // G(b): both directions about their common least-squares centre (the mean of the two).
  double cx = 0, cy = 0;
  const auto runs = static_cast<double>(e.fits.size());
  for (const CircleFit& f : e.fits) {
    cx += f.centre_first_mm / runs;
    cy += f.centre_second_mm / runs;
  }
  for (const CircleRun& run : test.runs)
    for (const auto& [phi, d] : run.points) {
      const double v = d + cx * std::cos(phi) + cy * std::sin(phi);
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
  e.circular_deviation_mm = hi - lo;
  if (test.runs.size() == 2)
    for (const auto& [phi, d] : test.runs[1].points)
      e.hysteresis_mm = std::max(e.hysteresis_mm, std::abs(d - at_angle(test.runs[0], phi)));
  return e;
}

CircleSetup default_circle_setup(const machine::Model& model) {
  CircleSetup setup{machine::Joints(model.joint_count()), model.tool_length_mm};
  for (int j = 0; j < model.joint_count(); ++j) {
    const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
    setup.centre[j] = a.type == machine::AxisType::Rotary ? 0.0 : (a.travel_min + a.travel_max) / 2;
  }
  return setup;
}

std::vector<SquarenessTerm> squareness_terms(const machine::Model& model, const std::string& plane, double radius_mm,
                                             double squareness_rad, const CircleSetup& setup) {
  const std::string axes = plane == "XY" ? "XY" : plane == "YZ" ? "YZ" : "ZX";
  const char normal = plane == "XY" ? 'Z' : plane == "YZ" ? 'X' : 'Y';
  const int component = normal == 'X' ? 3 : normal == 'Y' ? 4 : 5;  // rotation about the plane's normal
  const int first = model.joint_of(axes[0]), second = model.joint_of(axes[1]);
  if (first < 0 || second < 0) throw std::runtime_error("the machine has no " + axes + " plane");
  const machine::Model zero = machine::keep_only(model, {});
  if (setup.centre.size() != model.joint_count() || !setup.centre.allFinite() || !std::isfinite(setup.tool_length_mm))
    throw std::runtime_error("the circle's centre or tool length is not known");
  const machine::Joints& centre = setup.centre;
  const double r = std::min({radius_mm,
                             (model.axes[static_cast<std::size_t>(first)].travel_max -
                              model.axes[static_cast<std::size_t>(first)].travel_min) /
                                 2,
                             (model.axes[static_cast<std::size_t>(second)].travel_max -
                              model.axes[static_cast<std::size_t>(second)].travel_min) /
                                 2});
  const auto index = [](char axis) { return axis == 'X' ? 0 : axis == 'Y' ? 1 : 2; };
  // The squareness a model shows on the simulated circle, 72 points: dR = the radial part of the
  // tip error, its sin 2phi term (the first-order fit's squareness).
  const auto squareness_of = [&](const machine::Model& m) {
    Eigen::MatrixXd a(72, 5);
    Eigen::VectorXd d(72);
    for (int k = 0; k < 72; ++k) {
      const double phi = 2 * M_PI * k / 72;
      machine::Joints q = centre;
      q[first] += r * std::cos(phi);
      q[second] += r * std::sin(phi);
      const Eigen::Vector3d e = machine::tool_pose(m, machine::Machine::Real, q, setup.tool_length_mm).tip_mm -
                                machine::tool_pose(m, machine::Machine::Ideal, q, setup.tool_length_mm).tip_mm;
      a.row(k) << 1, std::cos(phi), std::sin(phi), std::cos(2 * phi), std::sin(2 * phi);
      d[k] = std::cos(phi) * e[index(axes[0])] + std::sin(phi) * e[index(axes[1])];
    }
    return 2 * a.colPivHouseholderQr().solve(d)[4] / r;
  };
  const double in_model = squareness_of(model);  // every error of the file: its lines and its tables' slopes
  std::vector<SquarenessTerm> out;
  for (char line : {axes[0], axes[1]}) {
    const int j = model.joint_of(line);
    constexpr double kProbe = 1e-5;  // rad
    machine::Model tilted = zero;
    machine::Axis& a = tilted.axes[static_cast<std::size_t>(j)];
    a.location_rad[component - 3] = kProbe;
    a.real_base = machine::line_placement(a.pole_mm, a.location_mm, a.location_rad);
    const double per_rad = squareness_of(tilted) / kProbe;  // squareness made by one rad of this error
    if (std::abs(per_rad) < 0.1) continue;                  // it does not tilt this plane's axes
    const double in_file = model.axes[static_cast<std::size_t>(j)].location_rad[component - 3];
    out.push_back({tables::ErrorSymbol{component, line, true}.name(), in_file + (squareness_rad - in_model) / per_rad,
                   in_file, in_model});
  }
  return out;
}

}  // namespace vc::identify
