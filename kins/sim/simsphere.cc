// simsphere: a simulated touch probe and calibration sphere, for running probing programs
// (volcomp probe-plan) in a LinuxCNC session without a machine.
//
//   loadrt simsphere machine=TRUE.toml centre=X,Y,Z [coordinates=xyzbc] [sphere_diameter=25]
//                    [ball_diameter=2] [probe_length=MM] [noise_um=0] [seed=1]
//   addf simsphere.update servo-thread 1          (before motion-controller)
//   net j0 => simsphere.joint.0   ...             (the joint positions motion feeds back)
//   net probe simsphere.probe => motion.probe-input
//
// The sphere is fixed on the table of the TRUE machine (its machine file, with every error):
// its centre is where that machine puts the probe's ball centre at the joints `centre` with the
// rotary axes at 0. Every servo period the ball's centre is the true machine's real tool tip at
// the joints on simsphere.joint.N and the probe length; simsphere.probe is set while the ball
// touches the sphere. Its period is the one in which motion-controller latches the probe
// position (control.c: process_inputs, forward kinematics, process_probe_inputs, all on the
// same fed-back joints): the trip is exact to the servo period, as with a real probe whose
// input the servo thread samples, and lies up to feed x period past the contact.
//
// noise_um: the probe's repeatability, a trigger point scattered along the approach (gaussian,
// standard deviation noise_um, drawn anew for each touch from `seed`); 0 is a perfect probe.
// Servo thread: no allocation, no locks, no I/O.

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
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
  hal_bit_t* probe;                  // out: the ball touches the sphere
  hal_float_t* gap_um;               // out: ball surface to sphere surface (negative: pressed in)
  hal_s32_t* touches;                // out: trips so far
};

struct Sphere {
  vm::Model model;
  Eigen::Vector3d centre_mm;  // the sphere's centre in the true machine's part frame
  double reach_mm = 0;        // ball centre to sphere centre at contact
  double length_mm = 0;       // probe length: gauge point to ball centre
  double noise_mm = 0;
  double trigger_mm = 0;     // this touch's trigger gap (noise)
  std::uint64_t random = 0;  // xorshift64 state
};

Sphere* sphere = nullptr;
HalData* hal = nullptr;
int comp_id = -1;

char* machine = nullptr;
char* coordinates = nullptr;
char* centre = nullptr;
char* sphere_diameter = nullptr;
char* ball_diameter = nullptr;
char* probe_length = nullptr;
char* noise_um = nullptr;
int seed = 1;

void draw_trigger() {
  const double n = std::fmax(-4.0, std::fmin(4.0, vc::sim::normal(sphere->random)));  // clipped at 4 sigma
  sphere->trigger_mm = sphere->noise_mm * n;
}

// Servo thread, before motion-controller.
void update(void*, long) {
  const vm::Model& model = sphere->model;
  vm::Joints q(model.joint_count());
  for (int j = 0; j < model.joint_count(); ++j) q[j] = *hal->joint[j];
  const Eigen::Vector3d ball = vm::tool_pose(model, vm::Machine::Real, q, sphere->length_mm).tip_mm;
  const double gap = (ball - sphere->centre_mm).norm() - sphere->reach_mm;
  *hal->gap_um = gap * 1e3;
  if (!*hal->probe) {
    if (gap <= sphere->trigger_mm) {
      *hal->probe = 1;
      ++*hal->touches;
    }
  } else if (gap > std::fabs(sphere->trigger_mm) + 0.005 + 4 * sphere->noise_mm) {
    // Released (a hysteresis of 5 um beyond the noise, so it cannot chatter): the next
    // touch's trigger point.
    *hal->probe = 0;
    draw_trigger();
  }
}

