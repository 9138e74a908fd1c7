// Cutting-force deflection (analytical predistortion, seeds/000 ch. I and seeds/004): a
// force per cutting move from the cutting conditions of its tool, and the deflection of the
// tool relative to the part it causes through the machine's compliance.
//
// Force (mean over a revolution, simplified): the cutting power kc * ap * ae * vf over the
// cutting speed pi * D * n gives the mean tangential force Fc = kc ap ae vf / (pi D n), with
// Kienzle's specific force kc = kc1.1 * hm^-mc at the mean chip thickness
// hm = fz * sqrt(ae / D), fz = vf / (z n). On the tool it acts against the feed, plus a
// radial part (radial_ratio * Fc) pushing the tool away from the material side.
// Deflection: diagonal compliance per linear axis (seeds/004: per-axis, position-dependent),
//     delta = sum_j c_j(q_j) (F . d_j) d_j
// with d_j the direction the tool tip moves relative to the part for joint j (ideal machine).
// The correction aims at the nominal point minus delta: joint j shifts by -c_j (F . d_j).
#pragma once

#include <map>
#include <string>

#include "vc/interpreter/linuxcnc_files.hpp"
#include "vc/interpreter/move.hpp"
#include "vc/machine/forward.hpp"

namespace vc::predistort {

// Cutting conditions of one tool (process file).
struct ToolProcess {
  int tool = 0;
  double diameter_mm = 0.0;
  int teeth = 0;
  double specific_force_N_per_mm2 = 0.0;  // kc1.1: for a 1 mm x 1 mm chip
  double chip_exponent = 0.25;            // mc (Kienzle)
  double depth_of_cut_mm = 0.0;           // ap (along the tool axis)
  double width_of_cut_mm = 0.0;           // ae (radial engagement)
  double radial_ratio = 0.0;              // radial / tangential force
  int material_side = 0;                  // +1 left of the feed (seen from the spindle), -1 right, 0 none
};

struct CuttingProcess {
  std::string path;
  std::map<int, ToolProcess> tools;
};

// Reads a process file (TOML, [[tool]] tables; units in the key names). A tool's diameter
// may come from the tool table's D column. Throws vc::LoadError with file:line:column.
CuttingProcess load_process(const std::string& path, const interpreter::ToolTable* tools);

class Deflection {
 public:
  Deflection(const machine::Model& model, CuttingProcess process);

  // Mean force on the tool (N, part frame) of a cutting move at feed direction `feed` (unit,
  // part frame) and tool axis `tool_axis`; zero for rapids, a stopped spindle, a tool
  // without cutting conditions, or a move along the tool axis.
  Eigen::Vector3d force(const interpreter::Move& move, const Eigen::Vector3d& feed, const Eigen::Vector3d& tool_axis,
                        double path_length_mm) const;

  // Deflection (part frame, mm) under `force` at nominal joints, and the joint shift that
  // takes it off (target = nominal - shift).
  void at(const machine::Joints& nominal, double tool_length_mm, const Eigen::Vector3d& force, machine::Joints& shift,
          Eigen::Vector3d& deflection_mm) const;

  const CuttingProcess& process() const { return process_; }

 private:
  const machine::Model& model_;
  CuttingProcess process_;
};

}  // namespace vc::predistort
