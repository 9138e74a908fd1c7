// simlaser: simulated laser interferometers along straight lines of a true machine (ISO 230-6's
// diagonal displacement test, ISO 230-2's linear runs), for running acceptance programs in a
// LinuxCNC session without a machine (volcomp acceptance evaluate reads what they record).
//
//   loadrt simlaser machine=TRUE.toml lines=SX,SY,SZ,EX,EY,EZ[/SX,...] [coordinates=xyz]
//                   [optic_length=MM] [noise_um=0] [seed=1]
//   addf simlaser.update servo-thread 1           (before motion-controller)
//   net j0 => simlaser.joint.0   ...              (the joint positions motion feeds back)
//
// Each line (up to 16, separated by '/') is given by its start and end joints X, Y, Z (mm, any
// rotary axes at 0), as `volcomp acceptance plan` writes them in its setup sheets. Its beam is
// where the IDEAL machine puts the optic between them (part frame): the start point and the
// direction from it to the end point, the laser aligned to the nominal line. Every servo period
// simlaser.N.position-mm is the TRUE machine's optic (optic_length from the gauge point, default
// the file's tool length; its 4x4 chain with every error) projected on the beam, from the start
// point, plus Gaussian noise of noise_um drawn anew each period from `seed`. A laser counts from
// where it is zeroed: as the laser software does, zero it at the first reading at the start.
// Servo thread: no allocation, no locks, no I/O.

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <sstream>
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
constexpr int kMaxLines = 16;

struct HalData {
  hal_float_t* joint[vm::kMaxAxes];     // in: joint positions (mm, deg)
  hal_float_t* position_mm[kMaxLines];  // out: along each beam from its start point
};

struct Beam {
  Eigen::Vector3d start_mm, direction;  // part frame, the ideal machine's
};

struct Lasers {
  vm::Model model;
  Beam beams[kMaxLines];
  int count = 0;
  double optic_mm = 0;
  double noise_mm = 0;
  std::uint64_t random = 0;
};

Lasers* lasers = nullptr;
HalData* hal = nullptr;
int comp_id = -1;

char* machine = nullptr;
char* coordinates = nullptr;
char* lines = nullptr;
char* optic_length = nullptr;
char* noise_um = nullptr;
int seed = 1;

// Servo thread, before motion-controller.
void update(void*, long) {
  const vm::Model& model = lasers->model;
  vm::Joints q(model.joint_count());
  for (int j = 0; j < model.joint_count(); ++j) q[j] = *hal->joint[j];
  const Eigen::Vector3d optic = vm::tool_pose(model, vm::Machine::Real, q, lasers->optic_mm).tip_mm;
  for (int i = 0; i < lasers->count; ++i) {
    const Beam& b = lasers->beams[i];
    double v = (optic - b.start_mm).dot(b.direction);
    if (lasers->noise_mm > 0) v += lasers->noise_mm * vc::sim::normal(lasers->random);
    *hal->position_mm[i] = v;
  }
}

// The lines parameter: SX,SY,SZ,EX,EY,EZ per line, lines separated by '/'; each a beam of the
// ideal machine.
void read_lines(Lasers& l) {
  const int x = l.model.joint_of('X'), y = l.model.joint_of('Y'), z = l.model.joint_of('Z');
  if (x < 0 || y < 0 || z < 0) throw std::runtime_error("the machine has no X, Y and Z axes to move along a line");
  const std::string usage = "lines=SX,SY,SZ,EX,EY,EZ[/SX,...] (mm): each line's start and end joints X, Y, Z";
  std::istringstream all(lines ? lines : "");
  for (std::string line; std::getline(all, line, '/');) {
    double v[6];
    char rest = 0;
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &rest) != 6)
      throw std::runtime_error(usage + ": cannot read '" + line + "'");
    if (l.count == kMaxLines) throw std::runtime_error("more than 16 lines");
    const auto ideal = [&](const double* p) {
      vm::Joints q = vm::Joints::Zero(l.model.joint_count());
      q[x] = p[0], q[y] = p[1], q[z] = p[2];
      return vm::tool_pose(l.model, vm::Machine::Ideal, q, l.optic_mm).tip_mm;
    };
    Beam& b = l.beams[l.count++];
    b.start_mm = ideal(v);
    const Eigen::Vector3d along = ideal(v + 3) - b.start_mm;
    if (!(along.norm() > 1e-6)) throw std::runtime_error("'" + line + "': its start and end are the same point");
    b.direction = along.normalized();
  }
  if (l.count == 0) throw std::runtime_error(usage);
}

Lasers* make_lasers() {
  auto* l = new Lasers;
  try {
    l->model = vc::kins::settings_from_parameters(machine, coordinates, "axes").model;
    l->optic_mm = vc::sim::number(optic_length, "optic_length", l->model.tool_length_mm);
    l->noise_mm = vc::sim::number(noise_um, "noise_um", 0.0) * 1e-3;
    if (!(l->noise_mm >= 0)) throw std::runtime_error("noise_um must not be negative");
    read_lines(*l);
    l->random = vc::sim::noise_state(seed);
  } catch (...) {
    delete l;
    throw;
  }
  return l;
}

}  // namespace

extern "C" {
MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("Simulated laser interferometers along lines of a machine file's real kinematics (volcomp)");
RTAPI_MP_STRING(machine, "the true machine's file (TOML)");
RTAPI_MP_STRING(coordinates, "axis letters, one per joint, in the machine file's order");
RTAPI_MP_STRING(lines, "SX,SY,SZ,EX,EY,EZ[/...] (mm): each line's start and end joints X, Y, Z");
RTAPI_MP_STRING(optic_length, "gauge point to the optic, mm (default: the machine file's tool length)");
RTAPI_MP_STRING(noise_um, "each reading's noise, um (standard deviation, default 0)");
RTAPI_MP_INT(seed, "seed of the noise");
}

extern "C" int rtapi_app_main(void) {
  try {
    lasers = make_lasers();
  } catch (const std::exception& e) {
    rtapi_print_msg(RTAPI_MSG_ERR, "simlaser: %s\n", e.what());
    return -EINVAL;
  }
  comp_id = hal_init("simlaser");
  if (comp_id < 0) {
    delete lasers;
    return comp_id;
  }
  hal = static_cast<HalData*>(hal_malloc(sizeof(HalData)));
  int r = hal ? 0 : -ENOMEM;
  for (int j = 0; r == 0 && j < lasers->model.joint_count(); ++j)
    r |= hal_pin_float_newf(HAL_IN, &hal->joint[j], comp_id, "simlaser.joint.%d", j);
  for (int i = 0; r == 0 && i < lasers->count; ++i)
    r |= hal_pin_float_newf(HAL_OUT, &hal->position_mm[i], comp_id, "simlaser.%d.position-mm", i);
  if (r == 0) r |= hal_export_funct("simlaser.update", update, nullptr, 1 /* floating point */, 0, comp_id);
  if (r) {
    rtapi_print_msg(RTAPI_MSG_ERR, "simlaser: cannot create its HAL pins\n");
    hal_exit(comp_id);
    delete lasers;
    return r;
  }
  for (int i = 0; i < lasers->count; ++i) *hal->position_mm[i] = 0;
  rtapi_print_msg(RTAPI_MSG_INFO, "simlaser: %s, %d lines, optic %.4f mm\n", lasers->model.path.c_str(), lasers->count,
                  lasers->optic_mm);
  hal_ready(comp_id);
  return 0;
}

extern "C" void rtapi_app_exit(void) {
  hal_exit(comp_id);
  delete lasers;
  lasers = nullptr;
}
