#include "vc/identify/sphere_centres.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "instrument_csv.hpp"
#include "vc/machine/forward.hpp"
#include "vc/tables/source_error.hpp"
#include "vc/tables/symbols.hpp"

namespace vc::identify {
namespace {

double& location(machine::Axis& a, int component) {
  return component < 3 ? a.location_mm[component] : a.location_rad[component - 3];
}

void set_location(machine::Model& m, int joint, int component, double value) {
  machine::Axis& a = m.axes[static_cast<std::size_t>(joint)];
  location(a, component) = value;
  a.real_base = machine::line_placement(a.pole_mm, a.location_mm, a.location_rad);
}

double scale_of(int component) { return component < 3 ? 1e-3 : 1e-6; }  // unknowns in um and urad

// A direction of the unknowns (um, urad) the poses see less than a thousandth as well as the
// best-seen one is not seen: what is left there is the second-order coupling with the other
// errors (seen at 1e-5 on the MC-300), not information.
constexpr double kSeen = 1e-3;

}  // namespace

std::vector<SpherePose> read_sphere_centres(const std::string& path, const machine::Model& model) {
  const std::vector<tables::CsvRow> rows = tables::read_csv_rows(path, "sphere centres");
  const std::string letters = model.coordinates();
  if (rows.empty()) throw LoadError({path}, "no header: the machine's axes, " + letters);
  const tables::CsvRow& header = rows.front();
  std::vector<int> column(letters.size(), -1);
  for (std::size_t i = 0; i < header.cells.size(); ++i) {
    const HeaderCell h = header_cell(path, header.line, header.cells[i]);
    const auto at = letters.find(h.name);
    if (h.name.size() != 1 || at == std::string::npos)
      throw LoadError({path, header.line, header.cells[i].column},
                      "'" + header.cells[i].text + "' is not an axis of " + model.info.name + " (" + letters + ")");
    column[at] = static_cast<int>(i);
  }
  for (std::size_t j = 0; j < letters.size(); ++j)
    if (column[j] < 0) throw LoadError({path, header.line}, std::string("missing column ") + letters[j]);
  std::vector<SpherePose> poses;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    SpherePose p;
    p.line = rows[r].line;
    p.joints = machine::Joints(model.joint_count());
    if (rows[r].cells.size() != header.cells.size())
      throw LoadError({path, rows[r].line}, std::to_string(rows[r].cells.size()) + " cells, the header has " +
                                                std::to_string(header.cells.size()));
    for (std::size_t j = 0; j < letters.size(); ++j)
      p.joints[static_cast<Eigen::Index>(j)] =
          tables::csv_number(path, rows[r].line, rows[r].cells[static_cast<std::size_t>(column[j])]);
    poses.push_back(p);
  }
  return poses;
}