Sphere* make_sphere() {
  auto* s = new Sphere;
  try {
    s->model = vc::kins::settings_from_parameters(machine, coordinates, "axes").model;
    const int x = s->model.joint_of('X'), y = s->model.joint_of('Y'), z = s->model.joint_of('Z');
    if (x < 0 || y < 0 || z < 0) throw std::runtime_error("the machine has no X, Y and Z axes to probe with");
    double c[3];
    const std::string text = centre ? centre : "";
    if (std::sscanf(text.c_str(), "%lf,%lf,%lf", &c[0], &c[1], &c[2]) != 3)
      throw std::runtime_error(
          "centre=X,Y,Z (mm): the joints at which the ball's centre is at the sphere's, rotary axes at 0");
    const double diameter = vc::sim::number(sphere_diameter, "sphere_diameter", 25.0);
    const double ball = vc::sim::number(ball_diameter, "ball_diameter", 2.0);
    s->length_mm = vc::sim::number(probe_length, "probe_length", s->model.tool_length_mm);
    s->noise_mm = vc::sim::number(noise_um, "noise_um", 0.0) * 1e-3;
    if (!(diameter > 0) || !(ball >= 0) || !(s->noise_mm >= 0))
      throw std::runtime_error("the diameters must be positive and noise_um not negative");
    s->reach_mm = (diameter + ball) / 2;
    vm::Joints q = vm::Joints::Zero(s->model.joint_count());
    q[x] = c[0], q[y] = c[1], q[z] = c[2];
    s->centre_mm = vm::tool_pose(s->model, vm::Machine::Real, q, s->length_mm).tip_mm;
    s->random = vc::sim::noise_state(seed);
  } catch (...) {
    delete s;
    throw;
  }
  return s;
}

}  // namespace

extern "C" {
MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("Simulated touch probe and calibration sphere on a machine file's real kinematics (volcomp)");
RTAPI_MP_STRING(machine, "the true machine's file (TOML)");
RTAPI_MP_STRING(coordinates, "axis letters, one per joint, in the machine file's order");
RTAPI_MP_STRING(centre, "X,Y,Z (mm): joints putting the ball's centre on the sphere's, rotary axes at 0");
RTAPI_MP_STRING(sphere_diameter, "mm (default 25)");
RTAPI_MP_STRING(ball_diameter, "the stylus ball, mm (default 2)");
RTAPI_MP_STRING(probe_length, "gauge point to ball centre, mm (default: the machine file's tool length)");
RTAPI_MP_STRING(noise_um, "repeatability of the trigger point, um (standard deviation, default 0)");
RTAPI_MP_INT(seed, "seed of the noise");
}

extern "C" int rtapi_app_main(void) {
  try {
    sphere = make_sphere();
  } catch (const std::exception& e) {
    rtapi_print_msg(RTAPI_MSG_ERR, "simsphere: %s\n", e.what());
    return -EINVAL;
  }
  comp_id = hal_init("simsphere");
  if (comp_id < 0) {
    delete sphere;
    return comp_id;
  }
  hal = static_cast<HalData*>(hal_malloc(sizeof(HalData)));
  int r = hal ? 0 : -ENOMEM;
  for (int j = 0; r == 0 && j < sphere->model.joint_count(); ++j)
    r |= hal_pin_float_newf(HAL_IN, &hal->joint[j], comp_id, "simsphere.joint.%d", j);
  if (r == 0) {
    r |= hal_pin_bit_newf(HAL_OUT, &hal->probe, comp_id, "simsphere.probe");
    r |= hal_pin_float_newf(HAL_OUT, &hal->gap_um, comp_id, "simsphere.gap-um");
    r |= hal_pin_s32_newf(HAL_OUT, &hal->touches, comp_id, "simsphere.touches");
    r |= hal_export_funct("simsphere.update", update, nullptr, 1 /* floating point */, 0, comp_id);
  }
  if (r) {
    rtapi_print_msg(RTAPI_MSG_ERR, "simsphere: cannot create its HAL pins\n");
    hal_exit(comp_id);
    delete sphere;
    return r;
  }
  *hal->probe = 0;
  *hal->touches = 0;
  *hal->gap_um = 0;
  draw_trigger();
  const Eigen::Vector3d& c = sphere->centre_mm;
  rtapi_print_msg(RTAPI_MSG_INFO, "simsphere: %s, sphere centre %.4f %.4f %.4f mm (part frame), reach %.4f mm\n",
                  sphere->model.path.c_str(), c.x(), c.y(), c.z(), sphere->reach_mm);
  hal_ready(comp_id);
  return 0;
}

extern "C" void rtapi_app_exit(void) {
  hal_exit(comp_id);
  delete sphere;
  sphere = nullptr;
}
