// A laser line into the machine file (`volcomp identify laser --machine M --machine-out DIR`):
// the identified table replaces the error where the axis's own 1-D table held it, solved so
// that the model, with every other error of the file as it is, reads what the laser read
// (laser_line.hpp); then the written file is loaded and must read the runs again within their
// noise, else nothing is written (preproc/identify/README.md).
//
// Load time: allocates, throws std::runtime_error with the reason.
#pragma once

#include <string>
#include <vector>

#include "vc/identify/laser_line.hpp"
#include "vc/machine/model.hpp"

namespace vc::identify {

struct LaserLineRuns {
  LaserSetup setup;
  std::vector<double> targets;   // ascending, mm or deg; a full turn 0 .. 360
  std::vector<double> readings;  // the runs' mean at each target (mm or rad)
  std::vector<double> noise;     // the standard uncertainty of each mean (mm or rad)
  Reference reference = Reference::None;
  std::string squareness;             // a referenced straightness: the location error that takes its slope
                                      // (e.g. EC0X; empty: the measured axis's own, or the one the file uses)
  std::vector<std::string> comments;  // the identified table's (the runs' metadata, the evaluation)
};

struct LaserIntoMachine {
  std::string written;            // the machine file
  std::string table_file;         // the identified table's file name, e.g. x_EXX_laser.csv
  std::string zeroed_copy;        // the copy of the table that held the error, its column 0 ("" if none)
  std::vector<std::string> kept;  // other tables with the error (cross-axis, over a temperature): kept
  ReferenceLine runs_reference;   // the runs' datum value or reference line
  ReferenceLine file_reference;   // what the file read there before (Datum: put in the runs' place)
  std::string squareness;         // a referenced straightness: the location error set, e.g. EC0X;
                                  // empty where none turns the line against the part (the file's slope kept)
  double squareness_before_rad = 0.0, squareness_rad = 0.0;
  std::vector<double> aimed;          // the readings the written file is made to give
  std::vector<double> written_reads;  // what it gives, read back from the written file
  std::vector<double> table;          // the identified column, node by node (mm or rad)
  double largest_misfit = 0.0;        // max |written_reads - aimed|
};

LaserIntoMachine laser_into_machine(const machine::Model& model, const LaserLineRuns& runs, const std::string& folder,
                                    const std::string& comment);

}  // namespace vc::identify
