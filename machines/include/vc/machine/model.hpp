// The machine model: what a machine is, built once from its machine file and never changed;
// what varies while the machine runs (temperatures, the pole fade in force) is its Conditions,
// passed beside it.
//
// Convention: docs/model.md (seed 000, ch. II-III, Appendix 3 psd43.m). Two chains
// leave the bed: the tool chain (axes carrying the spindle, bed outward) and the workpiece
// chain (axes carrying the part). One axis, parent <- child, at nominal position q:
//     linear:  A(q) = T(o + d0) * R(e0) * T(q*u) * T(delta(q)) * R(eps(q))
//     rotary:  A(q) = T(o + d0) * R(e0) * T(delta(q)) * R(eps(q)) * Rot(u, q)
// with R(a, b, c) = Rx(a) * Ry(b) * Rz(c), exact trigonometry, error = actual - nominal.
// Lengths in mm, angles in rad, rotary axis positions in deg.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "vc/machine/trigonometry.hpp"
#include "vc/tables/error_table.hpp"

namespace vc::machine {

// Most joints a machine may have: 3 linear axes and up to 3 rotary ones (the correction uses
// at most 2 rotary axes; LinuxCNC itself allows 9 axes, EMCMOT_MAX_JOINTS 16).
inline constexpr int kMaxAxes = 6;

// Most temperature inputs a machine file may declare ([temperatures]).
inline constexpr int kMaxTemperatureInputs = 8;

// The basic compensation types of ISO/TR 16907 Annex A a term is switched by (term_types.hpp).
inline constexpr int kBasicTypeCount = 10;

// Joint positions in joint order (mm for linear axes, deg for rotary ones). Dynamic size
// with a static maximum: lives on the stack, never allocates.
using Joints = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxAxes, 1>;

enum class AxisType { Linear, Rotary };
enum class Chain { Tool, Workpiece };

// A linear axis's thermal expansion (its measuring system, e.g. a ball screw, growing with a
// temperature input): the axis travels (1 + expansion (T - T_reference)) times as far from its
// reference point, the extra along its own direction u (an error of its frame's translation).
struct LinearThermal {
  int input = -1;                // index into Model::temperatures (and Conditions); -1: none
  double expansion_per_K = 0.0;  // 1/K (11.5e-6 for steel)
  double reference_mm = 0.0;     // the point of the axis that does not move as it grows
};

// What a chain walk reads comes first, from a cache line's start (the servo thread's cycle
// walks every axis; between cycles other threads evict them).
struct alignas(64) Axis {
  Eigen::Isometry3d real_base;   // T(o + d0) * R(e0)
  Eigen::Vector3d direction;     // u: unit direction of travel or rotation (child in parent)
  Eigen::Vector3d pole_mm;       // o: the pole at q = 0, in the parent frame
  Eigen::Vector3d location_rad;  // e0: orientation error of the axis line (EA0?, EB0?, EC0?)
  AxisType type;
  unsigned moved_by = 0;    // bit j set: joint j moves this axis's frame (itself, table variables)
  std::vector<int> tables;  // indices into Model::tables
  LinearThermal thermal;    // linear axes: the expansion with a temperature input
  char letter;              // 'X', 'Y', 'Z', 'A', 'B', 'C', ...
  Chain chain;
  double travel_min, travel_max;  // mm or deg
  Eigen::Vector3d location_mm;    // d0: position error of the axis line (EX0?, EY0?, EZ0?)

