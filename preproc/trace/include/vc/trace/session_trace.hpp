// A trace recorded in a LinuxCNC session (kins/configs/common/headless_driver.py) and what it
// shows about the tool: the accuracy the machine achieved and whether volkins did exactly
// what the core computes.
//
// How LinuxCNC turns world commands into joints (measured bit for bit with trivkins, see
// LinuxCNC's src/emc/motion/control.c and cubic.c): at servo cycle n, axis.*.pos-cmd is the
// newest planner point C[n]; the kinematics inverse gives p[n] = IK(C[n]); the joint cubic
// interpolator outputs joint[n] = (p[n-3] + 4 p[n-2] + p[n-1]) / 6. So the recorded joints lag
// and smooth the command: a check compares them with the same filter of the expected p,
// never with IK(C[n]) itself.
#pragma once

#include <string>
#include <vector>

#include "vc/machine/kinematics.hpp"
#include "vc/machine/term_types.hpp"

namespace vc::trace {

struct SessionTrace {
  std::string path;
  std::vector<machine::Joints> world;   // axis.<letter>.pos-cmd (mm, deg), the model's joint order
  std::vector<machine::Joints> joints;  // joint.<j>.pos-cmd of each model joint's principal joint (mm, deg)
  bool with_volkins = true;             // false: a session without volkins (no gain column)
  std::vector<double> gain;             // volkins.gain (0 throughout a session without volkins)
  std::vector<double>
      tool_offset_mm;  // motion.tooloffset.z: the tool length offset (L by Model::correction_length), mm
  std::vector<double> correction_length_mm;  // volkins.correction-length: the L applied (the offset's,
                                             // slewed); empty in a trace without the column
  std::vector<double> controller_ticks;      // motion-controller.time (CPU clock ticks)
  // The world's tool-axis coordinate (Model::tool_axis_coordinate, e.g. column "w"), per sample;
  // empty for a machine without one or a trace without the column (0 throughout).
  std::vector<double> tool_axis_mm;
  // The world convention of each sample (column "tcp": volkins.tcp, 1 in the TCP kinematics type);
  // empty in a trace without the column (the convention the module was loaded with throughout).
  std::vector<machine::WorldConvention> convention;
  // Per temperature input of the model (its order), per sample: volkins.temperature.<name>.filtered,
  // the value the cycle's kinematics used (column "temperature_<name>"); empty for an input
  // without the column (its reference is taken).
  std::vector<std::vector<double>> temperature_degC;
  std::size_t size() const { return world.size(); }
};

// How the trace's columns relate to the machine file: which of LinuxCNC's joint columns j<n>
// drives each axis of the model, and LinuxCNC's length unit.
struct TraceLayout {
  // Per joint of the model (its order): LinuxCNC's joints of its letter, the principal one (the
  // first of the letter in coordinates=, the one volkins reads: kins/src/module_settings.cpp)
  // first, then the others (a gantry's second motor), which must equal it. Empty: the model's
  // joint j is column j<j> (the layout of a configuration whose coordinates are the model's).
  std::vector<std::vector<int>> joints;
  // mm per LinuxCNC length unit (vc::init::LinearUnits; 25.4: inch): the linear axes' and
  // joints' columns, the tool offset and the tool-axis coordinate are in LinuxCNC's units and
  // are converted to mm where they are read. The rotary ones are deg in either.
  double mm_per_unit = 1.0;
};

// The layout of LinuxCNC's coordinates= (one letter per joint, e.g. "xyyz"; empty: the model's
// own order) for `model`. Throws std::invalid_argument where an axis of the model has no joint.
TraceLayout trace_layout(const machine::Model& model, const std::string& coordinates, double mm_per_unit);

// Reads a trace CSV: header with the machine's axis letters (x,y,z,b,c), joints j0..,
// tool_length and controller_time; optional gain (volkins.gain; a session with LinuxCNC's own
// kinematics has none), correction_length, tcp, temperature_<name> and the tool-axis coordinate's
// letter (w). `layout` maps the joint columns to the model's joints and gives the units (by
// default j0.. in the model's order, mm). Throws LoadError naming file, line and column, also
// where a joint of a letter differs from the principal joint of it.
SessionTrace read_session_trace(const std::string& path, const machine::Model& model, const TraceLayout& layout = {});

// LinuxCNC's joint interpolation of kinematics outputs p at sample n >= 3.
machine::Joints interpolated(const std::vector<machine::Joints>& p, std::size_t n);

struct SampleCheck {
  std::size_t sample;
  // The tool: real tip at the recorded joints minus the ideal tip at LinuxCNC's interpolation
  // of the nominal joints (so the trajectory lag is not counted), part frame, mm; and the
  // tool direction error |k' x k| (rad).
  Eigen::Vector3d tip_error_mm;
  double direction_error_rad;
  // The same of the machine with the selected compensation types' errors only (the model under
  // the selection's conditions): what volkins, correcting those, should take to zero.
  Eigen::Vector3d selected_tip_error_mm;
  // The module: recorded joints minus LinuxCNC's interpolation of the joints the core computes
  // for the recorded commands with the recorded gain and the selection (largest over joints, mm
  // or deg).
  double module_mismatch;
  // The correction: at the joints the core computes for this sample's command, the real pose of
  // the selected types' machine minus the commanded ideal pose (where the gain is 1; mm, and rad
  // where the pole fade is 1).
  double command_pose_mm;
  double command_pose_rad;
  // Gain 1, fade 1, FOR selected and two rotary axes: position and tool direction are both
  // corrected (a machine without two rotary axes cannot turn its tool: only the position is).
  bool full_correction;
};

struct TraceSummary {
  std::vector<SampleCheck> samples;  // from sample 3 on, except around tool length changes
  std::size_t skipped = 0;           // samples within 4 cycles of a tool length change
};

// `convention` as the module was loaded (TCP: world Z includes the tool length, as G43 adds it),
// for the samples whose own convention the trace does not record (switchable kinematics: its
// tcp column). `types`: the compensation types volkins corrected with (its type pins); the real
// machine (tip_error_mm, direction_error_rad) has every error, whichever types are on.
TraceSummary check_trace(const machine::Model& model, machine::WorldConvention convention, const SessionTrace& trace,
                         const machine::TypeSelection& types = machine::TypeSelection::all());

}  // namespace vc::trace
