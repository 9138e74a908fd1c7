#include "vc/identify/laser_line.hpp"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vc/machine/forward.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::identify {
namespace {

using machine::Machine;

Eigen::Isometry3d pose(const machine::Model& model, Machine m, const LaserSetup& setup, double target) {
  machine::Joints q = setup.at;
  q[setup.joint] = target;
  return machine::part_T_tool(model, m, q, 0.0);  // the spindle frame at the gauge point, in the part frame
}

// The rotation vector of `a` against `b` (a = exp([w]) b), in the frame both are expressed in.
Eigen::Vector3d turn(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::AngleAxisd aa(a * b.transpose());
  return aa.angle() * aa.axis();
}

bool is_positioning(const machine::Model& model, const LaserSetup& setup) {
  const machine::Axis& axis = model.axes[static_cast<std::size_t>(setup.joint)];
  return std::string("XYZABC")[static_cast<std::size_t>(setup.error.component)] == axis.letter;
}

// The unit direction a reading is taken along (translation) or about (rotation), part frame.
Eigen::Vector3d reading_direction(const machine::Model& model, const LaserSetup& setup, double target) {
  const int c = setup.error.component;
  if (!is_positioning(model, setup)) return Eigen::Vector3d::Unit(c % 3);
  // The axis's own ideal motion of the tool against the part, for increasing position.
  constexpr double kStep = 1e-3;  // mm or deg: the ideal machine is smooth
  const Eigen::Isometry3d a = pose(model, Machine::Ideal, setup, target),
                          b = pose(model, Machine::Ideal, setup, target + kStep);
  const Eigen::Vector3d d =
      c < 3 ? Eigen::Vector3d(b * setup.tool_point_mm - a * setup.tool_point_mm) : turn(b.linear(), a.linear());
  return d.normalized();
}

}  // namespace

