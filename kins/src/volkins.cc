// volkins: LinuxCNC 2.9 kinematics with full volumetric correction (linear and angular).
//
//   [KINS] KINEMATICS = volkins machine=/path/machine.toml [coordinates=xyzbc] [world=axes|tcp]
//                      [sparm=identityfirst] [units=mm|inch]
//
// The thin shell over vc_machine: rtapi_app_main reads and validates the machine file and its
// tables (any problem fails loadrt with file:line:problem, before anything is created in HAL);
// kinematicsInverse applies the correction, kinematicsForward is its exact inverse (Newton on
// the real pose, invert_correction), so the DRO, homing and probing see nominal coordinates.
// The HAL function volkins.update (servo thread, before motion-controller) ramps the
// correction in and out when volkins.enable changes, so switching never jumps; the kinematics
// functions read the ramp and the parameters, report on output pins and keep only the last
// four corrections between calls, as their solvers' start (an answer never depends on it).
// A HAL file without `addf volkins.update`
// does not leave the machine silently uncorrected: until the function has run, the kinematics
// apply what volkins.enable asks for in full (no ramp), say so on volkins.gain, volkins.active
// and volkins.update-missing, and print once how to fix the HAL file. Temperature inputs of
// the machine file are HAL pins volkins.temperature.<name>, low-passed in volkins.update;
// a missing or out-of-range reading holds the last good value and raises
// volkins.temperature-fault. Each compensation type of ISO/TR 16907 Annex A (and FOR, thermal)
// has a pin of its own, volkins.type.<code>.enable, ramped as volkins.enable is: the correction
// is then the model's with only the types on (term_types.hpp).
// coordinates= maps LinuxCNC's joints to the machine file's axes (a letter twice: two joints
// driven alike, a gantry). Switchable kinematics (LinuxCNC 2.9, motion.switchkins-type): type 0
// is the world= convention (or the identity with sparm=identityfirst), type 1 the other one;
// both corrected. A switch while the commanded position moves is refused (motion then aborts):
// the planner's queued moves are in the old world's coordinates.
// Servo thread: no allocation, no locks, no I/O, bounded iterations, no exceptions.

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <string_view>

#include "gain_ramp.hpp"
#include "module_settings.hpp"
#include "reload_worker.hpp"
#include "vc/machine/held_rotary.hpp"
#include "vc/machine/machine_checksum.hpp"
#include "vc/machine/term_types.hpp"

#include "rtapi.h"  // rtapi.h and hal.h declare C linkage themselves
#include "hal.h"
#include "emcpos.h"  // C++-aware (posemath overloads): included before the extern "C" block
#include "rtapi_bool.h"
extern "C" {
#include "rtapi_app.h"
#include "kinematics.h"  // no extern "C" guard of its own: the kinematics API must not be mangled
}

