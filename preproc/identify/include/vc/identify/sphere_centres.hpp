// Rotary axes' location errors from a sphere's centre probed at several rotary positions
// (ISO 230-7 / ISO 10791-6 location errors; seed 000, sections 2.8, 2.9 and 4.6, B-C location
// and sphere tracking; Heidenhain's KinematicsOpt and Siemens' CYCLE996 do this in the control).
//
// A sphere fixed on the table is probed at poses k (its rotary positions q_k fixed, X Y Z
// searching): the joints at which the tool tip sits at its centre are the measurement. The
// centre is one point p0 of the part frame, so with the right location errors the model's
// real tip at every measured q_k is the same point: the equations
//     tip_real(q_k; location errors) - p0 = 0        (3 per pose)
// are solved by least squares for p0 and the chosen location errors (Gauss-Newton on the
// model's forward kinematics, the Jacobian by central differences), in um and urad.
//
// What the poses cannot separate is found from the scaled Jacobian's singular values: a
// parameter that takes the largest part in a direction the data does not see (singular value
// below 1/1000 of the largest) is named and left out, never fitted, until none is left; the rest is solved, each value
// with its standard uncertainty from the residual (sigma^2 (J^T J)^-1, sigma^2 = the residual
// sum of squares over the degrees of freedom). Linear-axis errors enter the centres: identify
// after the linear tables are in the machine file.
#pragma once

#include <string>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::identify {

// One probed pose: the joints at the sphere's centre (machine order, mm and deg).
struct SpherePose {
  machine::Joints joints;
  int line = 0;  // in its file
};

// Reads a CSV with a header of the machine's lower-case axis letters (x,y,z,b,c), one pose per
// row. Throws vc::LoadError with file:line:column.
std::vector<SpherePose> read_sphere_centres(const std::string& path, const machine::Model& model);

struct LocationEstimate {
  std::string symbol;            // EX0C, EA0B, ...
  int joint = 0, component = 0;  // component 0..5: X Y Z (mm), A B C (rad)
  double before = 0.0;           // the machine file's value
  double value = 0.0;            // identified
  double uncertainty = 0.0;      // standard uncertainty (1 sigma)
};

// A location error the poses cannot tell apart from others: left out (zero change); only a
// combination is seen, carried by `with` (other location errors, or "the sphere's position").
struct NotSeparable {
  std::string symbol;
  std::vector<std::string> with;
};

struct SphereFit {
  std::vector<LocationEstimate> estimates;              // the identified ones
  std::vector<NotSeparable> not_separable;              // asked for, but the poses cannot tell them apart
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();  // p0, part frame
  int rank = 0, parameters = 0;
  double condition = 0.0;  // of the scaled Jacobian (identified parameters)
  double rms_before_um = 0.0, rms_after_um = 0.0;
  std::vector<double> residual_before_um, residual_after_um;  // |tip - p0| per pose
};

// `symbols`: the location errors to identify (empty: all six of every rotary axis).
// Throws std::runtime_error when nothing can be identified or the poses are too few.
SphereFit identify_from_sphere(const machine::Model& model, const std::vector<SpherePose>& poses,
                               std::vector<std::string> symbols, double tool_length_mm);

}  // namespace vc::identify