machine::Joints parse_axis_positions(const machine::Model& model, int moving_joint, const std::string& text) {
  machine::Joints q = machine::Joints::Zero(model.joint_count());
  std::vector<bool> given(static_cast<std::size_t>(model.joint_count()), false);
  std::string item;
  const auto take = [&] {
    if (item.empty()) return;
    const std::size_t eq = item.find('=');
    const int joint =
        eq == 1 ? model.joint_of(static_cast<char>(std::toupper(static_cast<unsigned char>(item[0])))) : -1;
    if (joint < 0)
      throw std::runtime_error("'" + item + "': an axis of " + model.info.name + " (" + model.coordinates() +
                               ") and its position, e.g. x=0");
    std::size_t used = 0;
    try {
      q[joint] = std::stod(item.substr(2), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() - 2 || !std::isfinite(q[joint]))
      throw std::runtime_error("'" + item + "': the position is not a number (mm or deg)");
    given[static_cast<std::size_t>(joint)] = true;
    item.clear();
  };
  for (const char c : text + ",") {
    if (c == ',' || c == ' ' || c == '\t')
      take();
    else
      item += c;
  }
  std::string missing;
  for (int j = 0; j < model.joint_count(); ++j)
    if (j != moving_joint && !given[static_cast<std::size_t>(j)])
      missing += std::string(missing.empty() ? "" : ", ") +
                 static_cast<char>(std::tolower(model.axes[static_cast<std::size_t>(j)].letter));
  if (!missing.empty())
    throw std::runtime_error("where did " + missing + " stand during the runs? Every axis's position is needed ('" +
                             text + "' lacks it): the laser reads the machine's errors there too");
  return q;
}

double laser_reading(const machine::Model& model, const LaserSetup& setup, double target) {
  const Eigen::Isometry3d real = pose(model, Machine::Real, setup, target),
                          ideal = pose(model, Machine::Ideal, setup, target);
  const Eigen::Vector3d e = setup.error.component < 3
                                ? Eigen::Vector3d(real * setup.tool_point_mm - ideal * setup.tool_point_mm)
                                : turn(real.linear(), ideal.linear());
  return reading_direction(model, setup, target).dot(e);
}

Reference default_reference(const tables::ErrorSymbol& error, bool rotary_axis) {
  const bool positioning = std::string("XYZABC")[static_cast<std::size_t>(error.component)] == error.axis;
  return !rotary_axis && error.component < 3 && !positioning ? Reference::LeastSquares : Reference::None;
}

const char* reference_name(Reference r) {
  switch (r) {
    case Reference::None:
      return "none";
    case Reference::Datum:
      return "datum";
    case Reference::LeastSquares:
      return "least-squares";
    case Reference::EndPoints:
      return "end-points";
  }
  return "";
}

ReferenceLine reference_line(const std::vector<double>& targets, const std::vector<double>& values, Reference r) {
  ReferenceLine line;
  const std::size_t n = targets.size();
  if (n == 0) return line;
  const double t0 = targets.front();
  switch (r) {
    case Reference::None:
      break;
    case Reference::Datum:
      line.offset = values.front();
      break;
    case Reference::EndPoints:
      line.offset = values.front();
      line.slope = n > 1 ? (values.back() - values.front()) / (targets.back() - t0) : 0.0;
      break;
    case Reference::LeastSquares: {
      Eigen::MatrixXd a(n, 2);
      Eigen::VectorXd b(n);
      for (std::size_t k = 0; k < n; ++k) {
        a.row(static_cast<Eigen::Index>(k)) << 1.0, targets[k] - t0;
        b[static_cast<Eigen::Index>(k)] = values[k];
      }
      const Eigen::Vector2d c = a.colPivHouseholderQr().solve(b);
      line.offset = c[0];
      line.slope = c[1];
      break;
    }
  }
  for (const double t : targets) line.at.push_back(line.offset + line.slope * (t - t0));
  return line;
}

void set_location_rotation(machine::Model& model, int joint, int component, double rad) {
  machine::Axis& a = model.axes[static_cast<std::size_t>(joint)];
  a.location_rad[component - 3] = rad;
  a.real_base = machine::line_placement(a.pole_mm, a.location_mm, a.location_rad);
}

LineSolution solve_line(machine::Model& model, const LineUnknowns& u, const LaserSetup& setup,
                        const std::vector<double>& targets, const std::vector<double>& readings) {
  tables::ErrorTable& t = model.tables[static_cast<std::size_t>(u.table)].table;
  const int nodes = t.node_count();
  const bool periodic = t.grid()[0].periodic;
  const int columns = periodic ? nodes - 1 : nodes;  // a full turn's last node is its first
  const bool squareness = u.squareness_joint >= 0;
  const int unknowns = columns + (squareness ? 1 : 0);
  const auto set = [&](const Eigen::VectorXd& v) {
    for (int i = 0; i < nodes; ++i) t.set_value(i, u.column, v[i % columns]);
    if (squareness) set_location_rotation(model, u.squareness_joint, u.squareness_component, v[columns]);
  };
  // The readings, then (a squareness) the table's slope by the reference's rule, held 0.
  const Eigen::Index rows = static_cast<Eigen::Index>(targets.size()) + (squareness ? 1 : 0);
  Eigen::RowVectorXd slope_rule = Eigen::RowVectorXd::Zero(unknowns);
  if (squareness) {
    if (u.reference == Reference::EndPoints) {
      slope_rule[0] = -1.0;
      slope_rule[columns - 1] = 1.0;
    } else {
      const Eigen::Map<const Eigen::VectorXd> x(t.grid()[0].nodes.data(), columns);
      const Eigen::VectorXd centred = x.array() - x.mean();
      slope_rule.head(columns) = centred.transpose() / centred.squaredNorm();
    }
  }
  const auto equations = [&](const Eigen::VectorXd& v) {
    set(v);
    Eigen::VectorXd p(rows);
    for (std::size_t k = 0; k < targets.size(); ++k)
      p[static_cast<Eigen::Index>(k)] = laser_reading(model, setup, targets[k]);
    if (squareness) p[rows - 1] = slope_rule.dot(v);
    return p;
  };
  Eigen::VectorXd m = Eigen::VectorXd::Zero(rows);
  for (std::size_t k = 0; k < readings.size(); ++k) m[static_cast<Eigen::Index>(k)] = readings[k];

  // Gauss-Newton, the Jacobian by forward differences: the readings are linear in a translation
  // table and nearly so in the angles, so two or three steps reach the rounding.
  const bool length = setup.error.component < 3;
  const double tolerance = length ? 1e-10 : 1e-13;  // mm or rad
  Eigen::VectorXd v = Eigen::VectorXd::Zero(unknowns);
  for (int i = 0; i < columns; ++i) v[i] = t.value(i, u.column);
  if (squareness)
    v[columns] = model.axes[static_cast<std::size_t>(u.squareness_joint)].location_rad[u.squareness_component - 3];
  LineSolution solution;
  for (int iteration = 1; iteration <= 10; ++iteration) {
    const Eigen::VectorXd p = equations(v);
    solution.iterations = iteration;
    solution.largest_residual = (p - m).head(static_cast<Eigen::Index>(targets.size())).cwiseAbs().maxCoeff();
    if (solution.largest_residual < tolerance && (!squareness || std::abs(p[rows - 1]) < 1e-12)) break;
    Eigen::MatrixXd jacobian(rows, unknowns);
    for (int i = 0; i < unknowns; ++i) {
      const double step = i < columns && length ? 1e-3 : 1e-6;  // mm or rad
      Eigen::VectorXd w = v;
      w[i] += step;
      jacobian.col(i) = (equations(w) - p) / step;
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(jacobian);
    if (qr.rank() < unknowns) {
      set(v);
      throw std::runtime_error(
          "the readings along this line do not see " + setup.error.name() +
          (squareness
               ? " and " + tables::ErrorSymbol{u.squareness_component,
                                               model.axes[static_cast<std::size_t>(u.squareness_joint)].letter, true}
                               .name()
               : std::string()) +
          " apart (the model's reading does not change with them): the line or the optics cannot measure it");
    }
    v += qr.solve(m - p);
  }
  set(v);
  if (solution.largest_residual >= tolerance * 1e3)
    throw std::runtime_error("the model's readings do not converge on the runs (" +
                             number_text(solution.largest_residual) + " left after " +
                             std::to_string(solution.iterations) + " steps)");
  solution.values.assign(v.data(), v.data() + columns);
  if (periodic) solution.values.push_back(v[0]);
  if (squareness) solution.squareness_rad = v[columns];
  return solution;
}

}  // namespace vc::identify
