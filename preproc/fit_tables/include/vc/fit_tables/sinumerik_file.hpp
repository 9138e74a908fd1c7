// SINUMERIK 840D sl compensation tables as the control loads them: part-program text files
// that set the compensation system variables. The writer, a reader of exactly that format and
// an evaluator that applies the read tables as the control does (README.md says which detail
// was checked in which document; controllers/source14.toml names the documents).
//
// Two files, as the Function Manual Extended Functions, K3 Compensations (6FC5397-1BP40-3BA1,
// 03/2013, sec. 4.4) describes the variables and shows the EEC file, and the 802D sl Function
// Manual K3 (6FC5397-1CP10-5BA0, 11/2012, sec. 11.3) shows the CEC file:
//   AX_EEC.INI  (%_N_AX_EEC_INI, CHANDATA(1), ..., M17): measuring system error / leadscrew
//     error compensation (MSEC / LEC), one table per axis, measuring system e = 0:
//       $AA_ENC_COMP[0,N,AXi]  value of node N (mm or deg)
//       $AA_ENC_COMP_STEP[0,AXi], $AA_ENC_COMP_MIN[0,AXi], $AA_ENC_COMP_MAX[0,AXi]  (mm or deg)
//       $AA_ENC_COMP_IS_MODULO[0,AXi]  0 or 1
//     A positive value moves the axis in the NEGATIVE direction (K3 4.4.2.1): the file holds
//     the measuring system's error, so its value is the fit's correction negated.
//   NC_CEC.INI  (%_N_NC_CEC_INI, CHANDATA(1), ..., M17): sag / angularity compensation (CEC),
//     table t = 0, 1, ...:
//       $AN_CEC[t,N]  value of node N for the output axis (mm or deg)
//       $AN_CEC_INPUT_AXIS[t]=(AXi), $AN_CEC_OUTPUT_AXIS[t]=(AXj)
//       $AN_CEC_STEP[t], $AN_CEC_MIN[t], $AN_CEC_MAX[t]  (input axis, mm or deg)
//       $AN_CEC_DIRECTION[t]=0, $AN_CEC_MULT_BY_TABLE[t]=0, $AN_CEC_IS_MODULO[t]  0 or 1
//     Written as the correction added to the output axis (an assumption: the documents read do
//     not state the sign of a CEC value; README.md says how to check it on the machine).
//     A squareness (output += s x input) is a 2-node CEC table spanning the input's travel,
//     s x MIN and s x MAX: its linear interpolation is exactly s x input inside the travel
//     (K3 treats angularity errors with the same CEC tables; it has no squareness variable).
// Axes are named AX1, AX2, ... (the machine axis's general name, K3's CEC example and its note
// on multi-channel systems): AXn is the machine file's n-th axis (XYZABC order), which must be
// machine axis n of the control (MD10000). Nodes: N = (MAX - MIN) / STEP + 1, values held
// outside MIN..MAX, a modulo table repeats with period MAX - MIN.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "vc/fit_tables/table_set.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::fit_tables {

struct SinumerikFile {
  std::string file_name;  // "AX_EEC.INI" or "NC_CEC.INI"
  std::string text;
};

// The smallest step of a written value (the control's resolution, the controller file's
// resolution_um / resolution_deg); 0: written to 1e-9.
struct SinumerikResolution {
  double mm = 0.0;
  double deg = 0.0;
};

// The resolution a controller's tables declare (the finest non-zero one of its tables).
SinumerikResolution sinumerik_resolution(const Controller& controller);

// The EEC file (every positioning table) and the CEC file (every cross and squareness table),
// from the fit's values x; a file with no table is not written. Throws std::invalid_argument for
// a direction-dependent table (written by neither file here).
std::vector<SinumerikFile> sinumerik_files(const machine::Model& model, const TableSet& set, const Eigen::VectorXd& x,
                                           SinumerikResolution resolution);

// The commissioning steps for the files (machine data, enabling), one line each.
std::string sinumerik_setup_lines(const TableSet& set, const std::vector<SinumerikFile>& files);

// One table as read back.
struct SinumerikTable {
  enum class Kind { Lec, Cec } kind = Kind::Lec;
  int index = 0;                        // CEC: t; LEC: the measuring system e (always 0 here)
  int input_axis = 0, output_axis = 0;  // AXn: n - 1 (LEC: both the table's axis)
  double min = 0.0, max = 0.0, step = 0.0;
  bool modulo = false;
  std::vector<double> values;  // N = (max - min) / step + 1
  SourceLocation where;        // the table's first line
};

// Reads an EEC or a CEC file of the form above (its header says which). Anything else (no
// header, an unknown variable, a bad index or axis, a value that is not a number, a missing or
// repeated entry, STEP / MIN / MAX not giving a whole number of nodes, a direction-dependent or
// multiplied table) throws vc::LoadError "path:line:column: error: ...".
std::vector<SinumerikTable> read_sinumerik_file(const std::string& text, const std::string& path);

// The value of one table at its input axis's setpoint `position` (mm or deg): linear between
// nodes, the first and last values held outside MIN..MAX, a modulo table taken into its period.
double sinumerik_table_value(const SinumerikTable& table, double position);

// The joints the control commands for nominal joints q: each axis moved by minus its LEC value
// and plus the sum of the CEC values it is the output of, every table read at the nominal
// (setpoint) position of its input axis.
machine::Joints sinumerik_commanded(const std::vector<SinumerikTable>& tables, const machine::Joints& q);

}  // namespace vc::fit_tables
