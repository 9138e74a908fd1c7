// The R-test (ISO 230-1 11.3.5.3, ISO 10791-6; seed 000 section 2.9's sphere tracking done with
// displacement sensors instead of a probe): a precision sphere fixed on the table, a nest of three
// displacement sensors in the spindle touching it. At each pose the machine is commanded to put the
// nest's centre on the sphere's centre (the rotary axes at their test positions, X Y Z following
// them, as TCP does); the sensors read where the sphere's centre actually is against the nest's
// centre, along the spindle frame's x, y, z (the nest turns with the spindle: on a head the frame
// turns with the head, on a table-table machine it is the machine's).
//
// A reading is error = actual - nominal: the sphere's centre relative to the nest's centre, in
// the spindle frame (+dx: the sphere sits +x of where the nest is). Moving the linear joints so
// that the nest's centre moves by the reading (in the part frame: the spindle frame's turn of it)
// would put the nest on the sphere: those joints are the sphere probing's measurement
// (sphere_centres.hpp), so the R-test's readings identify the same location errors, with the same
// fit and its uncertainties.
//
// The readings file, a CSV: the machine's lower-case axis letters (the commanded joints, mm and
// deg) and dx, dy, dz with their unit ("dx[um]"), one pose per row.
#pragma once

#include <random>
#include <string>
#include <vector>

#include "vc/identify/sphere_centres.hpp"
#include "vc/machine/model.hpp"

namespace vc::identify {

struct RTestReading {
  machine::Joints joints;                               // commanded (mm, deg)
  Eigen::Vector3d deviation_mm = Eigen::Vector3d::Zero();  // sphere centre - nest centre, spindle frame
  int line = 0;                                         // in its file
};

// Throws vc::LoadError with file:line:column.
std::vector<RTestReading> read_rtest_readings(const std::string& path, const machine::Model& model);

// The joints at which the nest's centre (tool length L) sits on the sphere's centre, for each
// reading, on `model` (its errors as the file has them: the linear axes' move the nest too):
// the rotary joints as commanded, the linear ones moved until the model's nest has moved by the
// reading. Throws std::runtime_error where the linear joints cannot move the nest that way.
std::vector<SpherePose> rtest_centres(const machine::Model& model, const std::vector<RTestReading>& readings,
                                      double tool_length_mm);

// What the sensors of a nest `tool_length_mm` from the gauge point read on the machine `truth` at
// the commanded `joints`, the sphere's centre at `sphere_mm` in the part frame: its real pose's
// (the 4x4 chain) view of the centre, plus Gaussian noise of `noise_mm` on each sensor.
Eigen::Vector3d rtest_reading(const machine::Model& truth, const machine::Joints& joints, double tool_length_mm,
                              const Eigen::Vector3d& sphere_mm, double noise_mm = 0.0, std::mt19937_64* rng = nullptr);

}  // namespace vc::identify
