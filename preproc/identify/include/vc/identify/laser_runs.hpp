// Laser interferometer runs of one axis, as the laser software exports them: the ISO 230-2
// test cycle (every target approached in both directions, several runs), as a CSV a
// spreadsheet opens. Two layouts, recognised from the header:
//
//   long:   target[mm],run,direction,deviation[um]     (one reading per row; any column order)
//   wide:   target[mm],1+[um],1-[um],2+[um],2-[um],... (one column per run and direction)
//
// Units in brackets: the target in mm (a linear axis) or deg (a rotary one), the deviation in
// mm, um, nm (positioning, straightness) or urad, arcsec, mrad, rad, deg (angular errors).
// Direction: +, -, up, down, forward, backward, fwd, bwd (upper or lower case); the run number
// a whole number. The deviation is ISO 230-2's positional deviation: actual - target (the
// project's error = actual - nominal). Metadata lines at the top, "# key: value" (instrument,
// date, temperature_degC, measured_at_mm, ...), are carried into the identified table.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "vc/tables/units.hpp"

namespace vc::identify {

enum class Direction { Up, Down };  // increasing target (+), decreasing (-)

struct Reading {
  int run = 0;
  Direction direction = Direction::Up;
  double target = 0.0;     // mm or deg
  double deviation = 0.0;  // core units: mm or rad
  int line = 0;            // in the file
};

struct LaserRuns {
  std::string path;
  bool rotary = false;                                   // targets in deg
  tables::Quantity quantity = tables::Quantity::Length;  // of the deviations
  std::vector<Reading> readings;
  std::vector<std::pair<std::string, std::string>> metadata;  // "# key: value" lines, in order
};

// Throws vc::LoadError with file:line:column for what it cannot read.
LaserRuns read_laser_runs(const std::string& path);

}  // namespace vc::identify
