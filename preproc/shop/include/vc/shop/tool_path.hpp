// The tool path a program makes a machine follow: tool tip and tool axis in the part frame
// (the machine file's [fixture] frame; for mill3 with mill3.var it is the G54 frame), sample
// by sample. What `volcomp simulate` writes and the virtual CMM and the self-tuning read.
#pragma once

#include <functional>
#include <istream>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vc/interpreter/interpreter.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/predistort/deflection.hpp"

namespace vc::shop {

enum class ToolEnd { Flat, Ball };

struct PathSample {
  int move = 0;    // moves numbered from 1 in program order; the samples of one move are
                   // joined by straight segments (its arcs are sampled finely enough)
  int line = 0;    // program line of the move
  double s = 0.0;  // fraction of the move
  int tool = 0;
  double radius_mm = 0.0;  // from the tool table's diameter (0: unknown)
  ToolEnd end = ToolEnd::Flat;
  bool cutting = false;                                // a feed move with the spindle on (rapids never cut)
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();       // actual tool tip, part frame, mm
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();     // actual tool axis: tip into the spindle
  Eigen::Vector3d error_mm = Eigen::Vector3d::Zero();  // tip - ideal machine's tip at the commanded point
  // Not written to the path file: what produced the sample.
  machine::Joints joints;  // joint positions the machine was at
  double tool_length_mm = 0.0;
  interpreter::Position program{};  // commanded point, program coordinates
};
using ToolPath = std::vector<PathSample>;

struct SimulationOptions {
  double step_mm = 0.5;              // largest distance between samples along a move
  double chord_tolerance_mm = 2e-5;  // arcs: sampled finely enough that chords stray less
  double step_deg = 0.05;            // largest rotary step between samples
  machine::WorldConvention world = machine::WorldConvention::Axes;
  // The model a kinematics module (volkins) corrects with, or none: the machine runs the
  // program's joints as they are (an uncompensated machine, or a pre-distorted program).
  const machine::Model* compensation = nullptr;
  // The conditions it corrects with (the compensation types switched on, temperatures: set by
  // machine::apply_selection), or none: the compensation model's own, every type on.
  const machine::Conditions* compensation_conditions = nullptr;
  const predistort::Deflection* deflection = nullptr;  // cutting-force deflection, or none
  std::set<int> ball_end_tools;                        // tools with a ball end (the others are flat)
};

// Runs `program` on `machine` (its real kinematics, all errors) and passes every sample to
// `sink` in order. Throws vc::LoadError (file:line:column) on a program it cannot read.
void simulate(const machine::Model& machine, std::istream& program, const interpreter::Setup& setup,
              const SimulationOptions& options, const std::function<void(const PathSample&)>& sink);

// The path file (CSV, units in the header). Writing keeps full precision.
void write_path_header(std::ostream& out, const std::vector<std::string>& comments);
void write_path_sample(std::ostream& out, const PathSample& sample);
// Reads a path file; throws vc::LoadError with file:line:column.
ToolPath read_tool_path(const std::string& path);

}  // namespace vc::shop