namespace {

using vc::machine::Joints;
namespace vm = vc::machine;

constexpr double kDegPerRad = 57.295779513082320876798154814105;
constexpr int kMaxTemperatures = vc::kins::kMaxTemperatureInputs;

// The compensation types switched by pins of their own (volkins.type.<code>.enable): ISO/TR
// 16907 Annex A's basic types (term_types.hpp), then FOR (the tool direction) and thermal.
constexpr int kBasicTypes = vm::kBasicTypeCount;
constexpr int kForSwitch = kBasicTypes, kThermalSwitch = kBasicTypes + 1, kSwitches = kBasicTypes + 2;

struct HalData {
  // Pins.
  hal_bit_t* enable;               // in: correction wanted
  hal_float_t* tool_offset;        // in: tool length offset (LinuxCNC's unit), net to motion.tooloffset.z
  hal_float_t* gain;               // out: fraction applied now (ramp, 0..1)
  hal_bit_t* active;               // out: a correction is applied (gain > 0)
  hal_bit_t* update_missing;       // out: the kinematics ran before volkins.update ever did
  hal_float_t* correction_length;  // out: L the correction is computed for now (LinuxCNC's unit)
  hal_float_t* correction[vc::kins::kMaxJoints];        // out: LinuxCNC joint - its nominal value, last inverse
  hal_s32_t* iterations;                                // out: Newton steps of the last inverse
  hal_s32_t* forward_iterations;                        // out: Newton steps (and band corrections) of the last forward
  hal_bit_t* out_of_table;                              // out: last inverse beyond a table's grid
  hal_bit_t* limit_exceeded;                            // out: last inverse refused (max correction)
  hal_s32_t* failures;                                  // out: inverse and forward calls refused so far
  hal_s32_t* inverse_time;                              // out: ns the last kinematicsInverse took (rtapi_get_time)
  hal_float_t* temperature[kMaxTemperatures];           // in: volkins.temperature.<name>, degC
  hal_float_t* temperature_filtered[kMaxTemperatures];  // out: what the correction uses, degC
  hal_bit_t* temperature_fault;                         // out: an input is missing or out of its range (held)
  hal_bit_t* kinstype_is[3];                            // out: kinstype.is-N, as LinuxCNC's switchable modules
  hal_bit_t* tcp;                                       // out: the world is the tool tip (TCP kinematics type)
  hal_bit_t* switch_enable[kSwitches];                  // in: volkins.type.<code>.enable, thermal.enable
  // Rotary joints only (else null), by LinuxCNC joint: a clamp (held_rotary.hpp).
  hal_bit_t* unlock[vc::kins::kMaxJoints];  // in: volkins.joint.N.unlock, LinuxCNC's locking indexer (joint.N.unlock)
  hal_bit_t* is_unlocked[vc::kins::kMaxJoints];  // in: volkins.joint.N.is-unlocked, its joint.N.is-unlocked
  hal_bit_t* locked[vc::kins::kMaxJoints];       // in: volkins.joint.N.locked, a clamp LinuxCNC does not manage
  hal_bit_t* held[vc::kins::kMaxJoints];         // out: volkins.joint.N.held, its correction held or on its way back
  hal_float_t* direction_error;                  // out: volkins.direction-error-urad, tool direction error left
  hal_float_t* switch_gain[kSwitches];           // out: its ramp, 0..1
  // A new machine file without a restart (reload_worker.hpp).
  hal_bit_t* reload;         // in: a rising edge reloads the machine file (machine=) from disk
  hal_s32_t* reload_state;   // out: 0 idle, 1 reading/validating, 2 ramping the old file out, 3 the new one in
  hal_bit_t* reload_failed;  // out: the last request was refused (cleared by the next one)
  hal_s32_t* reloads;        // out: files swapped in
  hal_u32_t* checksum;       // out: CRC-32 of the active machine file and its tables (machine_checksum.hpp)
  // Parameters.
  hal_float_t ramp_time;                  // s: 0 -> 1 (and back) takes this long
  hal_float_t max_correction_mm;          // largest linear joint correction allowed
  hal_float_t max_correction_deg;         // largest rotary joint correction allowed
  hal_float_t pole_fade_start_deg;        // phi0 (model.md): no orientation correction below
  hal_float_t pole_fade_full_deg;         // phi1: full orientation correction above
  hal_float_t tool_offset_slew_time;      // s: a tool length offset change reaches the correction in this time
  hal_float_t temperature_time_constant;  // s: of the low-pass on every temperature input
  // State of the ramp (only volkins.update writes it), and of each type's (ramp-time too).
  vc::kins::GainRamp ramp;
  vc::kins::GainRamp switch_ramp[kSwitches];
  // Each temperature input low-passed; the correction takes reference + thermal gain x (this -
  // reference).
  double temperature_state[kMaxTemperatures];
  // Clamped rotary joints, by model joint (only volkins.update writes it): what each holds and
  // how far it is released, its release ramp, whether it was clamped in the last cycle, and the
  // last inverse's correction of every joint (what a joint clamped now keeps).
  vm::HeldRotary holding;
  vc::kins::GainRamp release_ramp[vm::kMaxAxes];
  bool was_clamped[vm::kMaxAxes];
  double last_correction[vm::kMaxAxes];
  // Whether volkins.update has run, and whether the kinematics ran before it did (then it
  // applied the full correction, and the ramp starts there: no step when update starts).
  bool update_ran;
  bool kinematics_before_update;
  // The tool length offset the correction follows (volkins.update slews it to volkins.tool-offset
  // with a bounded rate and change of rate, so that a G43 does not step the joints by angular
  // error x change of L, nor a second one during the slew their velocity).
  vc::kins::ToolLengthSlew offset;  // mm
  double correction_length_mm;      // the correction's L (volkins.correction-length in mm)
  // What the correction is evaluated at, beside the model: each temperature input low-passed
  // (from its reference at load, held while it is faulty) and the pole fade of the pins.
  vm::Conditions conditions;
};

// The kinematics type motion selected (0 or 1: settings->kinematics_types) and whether the
// commanded position moved in the last servo cycle (a switch is refused then). The servo
// thread alone reads and writes them: kinematicsSwitch runs at the start of motion-controller,
// after volkins.update has compared the last inverse's pose with the one of the cycle before.
struct KinematicsType {
  int type = 0;
  EmcPose last_inverse_pose{};  // the pose of the newest kinematicsInverse call
  EmcPose pose_at_update{};     // last_inverse_pose when volkins.update last ran
  bool pose_known = false;      // pose_at_update holds an inverse's pose of this world
  bool moving = false;          // it changed between the last two volkins.update calls
};
KinematicsType kinematics;

// Built in rtapi_app_main; replaced only by volkins.update (a reload, between two kinematics
// calls of the same servo thread), the replaced one deleted by the reload worker.
const vc::kins::ModuleSettings* settings = nullptr;
vc::kins::ReloadWorker* reload_worker = nullptr;  // its thread: made in rtapi_app_main, joined in rtapi_app_exit
vc::kins::ReloadSequence reload_sequence;         // the servo thread's half
HalData* hal = nullptr;
int comp_id = -1;

// The corrections (q_c - q_n) of the last four inverses, servo thread only. The next inverse
// starts at its nominal joints plus the quadratic extrapolation of the last three (the
// correction moves smoothly, by the error slopes times the step: from there one Newton step is
// left as a rule, where a start at the previous joints, a whole step away, takes three). The
// forward's feedback is the cubic interpolator's way point two commands back, (p[k-3] + 4 p[k-2]
// + p[k-1]) / 6 (cubic.c), plus the following error: its start is the feedback less the same
// combination of the corrections, ~1e-9 off, close enough for the ideal machine's one Newton
// step to be proved rather than evaluated (invert_correction.hpp).
struct KeptCorrections {
  std::array<Joints, 4> corrections;  // newest first
  int kept = 0;                       // how many are set
  void keep(const Joints& correction) {
    for (int i = 3; i > 0; --i) corrections[i] = corrections[i - 1];
    corrections[0] = correction;
    kept = std::min(kept + 1, 4);
  }
  void forget() { kept = 0; }
  const Joints* for_forward(Joints& way_point) const {
    if (kept < 4) return kept > 0 ? &corrections[0] : nullptr;
    way_point = (corrections[3] + 4.0 * corrections[2] + corrections[1]) / 6.0;
    return &way_point;
  }
  const Joints* for_inverse(Joints& extrapolated) const {
    if (kept < 3) return kept > 0 ? &corrections[0] : nullptr;
    extrapolated = 3.0 * (corrections[0] - corrections[1]) + corrections[2];
    return &extrapolated;
  }
};
// The corrections applied, and the full ones without the pole fade (the same outside the fade
// band; none at the pole, where the inverse does not solve them): in the band the inverse's
// full Newton and the forward's estimate of the full correction start from these.
KeptCorrections applied_corrections, full_corrections;

char* machine = nullptr;
char* coordinates = nullptr;
char* world = nullptr;
char* sparm = nullptr;
char* units = nullptr;

// A field of LinuxCNC's EmcPose by its index in x y z a b c u v w (const or not).
template <class Pose>
auto& pose_field(Pose& pose, int field) {
  switch (field) {
    case 0:
      return pose.tran.x;
    case 1:
      return pose.tran.y;
    case 2:
      return pose.tran.z;
    case 3:
      return pose.a;
    case 4:
      return pose.b;
    case 5:
      return pose.c;
    case 6:
      return pose.u;
    case 7:
      return pose.v;
    default:
      return pose.w;
  }
}

vm::WorldConvention current_world() { return settings->kinematics_types[kinematics.type]; }

// Where LinuxCNC's numbers cross into the model and back: motion works in its LINEAR_UNITS
// (units=; mm or inch) and degrees, the model in mm and degrees.
double mm_of(double length) { return length * settings->mm_per_unit; }
double linuxcnc_length(double mm) { return mm / settings->mm_per_unit; }

// LinuxCNC's tool length offset (volkins.tool-offset, G43), mm.
double tool_offset_mm() { return mm_of(*hal->tool_offset); }

// LinuxCNC's world position as the core's world (TCP: less the tool length G43 added to Z).
Joints world_of(const EmcPose& pose, double tool_length_mm) {
  Joints w(settings->model.joint_count());
  for (int j = 0; j < w.size(); ++j) w[j] = pose_field(pose, settings->pose_field[j]) * settings->linear_scale[j];
  if (current_world() == vm::WorldConvention::Tcp) w[settings->z_joint] -= tool_length_mm;
  return w;
}

void set_world(EmcPose& pose, Joints w, double tool_length_mm) {
  if (current_world() == vm::WorldConvention::Tcp) w[settings->z_joint] += tool_length_mm;
  for (int j = 0; j < w.size(); ++j) pose_field(pose, settings->pose_field[j]) = w[j] / settings->linear_scale[j];
}

// The machine file's joints from LinuxCNC's (each axis's principal joint), and back.
Joints model_joints(const double* joints) {
  Joints q(settings->model.joint_count());
  for (int j = 0; j < q.size(); ++j) q[j] = joints[settings->principal_joint[j]] * settings->linear_scale[j];
  return q;
}
double linuxcnc_joint(const Joints& q, int j) { return q[j] / settings->linear_scale[j]; }

// The tool-axis coordinate's value (5axiskins' W; 0 without one), mm: the nominal TCP kinematics
// place the tip of a tool this much longer than the real one on the world point.
double tool_axis_of(const EmcPose& pose) {
  return settings->tool_axis_field >= 0 ? mm_of(pose_field(pose, settings->tool_axis_field)) : 0.0;
}

bool same_pose(const EmcPose& a, const EmcPose& b) {
  for (int field = 0; field < 9; ++field)
    if (pose_field(a, field) != pose_field(b, field)) return false;
  return true;
}

void show_kinematics_type() {
  for (int t = 0; t < 3; ++t) *hal->kinstype_is[t] = t == kinematics.type;
  *hal->tcp = current_world() == vm::WorldConvention::Tcp;
}

// The switches' gains into the conditions the correction is evaluated at: each basic type's
// scales its terms, FOR's the pole fade, thermal's takes each temperature from its reference
// (0) to its filtered reading (1).
void set_switched_conditions() {
  vm::Conditions& c = hal->conditions;
  for (int t = 0; t < kBasicTypes; ++t) c.type_gain[t] = *hal->switch_gain[t];
  c.fade.orientation = *hal->switch_gain[kForSwitch];
  const double thermal = *hal->switch_gain[kThermalSwitch];
  for (std::size_t i = 0; i < settings->model.temperatures.size(); ++i) {
    const double reference = settings->model.temperatures[i].reference_degC;
    c.temperature_degC[i] = reference + thermal * (hal->temperature_state[i] - reference);
  }
}

// All of the machine file is applied (no type off or on its way): the contraction bound, made
// for the whole model, holds.
bool everything_switched_on() { return hal->conditions.all_types_on() && hal->conditions.fade.orientation == 1.0; }

// Clamped rotary joints (held_rotary.hpp): a rotary joint is clamped unless motion asks it
// unlocked and the clamp says it is (LinuxCNC's locking indexer: volkins.joint.N.unlock and
// .is-unlocked netted to the signals of joint.N.unlock and joint.N.is-unlocked; motion moves the
// joint only then), and while volkins.joint.N.locked is set (a clamp LinuxCNC does not manage).
// Clamped, it keeps the correction the
// last inverse gave it; unclamped, its release ramps to 1 in ramp-time (the enable's follower),
// taking it back to its free correction.
void update_clamps(double period_s) {
  for (int j = 0; j < settings->model.joint_count(); ++j) {
    if (settings->model.axes[j].type != vm::AxisType::Rotary) continue;
    const int k = settings->principal_joint[j];
    const bool clamped = *hal->locked[k] || !*hal->unlock[k] || !*hal->is_unlocked[k];
    if (clamped) {
      if (!hal->was_clamped[j]) hal->holding.offset_deg[j] = hal->last_correction[j];
      hal->release_ramp[j] = {0.0, 0.0};
    } else {
      hal->release_ramp[j].step(1.0, period_s, hal->ramp_time);
    }
    hal->holding.release[j] = hal->release_ramp[j].gain;
    hal->was_clamped[j] = clamped;
    *hal->held[k] = hal->holding.release[j] < 1.0;
  }
}

// A reload's step (reload_worker.hpp): at rest, at the gain of 0 it swaps the settings; then
// what the old file seeded or set is forgotten: the kept corrections (the solvers' starts), and
// the pole fade pins where they still hold the old file's values (the user did not set them).
// Held rotary joints need not be reset: a reload is refused while one is held.
void update_reload(double period_s) {
  const vm::Model& old_model = settings->model;
  const double old_fade_start = old_model.fade.start_rad * kDegPerRad, old_fade_full = old_model.fade.full_rad * kDegPerRad;
  bool held = false;
  for (int j = 0; j < old_model.joint_count(); ++j) held |= hal->holding.release[j] < 1.0;
  if (reload_sequence.step(*reload_worker, settings, *hal->reload, kinematics.moving, held, hal->ramp, period_s,
                           hal->ramp_time)) {
    applied_corrections.forget();
    full_corrections.forget();
    const vm::Model& model = settings->model;  // the new file's
    if (hal->pole_fade_start_deg == old_fade_start && hal->pole_fade_full_deg == old_fade_full) {
      hal->pole_fade_start_deg = model.fade.start_rad * kDegPerRad;
      hal->pole_fade_full_deg = model.fade.full_rad * kDegPerRad;
    }
  }
  *hal->reload_state = reload_sequence.state;
  *hal->reload_failed = reload_sequence.failed;
  *hal->reloads = reload_sequence.reloads;
  *hal->checksum = reload_sequence.checksum;
}

// Servo thread, before motion-controller: moves the ramp one period towards volkins.enable and
// the correction's tool length towards volkins.tool-offset (gain_ramp.hpp: bounded rate and
// change of rate, so joint velocity stays continuous, also when either changes on the way),
// low-passes the temperatures and takes up valid pole fade parameters.
void update(void*, long period_ns) {
  const double target = *hal->enable ? 1.0 : 0.0;
  if (!hal->update_ran) {
    hal->update_ran = true;
    *hal->update_missing = 0;
    if (hal->kinematics_before_update) hal->ramp = {target, 0.0};  // where the kinematics were
    // The types start where their pins are: the correction is still off (or, after the
    // kinematics ran without update, the pins applied at once), so nothing moves.
    for (int k = 0; k < kSwitches; ++k) hal->switch_ramp[k] = {*hal->switch_enable[k] ? 1.0 : 0.0, 0.0};
    hal->offset.reset(tool_offset_mm());
  }
  hal->ramp.step(target, period_ns * 1e-9, hal->ramp_time);
  for (int k = 0; k < kSwitches; ++k) {
    hal->switch_ramp[k].step(*hal->switch_enable[k] ? 1.0 : 0.0, period_ns * 1e-9, hal->ramp_time);
    *hal->switch_gain[k] = hal->switch_ramp[k].gain;
  }
  kinematics.moving = kinematics.pose_known && !same_pose(kinematics.last_inverse_pose, kinematics.pose_at_update);
  kinematics.pose_at_update = kinematics.last_inverse_pose;
  kinematics.pose_known = true;
  update_reload(period_ns * 1e-9);
  // The fraction applied: the enable's ramp times the reload's (1 but while a file is swapped):
  // volkins.enable off wins.
  *hal->gain = hal->ramp.gain * reload_sequence.ramp.gain;
  *hal->active = *hal->gain > 0.0;

  hal->offset.step(tool_offset_mm(), period_ns * 1e-9, hal->tool_offset_slew_time);
  hal->correction_length_mm = settings->model.correction_length(hal->offset.length.value);
  *hal->correction_length = linuxcnc_length(hal->correction_length_mm);

  // Temperatures: a first-order low-pass (sensor noise never reaches the joints); a reading
  // that is not a number or lies outside the model's range is not taken: the last good value
  // is held and volkins.temperature-fault raised while it lasts.
  bool fault = false;
  const double dt = period_ns * 1e-9, tau = std::max(0.0, static_cast<double>(hal->temperature_time_constant));
  for (std::size_t i = 0; i < settings->model.temperatures.size(); ++i) {
    const vm::TemperatureInput& input = settings->model.temperatures[i];
    const double reading = *hal->temperature[i];
    double& state = hal->temperature_state[i];
    if (std::isfinite(reading) && reading >= input.min_degC && reading <= input.max_degC) {
      state += (reading - state) * dt / (tau + dt);
    } else {
      fault = true;
    }
    *hal->temperature_filtered[i] = state;
  }
  *hal->temperature_fault = fault;
  set_switched_conditions();
  update_clamps(dt);

  const double start = hal->pole_fade_start_deg, full = hal->pole_fade_full_deg;
  if (start >= 0.0 && full > start && full <= 90.0) {
    hal->conditions.fade.start_rad = start / kDegPerRad;
    hal->conditions.fade.full_rad = full / kDegPerRad;
  }
}

int refuse() {
  ++*hal->failures;
  return -1;
}

// The L the correction is computed for: the slewed tool length, or, while volkins.update has
// never run, LinuxCNC's offset as it is.
double correction_length() {
  if (!hal->update_ran) {
    hal->correction_length_mm = settings->model.correction_length(tool_offset_mm());
    *hal->correction_length = linuxcnc_length(hal->correction_length_mm);
  }
  return hal->correction_length_mm;
}

// The fraction of the correction the kinematics apply: the ramp's, or, while volkins.update has
// never run (not in a thread), all of it as volkins.enable asks, reported on the pins.
double applied_gain() {
  if (hal->update_ran) return *hal->gain;
  const double gain = *hal->enable ? 1.0 : 0.0;
  *hal->gain = gain;
  *hal->active = gain > 0.0;
  *hal->update_missing = 1;
  for (int k = 0; k < kSwitches; ++k) *hal->switch_gain[k] = *hal->switch_enable[k] ? 1.0 : 0.0;
  set_switched_conditions();
  if (!hal->kinematics_before_update) {  // once: the first call
    hal->kinematics_before_update = true;
    rtapi_print_msg(RTAPI_MSG_ERR,
                    "volkins: volkins.update has not run before the kinematics: the correction is applied in full "
                    "without its ramp (volkins.enable steps the joints). Add 'addf volkins.update servo-thread 1' to "
                    "the HAL file (kins/configs/common/volkins.hal)\n");
  }
  return gain;
}

// kinematicsInverse's work; the exported function times it.
int inverse(const EmcPose* pose, double* joints) {
  const vm::Model& model = settings->model;
  const int n = model.joint_count();
  const double offset = tool_offset_mm();  // LinuxCNC's tool length offset (G43)
  const double L = correction_length();    // the tool-length rule, slewed
  const double w = tool_axis_of(*pose);
  const Joints previous = model_joints(joints);  // LinuxCNC's seed: its principal joints
  kinematics.last_inverse_pose = *pose;
  Joints extrapolated, extrapolated_full;
  const bool holding = hal->holding.any(model);  // a rotary joint clamped: the held path, unseeded
  const vm::Applied applied{
      applied_gain(),
      &previous,
      holding ? nullptr : applied_corrections.for_inverse(extrapolated),
      !holding && everything_switched_on() && settings->contraction ? &*settings->contraction : nullptr,
      holding ? nullptr : full_corrections.for_inverse(extrapolated_full),
      model.correction_length(offset) + w,
      &hal->conditions,
      &hal->holding};
  Joints q;
  vm::Correction report;
  const vm::Status s = vm::joints_from_world(model, current_world(), world_of(*pose, offset), L, applied, q, &report);
  *hal->iterations = report.iterations;
  if (s != vm::Status::Ok) return refuse();
  for (int j = 0; j < n; ++j) hal->last_correction[j] = q[j] - report.nominal[j];
  *hal->direction_error = report.residual_rad * 1e6;
  if (holding) {  // the kept corrections are the free ones': none while a joint is held
    applied_corrections.forget();
    full_corrections.forget();
  } else if (applied.gain > 0.0) {
    const Joints correction = report.joints - report.nominal;
    applied_corrections.keep(correction);
    if (report.full_joints.size() > 0)
      full_corrections.keep(report.full_joints - report.nominal);
    else if (report.fade == 1.0)  // the full correction is the one applied
      full_corrections.keep(correction);
    else
      full_corrections.forget();
  }
  bool too_large = false;
  for (int j = 0; j < n; ++j) {
    const double limit = model.axes[j].type == vm::AxisType::Linear ? hal->max_correction_mm : hal->max_correction_deg;
    too_large |= !(std::abs(q[j] - report.nominal[j]) <= limit);
  }
  for (int k = 0; k < settings->joint_count; ++k) {
    const int j = settings->model_joint[k];
    *hal->correction[k] = j >= 0 ? (q[j] - report.nominal[j]) / settings->linear_scale[j] : 0.0;
  }
  *hal->out_of_table = vm::outside_tables(model, q);
  *hal->limit_exceeded = too_large;
  if (too_large) return refuse();
  for (int k = 0; k < settings->joint_count; ++k) {
    const int j = settings->model_joint[k];
    joints[k] = j >= 0 ? linuxcnc_joint(q, j) : linuxcnc_length(w);  // the tool-axis joint: the world's coordinate
  }
  return 0;
}

}  // namespace

