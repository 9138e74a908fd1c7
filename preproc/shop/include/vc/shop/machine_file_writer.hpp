// A machine file with extra error tables: how the self-tuning writes its updated table set,
// and how the tests make a "true" machine that differs from the model. The machine file is
// copied as it is (its comments stay), with its table paths pointed back at the original
// tables and each extra table listed under its axis, so the measured tables stay untouched
// and the tuning is a separate, visible table per axis, summed with them.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "vc/machine/model.hpp"
#include "vc/tables/error_table.hpp"

namespace vc::shop {

struct ExtraTable {
  int joint = 0;                           // the axis whose section lists it
  std::string file_name;                   // written in the output folder, e.g. "selftune_x.csv"
  tables::ErrorTable table;                // core units (mm, rad)
  std::vector<std::string> comments = {};  // written after the standard ones (e.g. a measurement's metadata)
  std::string text = {};  // if not empty: the file as it is to be written (an edited copy of a table), not `table`
};

// A location error of an axis line to write into the machine file.
struct LocationValue {
  int joint = 0;
  int component = 0;  // 0..5: X Y Z (mm), A B C (rad)
  double value = 0.0;
  double uncertainty = -1.0;  // standard uncertainty, value's unit; < 0: none, else written in the comment
};

// Writes a table as CSV: positions in mm or deg, translations in um, rotations in urad; to a
// file (atomically: the old file or the complete new one) or to a stream.
void write_table_csv(const tables::ErrorTable& table, const std::string& path,
                     const std::vector<std::string>& comments);
void write_table_csv(const tables::ErrorTable& table, std::ostream& out, const std::vector<std::string>& comments);

// Writes `folder`/<machine file name> and the extra tables beside it; returns the machine
// file's path. A table already listed under the same axis with the same file name (an
// earlier tuning) is replaced by the extra one. `locations` replace the values of their
// keys in the axis's location table (in the key's unit, the comment kept and the old value
// added to it), or are added to it (in um or arcsec). Throws std::runtime_error if the
// machine file cannot be read or written.
std::string write_machine_with_tables(const machine::Model& model, const std::string& folder,
                                      const std::vector<ExtraTable>& extras, const std::string& comment,
                                      const std::vector<LocationValue>& locations = {});

// An empty table (all zero) over the travel of `joint` with `nodes` equally spaced
// positions and the given error columns, linear interpolation.
tables::ErrorTable zero_table(const machine::Model& model, int joint, int nodes,
                              const std::vector<tables::ErrorSymbol>& columns, const std::string& path);

}  // namespace vc::shop

namespace vc::shop {

// A "true" machine for the virtual shop: for every table of `model`, an extra table on the
// same grid holding f(x) times its values, where f is smooth along the table's first grid
// variable, f = s (a + b sin(pi t + phi)), t in [0, 1] over the grid, with its magnitude in
// [low, high] (e.g. 0.2 .. 0.5: the true errors are 20-50 % off the measured ones), the sign
// s, the phase phi and a, b drawn per column from `seed` (on a full turn, sin(2 pi t + phi):
// a periodic table stays periodic).
std::vector<ExtraTable> perturbation_tables(const machine::Model& model, double low, double high, unsigned seed);

// ... and its location errors: each non-zero one off by a share in [low, high] of itself,
// the sign drawn per value from `seed`.
std::vector<LocationValue> perturbation_locations(const machine::Model& model, double low, double high, unsigned seed);

}  // namespace vc::shop
