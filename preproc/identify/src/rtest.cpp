#include "vc/identify/rtest.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

#include "instrument_csv.hpp"
#include "vc/machine/forward.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::identify {

std::vector<RTestReading> read_rtest_readings(const std::string& path, const machine::Model& model) {
  const std::vector<tables::CsvRow> rows = tables::read_csv_rows(path, "R-test readings");
  const std::string letters = model.coordinates();
  if (rows.empty()) throw LoadError({path}, "no header: the machine's axes (" + letters + ") and dx, dy, dz");
  const tables::CsvRow& header = rows.front();
  std::vector<int> joint_column(letters.size(), -1);
  int deviation_column[3] = {-1, -1, -1};
  double deviation_scale[3] = {0, 0, 0};
  for (std::size_t i = 0; i < header.cells.size(); ++i) {
    const HeaderCell h = header_cell(path, header.line, header.cells[i]);
    const auto at = h.name.size() == 1 ? letters.find(h.name) : std::string::npos;
    const int d = h.name == "dx" ? 0 : h.name == "dy" ? 1 : h.name == "dz" ? 2 : -1;
    if (at != std::string::npos) {
      joint_column[at] = static_cast<int>(i);
    } else if (d >= 0) {
      if (!h.unit || h.unit->quantity != tables::Quantity::Length)
        throw LoadError({path, header.line, header.cells[i].column},
                        "'" + header.cells[i].text + "' needs a length unit: " + h.name + "[um]");
      deviation_column[d] = static_cast<int>(i);
      deviation_scale[d] = h.unit->to_core;
    } else {
      throw LoadError({path, header.line, header.cells[i].column},
                      "'" + header.cells[i].text + "' is neither an axis of " + model.info.name + " (" + letters +
                          ") nor dx, dy, dz");
    }
  }
  for (std::size_t j = 0; j < letters.size(); ++j)
    if (joint_column[j] < 0) throw LoadError({path, header.line}, std::string("missing column ") + letters[j]);
  for (int d = 0; d < 3; ++d)
    if (deviation_column[d] < 0)
      throw LoadError({path, header.line}, std::string("missing column d") + "xyz"[d] + "[um]");
  std::vector<RTestReading> readings;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const tables::CsvRow& row = rows[r];
    if (row.cells.size() != header.cells.size())
      throw LoadError({path, row.line}, std::to_string(row.cells.size()) + " cells, the header has " +
                                            std::to_string(header.cells.size()));
    RTestReading reading;
    reading.line = row.line;
    reading.joints = machine::Joints(model.joint_count());
    for (std::size_t j = 0; j < letters.size(); ++j)
      reading.joints[static_cast<Eigen::Index>(j)] =
          tables::csv_number(path, row.line, row.cells[static_cast<std::size_t>(joint_column[j])]);
    for (int d = 0; d < 3; ++d)
      reading.deviation_mm[d] =
          tables::csv_number(path, row.line, row.cells[static_cast<std::size_t>(deviation_column[d])]) *
          deviation_scale[d];
    readings.push_back(reading);
  }
  return readings;
}

std::vector<SpherePose> rtest_centres(const machine::Model& model, const std::vector<RTestReading>& readings,
                                      double tool_length_mm) {
  std::vector<int> linear;
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.axes[static_cast<std::size_t>(j)].type == machine::AxisType::Linear) linear.push_back(j);
  if (linear.size() != 3) throw std::runtime_error("the R-test needs three linear axes to follow the sphere");
  std::vector<SpherePose> poses;
  for (const RTestReading& r : readings) {
    const Eigen::Isometry3d at = machine::part_T_tool(model, machine::Machine::Real, r.joints, tool_length_mm);
    const Eigen::Vector3d target = at.translation() + at.linear() * r.deviation_mm;  // the sphere's centre
    machine::Joints q = r.joints;
    // Newton on the linear joints (the model's tip Jacobian by them; the errors' slopes are ~1e-4,
    // so each step gains about four digits).
    bool reached = false;
    for (int step = 0; step < 8 && !reached; ++step) {
      machine::PoseDerivatives d;
      const machine::ToolPose pose = machine::tool_pose(model, machine::Machine::Real, q, tool_length_mm, d);
      const Eigen::Vector3d miss = target - pose.tip_mm;
      if (miss.norm() < 1e-10) {
        reached = true;
        break;
      }
      Eigen::Matrix3d jacobian;
      for (int c = 0; c < 3; ++c) jacobian.col(c) = d.tip.col(linear[static_cast<std::size_t>(c)]);
      const Eigen::FullPivLU<Eigen::Matrix3d> lu(jacobian);
      if (!lu.isInvertible()) throw std::runtime_error("line " + std::to_string(r.line) + ": the linear axes cannot move the nest there");
      const Eigen::Vector3d step_mm = lu.solve(miss);
      for (int c = 0; c < 3; ++c) q[linear[static_cast<std::size_t>(c)]] += step_mm[c];
    }
    if (!reached)
      throw std::runtime_error("line " + std::to_string(r.line) + ": no linear joints put the nest on the sphere");
    poses.push_back({q, r.line});
  }
  return poses;
}

Eigen::Vector3d rtest_reading(const machine::Model& truth, const machine::Joints& joints, double tool_length_mm,
                              const Eigen::Vector3d& sphere_mm, double noise_mm, std::mt19937_64* rng) {
  const Eigen::Isometry3d nest = machine::part_T_tool(truth, machine::Machine::Real, joints, tool_length_mm);
  Eigen::Vector3d reading = nest.inverse() * sphere_mm;  // the centre in the spindle frame, from the nest's centre
  if (noise_mm > 0.0 && rng) {
    std::normal_distribution<double> noise(0.0, noise_mm);
    for (int d = 0; d < 3; ++d) reading[d] += noise(*rng);
  }
  return reading;
}

}  // namespace vc::identify
