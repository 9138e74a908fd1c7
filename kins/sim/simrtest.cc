// simrtest: a simulated R-test (ISO 230-1 11.3.5.3, ISO 10791-6): a precision sphere on the table
// of a true machine and a nest of three displacement sensors in its spindle, for running R-test
// programs in a LinuxCNC session without a machine (identify rtest reads what it records).
//
//   loadrt simrtest machine=TRUE.toml centre=X,Y,Z [coordinates=xyzbc] [nest_length=MM]
//                   [range_um=1000] [noise_um=0] [seed=1]
//   addf simrtest.update servo-thread 1           (before motion-controller)
//   net j0 => simrtest.joint.0   ...              (the joint positions motion feeds back)
//
// The sphere is fixed on the table of the TRUE machine (its machine file, with every error): its
// centre is where that machine puts the nest's centre (nest_length from the gauge point, default
// the file's tool length) at the joints `centre` with the rotary axes at 0. Every servo period
// the sensors read the sphere's centre against the nest's centre along the spindle frame's x, y,
// z (the true machine's real pose, its 4x4 chain: on a head the frame turns with the spindle):
// simrtest.dx-um, .dy-um, .dz-um, error = actual - nominal as identify rtest takes them, each
// clipped to +-range_um where the sphere leaves the sensors' range (simrtest.in-range then
// FALSE), plus Gaussian noise of noise_um drawn anew each period from `seed`.
// Servo thread: no allocation, no locks, no I/O.

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include "module_settings.hpp"
#include "sim_parameters.hpp"
#include "vc/machine/forward.hpp"

#include "rtapi.h"
#include "hal.h"
extern "C" {
#include "rtapi_app.h"
}

namespace {

namespace vm = vc::machine;

struct HalData {
  hal_float_t* joint[vm::kMaxAxes];  // in: joint positions (mm, deg)
  hal_float_t* reading_um[3];        // out: dx, dy, dz
  hal_bit_t* in_range;               // out: every sensor within its range
};

struct Nest {
  vm::Model model;
  Eigen::Vector3d sphere_mm;  // the sphere's centre in the true machine's part frame
  double length_mm = 0;       // gauge point to the nest's centre
  double range_mm = 0;
  double noise_mm = 0;
  std::uint64_t random = 0;
};

Nest* nest = nullptr;
HalData* hal = nullptr;
int comp_id = -1;

char* machine = nullptr;
char* coordinates = nullptr;
char* centre = nullptr;
char* nest_length = nullptr;
char* range_um = nullptr;
char* noise_um = nullptr;
int seed = 1;

// Servo thread, before motion-controller.
void update(void*, long) {
  const vm::Model& model = nest->model;
  vm::Joints q(model.joint_count());
  for (int j = 0; j < model.joint_count(); ++j) q[j] = *hal->joint[j];
  const Eigen::Vector3d reading =
      vm::part_T_tool(model, vm::Machine::Real, q, nest->length_mm).inverse() * nest->sphere_mm;
  bool in_range = true;
  for (int d = 0; d < 3; ++d) {
    double v = reading[d];
    if (std::fabs(v) > nest->range_mm) {
      in_range = false;
      v = std::copysign(nest->range_mm, v);
    }
    if (nest->noise_mm > 0) v += nest->noise_mm * vc::sim::normal(nest->random);
    *hal->reading_um[d] = v * 1e3;
  }
  *hal->in_range = in_range;
}

Nest* make_nest() {
  auto* n = new Nest;
  try {
    n->model = vc::kins::settings_from_parameters(machine, coordinates, "axes").model;
    const int x = n->model.joint_of('X'), y = n->model.joint_of('Y'), z = n->model.joint_of('Z');
    if (x < 0 || y < 0 || z < 0) throw std::runtime_error("the machine has no X, Y and Z axes to follow the sphere with");
    double c[3];
    const std::string text = centre ? centre : "";
    if (std::sscanf(text.c_str(), "%lf,%lf,%lf", &c[0], &c[1], &c[2]) != 3)
      throw std::runtime_error(
          "centre=X,Y,Z (mm): the joints at which the nest's centre is at the sphere's, rotary axes at 0");
    n->length_mm = vc::sim::number(nest_length, "nest_length", n->model.tool_length_mm);
    n->range_mm = vc::sim::number(range_um, "range_um", 1000.0) * 1e-3;
    n->noise_mm = vc::sim::number(noise_um, "noise_um", 0.0) * 1e-3;
    if (!(n->range_mm > 0) || !(n->noise_mm >= 0))
      throw std::runtime_error("range_um must be positive and noise_um not negative");
    vm::Joints q = vm::Joints::Zero(n->model.joint_count());
    q[x] = c[0], q[y] = c[1], q[z] = c[2];
    n->sphere_mm = vm::part_T_tool(n->model, vm::Machine::Real, q, n->length_mm).translation();
    n->random = vc::sim::noise_state(seed);
  } catch (...) {
    delete n;
    throw;
  }
  return n;
}

}  // namespace

