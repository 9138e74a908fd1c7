// What a controller can compensate, as data (controllers/*.toml): which 1-D tables it has, how
// it interpolates them, their node limits and resolution. Loading it never depends on a
// machine; table_set.hpp resolves its axis letters against one.
#pragma once

#include <string>
#include <vector>

#include "vc/tables/source_error.hpp"

namespace vc::fit_tables {

enum class TableKind {
  Positioning,  // an axis's own position -> a correction of that axis
  Cross,        // an input axis's position -> a correction added to an output axis (straightness, sag)
  Squareness,   // one value s: the output axis's correction = s x the input axis's position
};

const char* kind_name(TableKind kind);  // "positioning", "cross", "squareness"

struct TableSpec {
  TableKind kind = TableKind::Positioning;
  // Axis letters as the file writes them (upper case). Positioning: `input` is a letter or
  // "all" (every axis of the machine) and `output` is empty (the same axis).
  std::string input, output;
  bool direction_dependent = false;  // the controller holds one table per direction of travel
  bool modulo = false;               // a rotary input whose travel spans 360 deg is read modulo 360
  int max_nodes = 0;                 // the controller's limit per table
  int default_nodes = 0;             // what the fit uses unless told otherwise
  // Smallest step of a stored value, by the unit of what the table corrects; 0: exact.
  double resolution_um = 0.0;      // a linear output (mm joints)
  double resolution_deg = 0.0;     // a rotary output (deg joints)
  double resolution_arcsec = 0.0;  // a squareness value
  SourceLocation where;            // the [[table]] entry in the controller file
};

struct Controller {
  std::string path;
  std::string name;             // [controller] name, e.g. "linuxcnc"
  std::string title;            // one line for reports
  std::string checked_against;  // which documentation or source the file's details were checked against
  // The controller's own file format the tables are also written in: "linuxcnc-comp-file"
  // (comp_file.hpp), "sinumerik-lec-cec" (sinumerik_file.hpp), or empty (the generic CSV only).
  std::string format;
  std::vector<TableSpec> tables;
};

// Reads a controller file. Throws vc::LoadError ("file:line:column: error: ...") for a file
// that cannot be read, unknown keys, wrong types, unknown kinds, bad letters or limits.
Controller load_controller(const std::string& path);

// The file of a controller given by name ("linuxcnc": the shipped
// preproc/fit_tables/controllers/linuxcnc.toml) or by path (anything with a '/' or ending in
// .toml). Throws std::invalid_argument for an unknown name, listing the shipped ones.
std::string controller_file(const std::string& name_or_path);

// The names of the shipped controller files, sorted.
std::vector<std::string> shipped_controllers();

}  // namespace vc::fit_tables