SphereFit identify_from_sphere(const machine::Model& model, const std::vector<SpherePose>& poses,
                               std::vector<std::string> symbols, double tool_length_mm) {
  if (symbols.empty())
    for (const machine::Axis& a : model.axes)
      if (a.type == machine::AxisType::Rotary)
        for (int c = 0; c < 6; ++c) symbols.push_back(tables::ErrorSymbol{c, a.letter, true}.name());
  std::vector<LocationEstimate> all;
  for (const std::string& s : symbols) {
    const auto symbol = tables::parse_error_symbol(s);
    if (!symbol || !symbol->location || model.joint_of(symbol->axis) < 0)
      throw std::runtime_error(s + " is not a location error of an axis of " + model.info.name + " (EX0C, EA0B, ...)");
    LocationEstimate e;
    e.symbol = s;
    e.joint = model.joint_of(symbol->axis);
    e.component = symbol->component;
    machine::Axis axis = model.axes[static_cast<std::size_t>(e.joint)];
    e.before = e.value = location(axis, e.component);
    all.push_back(e);
  }
  if (poses.size() < 3)
    throw std::runtime_error("at least 3 probed poses are needed, " + std::to_string(poses.size()) + " given");

  const auto residuals = [&](const machine::Model& m, const Eigen::Vector3d& p0) {
    Eigen::VectorXd r(3 * static_cast<Eigen::Index>(poses.size()));
    for (std::size_t k = 0; k < poses.size(); ++k)
      r.segment<3>(3 * static_cast<Eigen::Index>(k)) =
          machine::tool_pose(m, machine::Machine::Real, poses[k].joints, tool_length_mm).tip_mm - p0;
    return r;
  };
  const auto centre_of = [&](const machine::Model& m) {  // the mean tip: p0's least-squares value
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const SpherePose& p : poses)
      sum += machine::tool_pose(m, machine::Machine::Real, p.joints, tool_length_mm).tip_mm;
    return Eigen::Vector3d(sum / static_cast<double>(poses.size()));
  };
  const auto per_pose_um = [&](const Eigen::VectorXd& r) {
    std::vector<double> out;
    for (std::size_t k = 0; k < poses.size(); ++k)
      out.push_back(r.segment<3>(3 * static_cast<Eigen::Index>(k)).norm() * 1e3);
    return out;
  };

  SphereFit fit;
  machine::Model m = model;
  Eigen::Vector3d p0 = centre_of(m);
  Eigen::VectorXd r = residuals(m, p0);
  fit.residual_before_um = per_pose_um(r);
  fit.rms_before_um = r.norm() / std::sqrt(static_cast<double>(poses.size())) * 1e3;

  // The scaled Jacobian (unknowns: p0 in um, then the location errors in um / urad).
  const auto jacobian = [&](const std::vector<LocationEstimate>& unknown) {
    const auto rows = 3 * static_cast<Eigen::Index>(poses.size());
    Eigen::MatrixXd j(rows, 3 + static_cast<Eigen::Index>(unknown.size()));
    for (Eigen::Index k = 0; k < rows; k += 3) j.block<3, 3>(k, 0) = -1e-3 * Eigen::Matrix3d::Identity();
    for (std::size_t u = 0; u < unknown.size(); ++u) {
      const LocationEstimate& e = unknown[u];
      const double h = scale_of(e.component) * 10, v = e.value;
      machine::Model plus = m, minus = m;
      set_location(plus, e.joint, e.component, v + h);
      set_location(minus, e.joint, e.component, v - h);
      j.col(3 + static_cast<Eigen::Index>(u)) =
          (residuals(plus, p0) - residuals(minus, p0)) / (2 * h) * scale_of(e.component);
    }
    return j;
  };

  // What the poses can tell apart: drop, one at a time, the parameter that takes the largest
  // part in the least-seen direction, while that direction is not seen.
  std::vector<LocationEstimate> unknown = all;
  while (!unknown.empty()) {
    const Eigen::MatrixXd j = jacobian(unknown);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(j, Eigen::ComputeThinV);
    const Eigen::VectorXd s = svd.singularValues();
    const Eigen::Index last = s.size() - 1;
    if (s[last] > kSeen * s[0]) break;
    const auto v = [&](Eigen::Index u) { return std::abs(svd.matrixV()(u, last)); };
    Eigen::Index worst = 3;
    for (Eigen::Index u = 3; u < s.size(); ++u)
      if (v(u) > v(worst)) worst = u;
    NotSeparable n{unknown[static_cast<std::size_t>(worst - 3)].symbol, {}};
    for (Eigen::Index u = 3; u < s.size(); ++u)
      if (u != worst && v(u) > 0.3 * v(worst)) n.with.push_back(unknown[static_cast<std::size_t>(u - 3)].symbol);
    if (n.with.empty()) n.with.push_back("the sphere's position");  // the only other unknown
    fit.not_separable.push_back(n);
    unknown.erase(unknown.begin() + (worst - 3));
  }
  if (unknown.empty())
    throw std::runtime_error("these poses cannot identify any of the location errors asked for (" +
                             std::to_string(poses.size()) + " poses): probe at several positions of each rotary axis");
  const auto dof = 3 * static_cast<Eigen::Index>(poses.size()) - 3 - static_cast<Eigen::Index>(unknown.size());
  if (dof < 1)
    throw std::runtime_error("too few poses for " + std::to_string(unknown.size()) +
                             " location errors and the centre: " + std::to_string(poses.size()) + " poses give " +
                             std::to_string(3 * poses.size()) + " equations; probe more positions");

  // Gauss-Newton (the model is nearly linear in the location errors: a few steps).
  Eigen::MatrixXd j;
  for (int step = 0; step < 8; ++step) {
    j = jacobian(unknown);
    const Eigen::VectorXd dx = j.colPivHouseholderQr().solve(-r);
    p0 += dx.head<3>() * 1e-3;
    for (std::size_t u = 0; u < unknown.size(); ++u) {
      LocationEstimate& e = unknown[u];
      e.value += dx[3 + static_cast<Eigen::Index>(u)] * scale_of(e.component);
      set_location(m, e.joint, e.component, e.value);
    }
    r = residuals(m, p0);
    if (dx.norm() < 1e-9) break;
  }
  fit.centre_mm = p0;
  fit.residual_after_um = per_pose_um(r);
  fit.rms_after_um = r.norm() / std::sqrt(static_cast<double>(poses.size())) * 1e3;
  // Uncertainties: sigma^2 (J^T J)^-1 in the scaled unknowns (r in mm, J per um / urad).
  const double sigma2 = r.squaredNorm() / static_cast<double>(dof);
  const Eigen::MatrixXd covariance = sigma2 * (j.transpose() * j).inverse();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(j);
  fit.condition = svd.singularValues()[0] / svd.singularValues()[svd.singularValues().size() - 1];
  fit.rank = static_cast<int>(unknown.size());
  fit.parameters = static_cast<int>(all.size());
  for (std::size_t u = 0; u < unknown.size(); ++u) {
    LocationEstimate& e = unknown[u];
    const auto i = 3 + static_cast<Eigen::Index>(u);
    e.uncertainty = std::sqrt(covariance(i, i)) * scale_of(e.component);
  }
  fit.estimates = unknown;
  return fit;
}

}  // namespace vc::identify
