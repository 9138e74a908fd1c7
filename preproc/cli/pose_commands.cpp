// `volcomp error` and `volcomp correct`: one output row per pose, CSV on stdout.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "vc/tables/number_text.hpp"
#include "poses_csv.hpp"
#include "vc/machine/correct.hpp"
#include "vc/machine/deviations.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::cli {
namespace {

struct PoseArgs {
  std::string machine;
  std::string poses;
  std::optional<double> tool_length_mm;  // default: the machine file's tool_length_mm
  std::vector<std::string> only;         // deviations to keep (error): all if empty
  bool ideal_tip = false;                // error: also the ideal tool tip (tx,ty,tz)
};

void write_row(std::ostream& out, const std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) out << (i ? "," : "") << number_text(values[i]);
  out << '\n';
}

std::vector<double> nominal_columns(const Poses& poses, std::size_t row) {
  std::vector<double> v;
  for (int j : poses.joint_of_column) v.push_back(poses.joints[row][j]);
  return v;
}

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
      const Eigen::Vector3d tip =
          machine::tool_pose(model, machine::Machine::Ideal, poses.joints[r], tool_length).tip_mm;
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
      std::cerr << args.poses << ':' << poses.lines[r] << ": error: correction " << machine::describe(c.status) << '\n';
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

// The options both commands take.
std::shared_ptr<PoseArgs> add_pose_options(CLI::App* cmd) {
  auto args = std::make_shared<PoseArgs>();
  cmd->add_option("MACHINE", args->machine, "machine description file (.toml)")->required();
  cmd->add_option("--poses", args->poses, "CSV of nominal poses, header of axis letters (x,y,z,b,c)")->required();
  cmd->add_option("--tool-length", args->tool_length_mm,
                  "L in mm: gauge length + tool length (default: the machine file's tool_length_mm)");
  return args;
}

}  // namespace

void add_pose_commands(CLI::App& volcomp, int& exit_code) {
  CLI::App* error_cmd =
      volcomp.add_subcommand("error", "Volumetric error at each pose: ex,ey,ez (mm, part frame), ekx,eky,ekz (rad)");
  CLI::App* correct_cmd = volcomp.add_subcommand(
      "correct", "Corrected joints at each pose: c<axis>..., residual_mm, residual_rad, iterations");
  const std::shared_ptr<PoseArgs> error = add_pose_options(error_cmd);
  const std::shared_ptr<PoseArgs> correct = add_pose_options(correct_cmd);
  error_cmd->add_option("--only", error->only, "keep only these deviations, e.g. --only EAX,EC0Y (the others are zero)")
      ->delimiter(',');
  error_cmd->add_flag("--ideal-tip", error->ideal_tip,
                      "also the ideal machine's tool tip, tx,ty,tz (mm, part frame): where each pose puts the tool");
  error_cmd->callback([error, &exit_code] { exit_code = run_error(*error, std::cout); });
  correct_cmd->callback([correct, &exit_code] { exit_code = run_correct(*correct, std::cout); });
}

}  // namespace vc::cli