extern "C" {

// Timed (volkins.inverse-time, ns, the monotonic clock rtapi_get_time reads: no allocation, lock
// or I/O; clamped to the pin's range).
int kinematicsInverse(const EmcPose* pose, double* joints, const KINEMATICS_INVERSE_FLAGS*, KINEMATICS_FORWARD_FLAGS*) {
  const long long start = rtapi_get_time();
  const int result = inverse(pose, joints);
  *hal->inverse_time = static_cast<std::int32_t>(std::min(rtapi_get_time() - start, 2147483647LL));
  return result;
}

int kinematicsForward(const double* joints, EmcPose* pose, const KINEMATICS_FORWARD_FLAGS*, KINEMATICS_INVERSE_FLAGS*) {
  const vm::Model& model = settings->model;
  const Joints q = model_joints(joints);  // the principal joint of each axis, as LinuxCNC's modules read them
  const double offset = tool_offset_mm();
  const double L = correction_length();
  const double tool_axis = settings->tool_axis_joint >= 0 ? mm_of(joints[settings->tool_axis_joint]) : 0.0;
  const Joints seed = world_of(*pose, offset);  // LinuxCNC passes the previous position (or home)
  Joints w, way_point, way_point_full;
  int iterations = 0;
  const vm::Applied applied{applied_gain(),
                            &seed,
                            applied_corrections.for_forward(way_point),
                            nullptr,
                            full_corrections.for_forward(way_point_full),
                            model.correction_length(offset) + tool_axis,
                            &hal->conditions,
                            &hal->holding};
  const vm::Status s = vm::world_from_joints(model, current_world(), q, L, applied, w, &iterations);
  *hal->forward_iterations = iterations;
  if (s != vm::Status::Ok) return refuse();
  set_world(*pose, w, offset);
  if (settings->tool_axis_field >= 0) pose_field(*pose, settings->tool_axis_field) = linuxcnc_length(tool_axis);
  return 0;
}

KINEMATICS_TYPE kinematicsType() { return KINEMATICS_BOTH; }

int kinematicsSwitchable() { return 1; }

// Called by motion-controller when motion.switchkins-type changes; motion then recomputes its
// world position with the forward of the joint commands (the joints do not move). Refused
// (motion aborts) for a type volkins does not have and while the commanded position moves.
int kinematicsSwitch(int type) {
  static const char* const names[] = {"identity", "TCP"};
  if (type < 0 || type >= settings->kinematics_type_count()) {
    rtapi_print_msg(RTAPI_MSG_ERR,
                    "volkins: kinematics type %d refused: volkins has %s (motion.switchkins-type %s); it stays in "
                    "type %d (%s)\n",
                    type, settings->kinematics_type_count() == 2 ? "types 0 and 1" : "type 0 only (no Z axis: no TCP)",
                    settings->kinematics_type_count() == 2 ? "0 or 1" : "0", kinematics.type,
                    names[current_world() == vm::WorldConvention::Tcp]);
    return -1;
  }
  if (type == kinematics.type) return 0;
  if (kinematics.moving) {
    rtapi_print_msg(
        RTAPI_MSG_ERR,
        "volkins: switch to kinematics type %d refused while the commanded position moves (the queued moves "
        "are in the old world's coordinates); volkins stays in type %d (%s). Switch at rest: M66 E0 L0 "
        "before and after setting motion.switchkins-type, as LinuxCNC's M428/M429 remaps do\n",
        type, kinematics.type, names[current_world() == vm::WorldConvention::Tcp]);
    return -1;
  }
  kinematics.type = type;
  kinematics.pose_known = false;  // the next inverse's pose is in the new world
  if (hal) show_kinematics_type();
  return 0;
}

EXPORT_SYMBOL(kinematicsType);
EXPORT_SYMBOL(kinematicsSwitchable);
EXPORT_SYMBOL(kinematicsSwitch);
EXPORT_SYMBOL(kinematicsForward);
EXPORT_SYMBOL(kinematicsInverse);

MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("Kinematics with volumetric error correction (volcomp)");
RTAPI_MP_STRING(machine, "machine description file (TOML)");
RTAPI_MP_STRING(coordinates, "axis letter of each joint (default: the machine file's axes in its order)");
RTAPI_MP_STRING(world, "world convention of kinematics type 0: axes (default) or tcp");
RTAPI_MP_STRING(sparm, "identityfirst: kinematics type 0 is the identity (as LinuxCNC's trt modules)");
RTAPI_MP_STRING(units, "LinuxCNC's [TRAJ]LINEAR_UNITS: mm (default) or inch");

}  // extern "C"

