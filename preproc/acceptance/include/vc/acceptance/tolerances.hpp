// The user's limits for the acceptance figures (TOML, um), one table per kind of test:
//
//   [diagonal]        # ISO 230-6 diagonals: ISO 230-2 figures along each line
//   A_um = 25.0       # accuracy
//   E_um = 20.0       # systematic deviation
//   R_um = 8.0        # repeatability
//   B_um = 5.0        # reversal value
//   M_um = 15.0       # range of the mean bidirectional deviation
//
//   [axis]            # ISO 230-2 on each linear axis: the same keys as [diagonal]
//   E_um = 10.0
//
//   [circle]          # ISO 230-4 circular tests
//   Gb_um = 15.0      # bidirectional circular deviation G(b)
//   H_um = 5.0        # circular hysteresis
//   F_um = 20.0       # radial deviation (about the nominal centre, the ballbar's calibrated length)
//
//   [rtest]           # ISO 10791-6 R-test, per sequence
//   X_um = 10.0       # range of the sphere centre's deviation along x (Y_um, Z_um likewise)
//   D_um = 8.0        # its largest distance from the sequence's mean
//
// Any subset of the figures; a figure without a limit is reported, not judged.
#pragma once

#include <map>
#include <string>

namespace vc::acceptance {

struct Tolerances {
  std::string path;
  std::map<std::string, double> diagonal_mm;  // "A", "E", "R", "B", "M" -> limit (mm)
  std::map<std::string, double> axis_mm;      // the same figures, of the axis runs
  std::map<std::string, double> circle_mm;    // "G(b)", "H", "F" -> limit (mm)
  std::map<std::string, double> rtest_mm;     // "X", "Y", "Z", "D" -> limit (mm)
};

// Throws LoadError at file:line for an unknown table or key, a limit that is not a number > 0.
Tolerances read_tolerances(const std::string& path);

}  // namespace vc::acceptance
