// CMM reports as CMM software exports them: a table with one row per point holding the
// nominal point (X Y Z), the surface normal out of the material (I J K) and the actual point
// (X Y Z) and/or the deviation along the normal, in mm, um or inch.
//
// - The header may follow lines of free text (title, part name, date); it is the first line
//   that names the nominal X, Y and Z. Its columns may come in any order and use the common
//   spellings: "Nominal X", "X Nom", "Theo X", "NX", "X"; "Actual X", "Meas X", "MX", "X Act";
//   "I", "Normal X", "Vec I"; "Dev", "Deviation"; "Dev X" (a deviation vector); "Name",
//   "Point", "ID". Columns not understood or not needed (tolerances, types) are not used.
// - Cells are separated by commas, semicolons or tabs (the header's separator), optionally in
//   double quotes. Numbers use a decimal point; a decimal comma only with `decimal_comma`.
// - Units: in the header cell ("X [mm]", "Dev (um)", "X inch"), on a line above the header
//   ("Units: inch", "UNITS=MM"), or from ReportFormat::unit; when two of them disagree for a
//   coordinate the file is refused.
// - The deviation: from the actual point when there is one, n . (actual - nominal) (no sign
//   to state); else the deviation column read with ReportFormat::sign, which must be stated.
//   With both, and a stated sign, each row's deviation is checked against its actual point
//   (to the digits written): a wrong sign is refused rather than tuned into the machine.
// - Ambiguities are refused with the way out: "NX" when nothing tells nominal from normal, a
//   bare "X" beside a marked nominal X, two columns for one quantity.
// The normals must point out of the material (the CMM's surface vector); nothing in the file
// can tell the other way round.
#pragma once

#include <string>
#include <vector>

#include "vc/shop/cmm.hpp"

namespace vc::shop {

// `report`: the actual point or a deviation is needed (else a plan: nominal and normal).
// Throws vc::LoadError with file:line:column and the reason.
std::vector<CmmPoint> read_cmm_export(const std::string& path, bool report, const ReportFormat& format,
                                      std::string* layout = nullptr);

}  // namespace vc::shop
