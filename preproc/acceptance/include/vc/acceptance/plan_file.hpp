// The machine-readable plan of an acceptance test set (DIR/plan.toml), which `volcomp acceptance
// simulate` and `evaluate` read back. The folder holds one sub-folder per kind of test beside it
// (diagonals/, axes/ and circles/ now; rtest/, test-piece/ later), each test a G-code program and a setup
// sheet; plan.toml has a [[diagonal]] table per diagonal, an [[axis_run]] per axis run and a
// [[circle]] per circle.
//
//   [plan]
//   machine = "machines/data/mc300.toml"   # as given to plan
//   coordinates = "xyzbc"                  # the machine's joints, for a check on reading back
//   tool_length_mm = 100.0                 # L of the tool-side optic below the gauge point
//   tool_offset_mm = 100.0                 # the program's G43.1 Z: L - tool_length_reference_mm
//   rest = [0, 0, 0, 0, 0]                 # every joint (mm, deg) but X, Y, Z during the tests
//   volume_mm = [[x0, x1], [y0, y1], [z0, z1]]
//   feed_mm_per_min = 1000.0, dwell_s = 2.0, overrun_mm = 5.0, runs = 5
//
//   [[diagonal]]
//   name = "body-NNN-PPP", kind = "body"
//   start_mm = [x, y, z], end_mm = [x, y, z]        # X, Y, Z joints
//   targets_mm = [0, ...]                           # distance from the start
//   program = "diagonals/body-NNN-PPP.ngc", sheet = "diagonals/body-NNN-PPP.md"
//   measurements = "body-NNN-PPP.csv"               # its file in the measurements folder
//
//   [[axis_run]]                                    # ISO 230-2 along an axis: the keys of [[diagonal]]
//   name = "axis-X", kind = "axis X", ...           # program = "axes/axis-X.ngc", ...
//
//   [[circle]]                                      # ISO 230-4, a ballbar
//   name = "circle-XY", plane = "XY"
//   centre_mm = [x, y, z], radius_mm = 150          # X, Y, Z joints; the ballbar's length
//   program = "circles/circle-XY.ngc", sheet = "circles/circle-XY.md", measurements = "circle-XY.csv"
//
//   [rtest]                                         # ISO 10791-6, machines with two rotary axes
//   sphere_joints_mm = [x, y, z], sphere_mm = [x, y, z]   # the nest on the sphere at rest; part frame
//   program = "rtest/rtest.ngc", sheet = "rtest/rtest.md", measurements = "rtest.csv"
//   [[rtest.sequence]]
//   name = "rtest-B", left_out = 0
//   poses = [[x, y, z, b, c], ...], retracts = [[...], ...]   # every joint, mm and deg
#pragma once

#include <string>
#include <vector>

#include "vc/acceptance/circles.hpp"
#include "vc/acceptance/diagonals.hpp"
#include "vc/acceptance/rtest_plan.hpp"

namespace vc::acceptance {

struct Plan {
  std::string machine;      // the machine file, as given
  std::string coordinates;  // e.g. "xyzbc"
  DiagonalSettings settings;
  double tool_offset_mm = 0;
  machine::Joints rest;
  std::vector<Diagonal> diagonals;
  std::vector<Diagonal> axis_runs;  // the laser lines along X, Y, Z (ISO 230-2)
  std::vector<Circle> circles;
  RTestPlan rtest;  // empty: none
};

// Every laser line of the plan: the diagonals, then the axis runs.
std::vector<const Diagonal*> laser_lines(const Plan& plan);

// Where a diagonal's files are, relative to the plan's folder / the measurements folder.
std::string program_path(const Diagonal& d);
std::string sheet_path(const Diagonal& d);
std::string measurements_name(const Diagonal& d);
std::string program_path(const Circle& c);
std::string sheet_path(const Circle& c);
std::string measurements_name(const Circle& c);
inline const char* kRTestProgram = "rtest/rtest.ngc";
inline const char* kRTestSheet = "rtest/rtest.md";
inline const char* kRTestMeasurements = "rtest.csv";

std::string plan_toml(const Plan& plan);

// DIR/plan.toml (read_plan_file: that file by its own path); every problem a LoadError at its
// file:line.
Plan read_plan(const std::string& dir);
Plan read_plan_file(const std::string& path);

}  // namespace vc::acceptance