namespace {

// HAL pins, parameters and the update function; false (after a message) if HAL refused one.
bool export_hal(const vm::Model& model) {
  hal = static_cast<HalData*>(hal_malloc(sizeof(HalData)));
  if (!hal) return false;
  int r = 0;
  r |= hal_pin_bit_newf(HAL_IN, &hal->enable, comp_id, "volkins.enable");
  // volkins.tool-offset: LinuxCNC's tool length offset, the name its own 5-axis modules give it
  // (xyzbc-trt-kins.tool-offset); Model::tool_length_mm is the physical tool. Made under the
  // name of releases before 2026-12 and renamed by an alias, so that configurations that net
  // volkins.tool-length (and setp volkins.tool-length-slew-time) still load, for one release.
  r |= hal_pin_float_newf(HAL_IN, &hal->tool_offset, comp_id, "volkins.tool-length");
  r |= hal_pin_alias("volkins.tool-length", "volkins.tool-offset");
  r |= hal_pin_float_newf(HAL_OUT, &hal->gain, comp_id, "volkins.gain");
  r |= hal_pin_bit_newf(HAL_OUT, &hal->active, comp_id, "volkins.active");
  r |= hal_pin_bit_newf(HAL_OUT, &hal->update_missing, comp_id, "volkins.update-missing");
  r |= hal_pin_float_newf(HAL_OUT, &hal->correction_length, comp_id, "volkins.correction-length");
  r |= hal_param_float_newf(HAL_RW, &hal->tool_offset_slew_time, comp_id, "volkins.tool-length-slew-time");
  r |= hal_param_alias("volkins.tool-length-slew-time", "volkins.tool-offset-slew-time");
  for (int k = 0; k < settings->joint_count; ++k)
    r |= hal_pin_float_newf(HAL_OUT, &hal->correction[k], comp_id, "volkins.joint.%d.correction", k);
  r |= hal_pin_s32_newf(HAL_OUT, &hal->iterations, comp_id, "volkins.iterations");
  r |= hal_pin_s32_newf(HAL_OUT, &hal->forward_iterations, comp_id, "volkins.forward-iterations");
  r |= hal_pin_bit_newf(HAL_OUT, &hal->out_of_table, comp_id, "volkins.out-of-table");
  r |= hal_pin_bit_newf(HAL_OUT, &hal->limit_exceeded, comp_id, "volkins.limit-exceeded");
  r |= hal_pin_s32_newf(HAL_OUT, &hal->failures, comp_id, "volkins.failures");
  r |= hal_pin_s32_newf(HAL_OUT, &hal->inverse_time, comp_id, "volkins.inverse-time");
  r |= hal_param_float_newf(HAL_RW, &hal->ramp_time, comp_id, "volkins.ramp-time");
  r |= hal_param_float_newf(HAL_RW, &hal->max_correction_mm, comp_id, "volkins.max-correction-mm");
  r |= hal_param_float_newf(HAL_RW, &hal->max_correction_deg, comp_id, "volkins.max-correction-deg");
  r |= hal_param_float_newf(HAL_RW, &hal->pole_fade_start_deg, comp_id, "volkins.pole-fade-start-deg");
  r |= hal_param_float_newf(HAL_RW, &hal->pole_fade_full_deg, comp_id, "volkins.pole-fade-full-deg");
  for (std::size_t i = 0; i < model.temperatures.size(); ++i) {
    const char* name = model.temperatures[i].name.c_str();
    r |= hal_pin_float_newf(HAL_IN, &hal->temperature[i], comp_id, "volkins.temperature.%s", name);
    r |= hal_pin_float_newf(HAL_OUT, &hal->temperature_filtered[i], comp_id, "volkins.temperature.%s.filtered", name);
  }
  r |= hal_pin_bit_newf(HAL_OUT, &hal->temperature_fault, comp_id, "volkins.temperature-fault");
  r |= hal_param_float_newf(HAL_RW, &hal->temperature_time_constant, comp_id, "volkins.temperature-time-constant");
  // LinuxCNC's switchable modules' pins, under their names (GUIs and programs read them).
  for (int t = 0; t < 3; ++t) r |= hal_pin_bit_newf(HAL_OUT, &hal->kinstype_is[t], comp_id, "kinstype.is-%d", t);
  r |= hal_pin_bit_newf(HAL_OUT, &hal->tcp, comp_id, "volkins.tcp");
  r |= hal_pin_float_newf(HAL_OUT, &hal->direction_error, comp_id, "volkins.direction-error-urad");
  for (int k = 0; k < settings->joint_count; ++k) {
    hal->unlock[k] = hal->is_unlocked[k] = hal->locked[k] = hal->held[k] = nullptr;
    const int j = settings->model_joint[k];
    if (j < 0 || model.axes[j].type != vm::AxisType::Rotary || settings->principal_joint[j] != k) continue;
    r |= hal_pin_bit_newf(HAL_IN, &hal->unlock[k], comp_id, "volkins.joint.%d.unlock", k);
    r |= hal_pin_bit_newf(HAL_IN, &hal->is_unlocked[k], comp_id, "volkins.joint.%d.is-unlocked", k);
    r |= hal_pin_bit_newf(HAL_IN, &hal->locked[k], comp_id, "volkins.joint.%d.locked", k);
    r |= hal_pin_bit_newf(HAL_OUT, &hal->held[k], comp_id, "volkins.joint.%d.held", k);
  }
  // One switch per compensation type, named by its Annex A code in lower case
  // (volkins.type.l-pos.enable), FOR's volkins.type.for.enable, and volkins.thermal.enable.
  for (int k = 0; k < kSwitches; ++k) {
    char name[32];
    if (k == kThermalSwitch) {
      std::snprintf(name, sizeof name, "thermal");
    } else {
      const std::string_view code = k == kForSwitch ? "FOR" : vm::basic_type_code(static_cast<vm::BasicType>(k));
      std::snprintf(name, sizeof name, "type.%.*s", static_cast<int>(code.size()), code.data());
      for (char* c = name; *c; ++c) *c = static_cast<char>(*c >= 'A' && *c <= 'Z' ? *c - 'A' + 'a' : *c);
    }
    r |= hal_pin_bit_newf(HAL_IN, &hal->switch_enable[k], comp_id, "volkins.%s.enable", name);
    r |= hal_pin_float_newf(HAL_OUT, &hal->switch_gain[k], comp_id, "volkins.%s.gain", name);
  }
  r |= hal_pin_bit_newf(HAL_IN, &hal->reload, comp_id, "volkins.reload");
  r |= hal_pin_s32_newf(HAL_OUT, &hal->reload_state, comp_id, "volkins.reload-state");
  r |= hal_pin_bit_newf(HAL_OUT, &hal->reload_failed, comp_id, "volkins.reload-failed");
  r |= hal_pin_s32_newf(HAL_OUT, &hal->reloads, comp_id, "volkins.reloads");
  r |= hal_pin_u32_newf(HAL_OUT, &hal->checksum, comp_id, "volkins.checksum");
  r |= hal_export_funct("volkins.update", update, nullptr, 1 /* uses floating point */, 0, comp_id);
  if (r) return false;

  // Defaults: correction on (after the ramp), the machine file's tool length and pole fade.
  *hal->enable = 1;
  // Not netted: the typical tool's offset, so that L = the machine file's tool_length_mm.
  *hal->tool_offset = linuxcnc_length(model.tool_length_mm - model.tool_length_reference_mm);
  *hal->gain = 0.0;
  *hal->active = 0;
  *hal->update_missing = 0;
  hal->ramp = vc::kins::GainRamp{};
  hal->update_ran = false;
  hal->kinematics_before_update = false;
  hal->tool_offset_slew_time = 0.25;
  hal->offset.reset(tool_offset_mm());
  hal->correction_length_mm = model.correction_length(tool_offset_mm());
  *hal->correction_length = linuxcnc_length(hal->correction_length_mm);
  hal->conditions = model.reference_conditions();  // until a sensor says otherwise
  for (std::size_t i = 0; i < model.temperatures.size(); ++i)
    *hal->temperature[i] = *hal->temperature_filtered[i] = hal->temperature_state[i] =
        hal->conditions.temperature_degC[i];
  hal->holding = vm::HeldRotary{};  // every joint free
  for (int j = 0; j < vm::kMaxAxes; ++j) {
    hal->release_ramp[j] = {1.0, 0.0};
    hal->was_clamped[j] = false;
    hal->last_correction[j] = 0.0;
  }
  for (int k = 0; k < settings->joint_count; ++k)
    if (hal->is_unlocked[k]) {
      *hal->unlock[k] = *hal->is_unlocked[k] = 1;
      *hal->locked[k] = 0;
      *hal->held[k] = 0;
    }
  *hal->direction_error = 0.0;
  for (int k = 0; k < kSwitches; ++k) {  // every type on
    *hal->switch_enable[k] = 1;
    *hal->switch_gain[k] = 1.0;
    hal->switch_ramp[k] = {1.0, 0.0};
  }
  *hal->temperature_fault = 0;
  hal->temperature_time_constant = 10.0;
  hal->ramp_time = 1.0;
  hal->max_correction_mm = 1.0;
  hal->max_correction_deg = 0.1;
  hal->pole_fade_start_deg = model.fade.start_rad * kDegPerRad;
  hal->pole_fade_full_deg = model.fade.full_rad * kDegPerRad;
  kinematics = KinematicsType{};
  show_kinematics_type();
  *hal->reload = 0;
  *hal->reload_state = reload_sequence.state;
  *hal->reload_failed = 0;
  *hal->reloads = 0;
  *hal->checksum = reload_sequence.checksum;
  return true;
}

}  // namespace

