// `volcomp error` and `volcomp correct`: one output row per pose, CSV on stdout.
#include <iostream>

#include "commands.hpp"
#include "format.hpp"
#include "poses_csv.hpp"
#include "vc/machine/correct.hpp"
#include "vc/machine/deviations.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::cli {
namespace {

void write_row(std::ostream& out, const std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) out << (i ? "," : "") << format_number(values[i]);
  out << '\n';
}

std::vector<double> nominal_columns(const Poses& poses, std::size_t row) {
  std::vector<double> v;
  for (int j : poses.joint_of_column) v.push_back(poses.joints[row][j]);
  return v;
}

}  // namespace

int run_error(const PoseArgs& args, std::ostream& out) {
  machine::Model model = machine::load_machine(args.machine);
  if (!args.only.empty()) model = machine::keep_only(model, args.only);
  const Poses poses = read_poses(args.poses, model);
  const double tool_length = args.tool_length_mm.value_or(model.tool_length_mm);
  for (const std::string& h : poses.header) out << h << ',';
  out << "ex,ey,ez,ekx,eky,ekz" << (args.ideal_tip ? ",tx,ty,tz" : "") << "\n";
  for (std::size_t r = 0; r < poses.joints.size(); ++r) {
    const machine::VolumetricError e = machine::volumetric_error(model, poses.joints[r], tool_length);
    std::vector<double> row = nominal_columns(poses, r);
    for (int k = 0; k < 3; ++k) row.push_back(e.position_mm[k]);
    for (int k = 0; k < 3; ++k) row.push_back(e.direction_rad[k]);
    if (args.ideal_tip) {
      const Eigen::Vector3d tip = machine::tool_pose(model, machine::Machine::Ideal, poses.joints[r], tool_length).tip_mm;
      for (int k = 0; k < 3; ++k) row.push_back(tip[k]);
    }
    write_row(out, row);
  }
  return 0;
}

int run_correct(const PoseArgs& args, std::ostream& out) {
  const machine::Model model = machine::load_machine(args.machine);
  const Poses poses = read_poses(args.poses, model);
  const double tool_length = args.tool_length_mm.value_or(model.tool_length_mm);
  for (const std::string& h : poses.header) out << h << ',';
  for (const std::string& h : poses.header) out << 'c' << h << ',';
  out << "residual_mm,residual_rad,iterations\n";
  int failures = 0;
  for (std::size_t r = 0; r < poses.joints.size(); ++r) {
    const machine::Correction c = machine::correct(model, poses.joints[r], tool_length);
    if (c.status != machine::Status::Ok) {
      ++failures;
      std::cerr << args.poses << ':' << poses.lines[r] << ": error: correction "
                << machine::describe(c.status) << '\n';
    }
    std::vector<double> row = nominal_columns(poses, r);
    for (int j : poses.joint_of_column) row.push_back(c.joints[j]);
    row.push_back(c.residual_mm);
    row.push_back(c.residual_rad);
    row.push_back(c.iterations);
    write_row(out, row);
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace vc::cli
