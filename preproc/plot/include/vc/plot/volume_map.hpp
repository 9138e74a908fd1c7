// The volume map (issue 37): the tool-tip error |e| (um) over the working volume, per tool
// length, as a machine's user reads it: a grid over the plane of the first two linear joints
// (X-Y on the shipped machines) at a few levels of the third (Z: its travel's ends and middle),
// with the rotary axes at 0 and at their worst position (the rotary setting whose largest
// uncompensated error over a coarse grid of the linear travel is largest), for
//   - no compensation (the machine as it is),
//   - a stock controller's tables filled by the usual practice, and by the modified method
//     (vc::fit_tables::run_study for that controller, fitted over the map's tool lengths,
//     then fit_tables::table_errors on the map's own poses),
//   - the full correction (volkins, vc::machine::correct): 0 on the model up to the solver's
//     tolerance; only its largest value over the map is kept, to state it, never drawn.
// Every error is computed on the nonlinear model: |real tip - ideal tip| at the joints the
// compensation commands. Load time only: allocates.
#pragma once

#include <string>
#include <vector>

#include "vc/fit_tables/controller.hpp"
#include "vc/machine/model.hpp"

namespace vc::plot {

struct VolumeMapOptions {
  std::vector<double> tool_lengths_mm;  // default: the machine file's tool_length_mm
  int grid = 21;                        // positions per joint of the map's plane (2..101)
  int levels = 3;                       // positions of the third linear joint (1..7): ends and between
  // The map's plane: two letters of linear axes ("xy", "xz", "yz", any case); the third linear
  // axis gives the levels. Empty: the first two linear joints (X-Y on the shipped machines).
  std::string plane;
  std::string controller = "linuxcnc";  // the stock controller whose tables are judged; "" for none
  int fresh_poses = 1000;               // the study's fresh poses per tool length (fit_tables::StudyOptions)
};

// One place the rotary axes are held at while the linear ones sweep the map.
struct RotarySetting {
  std::string label;   // "B 0 deg, C 0 deg" ("no rotary axes" on a 3-axis machine)
  bool worst = false;  // the worst position found, not 0
  machine::Joints q;   // every joint; only the rotary ones matter (the linear ones swept)
};

// The map's errors for one tool length and one rotary setting.
struct MapSheet {
  double tool_length_mm = 0.0;
  RotarySetting rotary;
  // error_um[compensation][level][i_second * grid + i_first]: |e| in um.
  std::vector<std::vector<std::vector<double>>> error_um;
  // Per compensation: the largest |e| over the whole sheet (all levels), um.
  std::vector<double> max_um;
};

struct VolumeMap {
  std::string machine_name, machine_path;
  int first_joint = 0, second_joint = 1, level_joint = 2;  // joints of the plane and of the levels
  std::vector<double> first_mm, second_mm, levels_mm;      // the grid's positions (joints, mm)
  // The compensations drawn, in order: "none", then (with a controller) "usual practice" and
  // "modified method" with the controller's tables.
  std::vector<std::string> compensations;
  std::string controller_title;         // "" without a controller
  std::vector<MapSheet> sheets;         // per tool length (ascending), rotary 0 first, then the worst
  int poses = 0;                        // poses of the whole map (each compensation judged on all)
  double full_correction_max_um = 0.0;  // volkins' largest |e| over all of them (the model's own: ~0)
  double seconds = 0.0;                 // how long the map took
};

// Throws std::invalid_argument for a machine with fewer than three linear joints, a grid or
// level count out of range, no tool length, or a plane that is not two of the machine's linear
// axes; the controller's own errors (unknown name) pass.
VolumeMap volume_map(const machine::Model& model, const VolumeMapOptions& options);

// The line the report and `volcomp plot --volume` print for the full correction.
std::string full_correction_statement(const VolumeMap& map);

}  // namespace vc::plot