  // The axis has component errors (delta, eps): tables or a thermal expansion.
  bool has_component_errors() const { return !tables.empty() || thermal.input >= 0; }
};

// A temperature input of the machine file's [temperatures] (a sensor: volkins reads it from a
// HAL pin, predistort takes --temperature NAME=VALUE). Its current value is in Conditions; the
// range is what the model is valid for.
struct TemperatureInput {
  std::string name;
  double reference_degC = 20.0;  // the temperature the tables hold
  double min_degC = 0.0, max_degC = 50.0;
};

// An error table bound to this machine's joints and temperature inputs. The binding comes
// first and the table's lookup data right after it, on one cache line (the servo thread's
// cycle reads every table's; between cycles other threads evict them).
struct alignas(64) BoundTable {
  explicit BoundTable(tables::ErrorTable t) : table(std::move(t)) {}
  // Of each grid variable: its joint (an axis position), or -1 for a temperature, read from
  // Conditions::temperature_degC[input[v]] (else input[v] is -1).
  std::array<int, tables::ErrorTable::kMaxVariables> joint{};
  std::array<int, tables::ErrorTable::kMaxVariables> input{-1, -1, -1};
  tables::ErrorTable table;
  int file_line = 0;  // the line of its `file =` in the machine file (machine_checksum's order)
};

// The spindle line: the gauge point in the last tool-chain frame and its own location errors
// (EX0S .. EB0S). T_spindle = T(s_o + s_d0) * R(s_e0) (model.md).
struct Spindle {
  Eigen::Vector3d gauge_point_mm;
  Eigen::Vector3d location_mm;
  Eigen::Vector3d location_rad;
  Eigen::Isometry3d real;   // T(s_o + s_d0) * R(s_e0)
  Eigen::Isometry3d ideal;  // T(s_o)
};

struct MachineInfo {
  std::string name, serial, description;
  std::string measured_on, measured_by, instrument;  // metadata of the measurement
  double temperature_C = 20.0;                       // temperature during measurement
};

// Pole fade (model.md, Correction): orientation correction fades out as the tool axis
// approaches a rotary axis line, s = clamp((phi - phi0) / (phi1 - phi0)), f = s^2 (3 - 2 s).
// FOR switched off (term_types.hpp) scales f by `orientation` 0: the tool position alone is
// corrected everywhere, as at the pole (between 0 and 1 while volkins ramps the switch).
struct PoleFade {
  double start_rad;          // phi0: below it, f = 0 (position-only correction)
  double full_rad;           // phi1: above it, f = 1 (full position and orientation correction)
  double orientation = 1.0;  // FOR's gain: f is this times the fade of the pole angle
};

// What varies while a machine runs, beside its Model, which does not (as Pinocchio keeps a
// Model and its Data apart): the temperature inputs' current values and the pole fade in
// force. volkins keeps one and sets it from its pins every servo cycle, predistort from
// --temperature, the trace from its columns; Model::reference_conditions() is the machine as
// its file holds it. Fixed size: set in the servo thread without allocation.
struct Conditions {
  std::array<double, kMaxTemperatureInputs> temperature_degC{};  // by index of Model::temperatures
  PoleFade fade{};
  // The compensation types switched on (term_types.hpp: the basic types of ISO/TR 16907 Annex
  // A): every error term is scaled by its type's gain, 1 (on) unless volkins' pins or volcomp's
  // --types switch it off (0; between while volkins ramps the switch).
  std::array<double, kBasicTypeCount> type_gain{1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  bool all_types_on() const noexcept {
    for (double g : type_gain)
      if (g != 1.0) return false;
    return true;
  }
};

// Newton stopping rules (shared by the correction and its inverse).
struct SolverOptions {
  int max_iterations = 12;               // Newton steps per solve (real-time bound)
  double position_tolerance_mm = 1e-10;  // residual below which a solve has converged
  double direction_tolerance_rad = 1e-12;
};

// Compliance of the tool relative to the part along one linear axis, under a force along
// that axis (seeds/004: per axis, depending on the axis position). Piecewise linear in the
// axis position, held at the ends; one value without positions is a constant.
struct AxisCompliance {
  std::vector<double> position_mm;  // increasing; empty for a constant
  std::vector<double> mm_per_N;     // empty: rigid (no model for this axis)
  double at(double q) const;
};

struct Model {
  std::string path;  // machine file
  MachineInfo info;
  std::vector<Axis> axes;            // joint order: letters in "XYZABCUVW" order
  std::vector<int> tool_chain;       // joint indices, bed outward
  std::vector<int> workpiece_chain;  // joint indices, bed outward
  Spindle spindle;
  Eigen::Isometry3d fixture;    // T(t) * R(r) in the last workpiece-chain frame
  double tool_length_mm = 0.0;  // L of a typical tool: gauge length + tool length (check, poses)
  // The tool-length rule (every component: volkins, predistort, simulate, selftune): the
  // correction is computed for L = tool_length_reference_mm + the active tool length offset
  // (G43, LinuxCNC's motion.tooloffset.z). 0 where the tool table holds gauge lengths.
  double tool_length_reference_mm = 0.0;
  // A LinuxCNC coordinate (U, V or W; 0: none) that moves the tool along its own axis without
  // an axis of its own: the linear joints make the motion (LinuxCNC's 5axiskins' W). Its value
  // w lengthens the tool the nominal TCP kinematics place on the world point to L + w (the real
  // tool, L long, stays w short of it); the correction is still for the real tool, L. Not a
  // joint of the model: volkins passes its LinuxCNC joint through (joint = world).
  char tool_axis_coordinate = 0;
  PoleFade fade;  // the file's (volkins: the pins' defaults)
  SolverOptions solver;
  std::vector<BoundTable> tables;
  std::vector<AxisCompliance> compliance;      // per joint ([stiffness]); all rigid if absent
  std::vector<TemperatureInput> temperatures;  // [temperatures], in the file's order (at most kMaxTemperatureInputs)
  Warnings warnings;                           // found at load time, for `check` and loadrt

  int joint_count() const { return static_cast<int>(axes.size()); }
  // L the correction is computed for while LinuxCNC's tool length offset is `offset_mm`.
  double correction_length(double offset_mm) const { return tool_length_reference_mm + offset_mm; }
  int rotary_count() const;
  int joint_of(char letter) const;                    // -1 if the machine has no such axis
  int temperature_of(const std::string& name) const;  // -1 if the machine has no such input
  // Every temperature at its reference, the file's pole fade.
  Conditions reference_conditions() const noexcept;
  // `conditions` with input `name` at `degC` (predistort --temperature): throws
  // std::invalid_argument for an unknown input or a value outside its range. The servo thread
  // sets Conditions::temperature_degC[i] directly.
  void set_temperature(Conditions& conditions, const std::string& name, double degC) const;
  std::string coordinates() const;  // lower-case letters in joint order, e.g. "xyzbc"
};

// True if a joint lies outside the grid of a table that reads it (the table then holds its
// end value: the machine runs where it was not measured). Periodic rotary grids never are.
// Real-time: no allocation.
bool outside_tables(const Model& model, const Joints& q) noexcept;

// T(origin + location_mm) * R(location_rad): the real placement of an axis or spindle line.
Eigen::Isometry3d line_placement(const Eigen::Vector3d& origin_mm, const Eigen::Vector3d& location_mm,
                                 const Eigen::Vector3d& location_rad);

}  // namespace vc::machine