extern "C" int rtapi_app_main(void) {
  // Everything that can fail on the user's files happens before HAL sees the component, so a
  // refused machine file leaves nothing loaded.
  try {
    settings =
        new vc::kins::ModuleSettings(vc::kins::settings_from_parameters(machine, coordinates, world, sparm, units));
  } catch (const std::exception& e) {
    rtapi_print_msg(RTAPI_MSG_ERR, "volkins: %s\n", e.what());
    return -EINVAL;
  } catch (...) {
    rtapi_print_msg(RTAPI_MSG_ERR, "volkins: unknown error while loading the machine file\n");
    return -EINVAL;
  }
  const vm::Model& model = settings->model;
  for (const vc::Warning& w : model.warnings) rtapi_print_msg(RTAPI_MSG_WARN, "volkins: %s\n", w.to_string().c_str());
  reload_sequence = vc::kins::ReloadSequence{};
  try {
    reload_sequence.checksum = vm::machine_checksum(model);
  } catch (const std::exception& e) {  // read a moment ago: only if it was removed since
    rtapi_print_msg(RTAPI_MSG_ERR, "volkins: %s\n", e.what());
    delete settings;
    settings = nullptr;
    return -EINVAL;
  }
  // The reload worker's thread: the same module parameters, its messages printed as loadrt's.
  try {
    reload_worker = new vc::kins::ReloadWorker(
        settings,
        [] {
          return std::make_unique<vc::kins::ModuleSettings>(
              vc::kins::settings_from_parameters(machine, coordinates, world, sparm, units));
        },
        [](const vm::Model& m) { return vm::machine_checksum(m); },
        [](const std::string& message) { rtapi_print_msg(RTAPI_MSG_ERR, "volkins: %s\n", message.c_str()); });
  } catch (const std::exception& e) {
    rtapi_print_msg(RTAPI_MSG_ERR, "volkins: cannot start the reload thread: %s\n", e.what());
    delete settings;
    settings = nullptr;
    return -ENOMEM;
  }

  comp_id = hal_init("volkins");
  if (comp_id < 0) {
    delete reload_worker;
    reload_worker = nullptr;
    delete settings;
    settings = nullptr;
    return comp_id;
  }
  if (!export_hal(model)) {
    rtapi_print_msg(RTAPI_MSG_ERR, "volkins: cannot create its HAL pins\n");
    hal_exit(comp_id);
    delete reload_worker;
    reload_worker = nullptr;
    delete settings;
    settings = nullptr;
    return -ENOMEM;
  }
  rtapi_print_msg(RTAPI_MSG_INFO, "volkins: %s (%s, %d tables), joints %s in %s, kinematics type 0 %s\n",
                  model.path.c_str(), model.info.name.c_str(), static_cast<int>(model.tables.size()),
                  model.coordinates().c_str(), settings->mm_per_unit == 1.0 ? "mm" : "inch",
                  settings->kinematics_types[0] == vm::WorldConvention::Tcp ? "tcp" : "identity (axes)");
  hal_ready(comp_id);
  return 0;
}

extern "C" void rtapi_app_exit(void) {
  hal_exit(comp_id);
  delete reload_worker;  // joins its thread, deletes what it holds
  reload_worker = nullptr;
  delete reload_sequence.incoming;  // taken, not swapped in
  reload_sequence.incoming = nullptr;
  delete settings;
  settings = nullptr;
}
