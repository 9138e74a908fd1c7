// What the header cells of a CMM software's table export name: "Nominal X", "X Nom", "NX",
// "Meas X", "X Act", "I", "Normal Y", "Vec K", "Dev", "Deviation [um]", "Point Name", ...
// A cell is read as words (case, spaces, '_', '-', '.' do not matter; "NX" and "XNom" are split
// into their role and axis); a unit may be written in brackets, "X [mm]", "Dev (in)", or as a
// word, "Dev um". A cell with a word that is not understood is not used (and listed when a
// needed column is missing); tolerances, types and the like are not used.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace vc::shop {

struct LengthUnit {
  std::string name;  // as shown in messages: mm, um, inch
  double to_mm;
};

// "mm", "MM", "um", "µm", "micron", "in", "inch", "Inches", ...; nothing for anything else.
std::optional<LengthUnit> length_unit(std::string_view word);

enum class ColumnRole {
  Unknown,             // a word not understood: not used
  Ignored,             // understood, not needed (tolerances, types, measured normals, ...)
  Id,                  // the point's name
  Coordinate,          // "X": no role word; the nominal unless the file also marks one
  Nominal,             // "Nominal X", "X Nom", "Theo X"
  Actual,              // "Actual X", "Meas X", "MX", "X Act"
  Normal,              // "I", "Normal X", "Vec I", "Nom I"
  NominalOrNormal,     // "NX": nominal or normal, told by the other columns
  Deviation,           // "Dev", "Deviation", "Normal Deviation": along the normal
  DeviationComponent,  // "Dev X", "DX": a component of the deviation vector
  LongLayout,          // "Axis", or "Nominal" / "Measured" without an axis: one row per axis
};

struct ColumnName {
  ColumnRole role = ColumnRole::Unknown;
  int axis = -1;                   // 0, 1, 2 for X, Y, Z (I, J, K of a normal)
  std::optional<LengthUnit> unit;  // written in the cell
  std::string bad_unit;            // a bracketed unit that is not a length unit
};

ColumnName column_name(std::string_view header_cell);

}  // namespace vc::shop