extern "C" {
MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("Simulated R-test: a sphere and a nest of three displacement sensors on a machine file's real kinematics (volcomp)");
RTAPI_MP_STRING(machine, "the true machine's file (TOML)");
RTAPI_MP_STRING(coordinates, "axis letters, one per joint, in the machine file's order");
RTAPI_MP_STRING(centre, "X,Y,Z (mm): joints putting the nest's centre on the sphere's, rotary axes at 0");
RTAPI_MP_STRING(nest_length, "gauge point to the nest's centre, mm (default: the machine file's tool length)");
RTAPI_MP_STRING(range_um, "each sensor's range, +- um (default 1000)");
RTAPI_MP_STRING(noise_um, "each sensor's noise, um (standard deviation, default 0)");
RTAPI_MP_INT(seed, "seed of the noise");
}

extern "C" int rtapi_app_main(void) {
  try {
    nest = make_nest();
  } catch (const std::exception& e) {
    rtapi_print_msg(RTAPI_MSG_ERR, "simrtest: %s\n", e.what());
    return -EINVAL;
  }
  comp_id = hal_init("simrtest");
  if (comp_id < 0) {
    delete nest;
    return comp_id;
  }
  hal = static_cast<HalData*>(hal_malloc(sizeof(HalData)));
  int r = hal ? 0 : -ENOMEM;
  for (int j = 0; r == 0 && j < nest->model.joint_count(); ++j)
    r |= hal_pin_float_newf(HAL_IN, &hal->joint[j], comp_id, "simrtest.joint.%d", j);
  if (r == 0) {
    for (int d = 0; d < 3; ++d)
      r |= hal_pin_float_newf(HAL_OUT, &hal->reading_um[d], comp_id, "simrtest.d%c-um", "xyz"[d]);
    r |= hal_pin_bit_newf(HAL_OUT, &hal->in_range, comp_id, "simrtest.in-range");
    r |= hal_export_funct("simrtest.update", update, nullptr, 1 /* floating point */, 0, comp_id);
  }
  if (r) {
    rtapi_print_msg(RTAPI_MSG_ERR, "simrtest: cannot create its HAL pins\n");
    hal_exit(comp_id);
    delete nest;
    return r;
  }
  for (int d = 0; d < 3; ++d) *hal->reading_um[d] = 0;
  *hal->in_range = 0;
  const Eigen::Vector3d& c = nest->sphere_mm;
  rtapi_print_msg(RTAPI_MSG_INFO, "simrtest: %s, sphere centre %.4f %.4f %.4f mm (part frame), nest %.4f mm\n",
                  nest->model.path.c_str(), c.x(), c.y(), c.z(), nest->length_mm);
  hal_ready(comp_id);
  return 0;
}

extern "C" void rtapi_app_exit(void) {
  hal_exit(comp_id);
  delete nest;
  nest = nullptr;
}
