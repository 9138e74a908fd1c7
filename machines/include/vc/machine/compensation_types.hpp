// The compensation types a machine file provides, in the terms of ISO/TR 16907 Annex A
// (digest: docs of seed 002, section 7): from a loaded Model, which of L-POS, L-STR, L-SQU,
// L-ANG, L-VOL, FOR, L-VOL+, R-POS, R-RAX, R-POR, R-ANG, R-VOL, R-VOL+, L-SPEC, R-SPEC its
// non-zero error terms give, each with the terms that give it; besides them, thermal
// compensation (not an Annex type) and whether the tool direction can be corrected (FOR).
// `volcomp check` prints them, `volcomp report` declares them.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::machine {

struct CompensationType {
  std::string code;  // Annex A code, e.g. "L-POS"
  std::string name;  // what it compensates, e.g. "positioning of linear axes"
  // Composite types (L-VOL, R-VOL, L-VOL+, R-VOL+): complete only with all their parts.
  bool complete = true;
  // Basic types: what provides it, one entry per axis, e.g. "X: EXX (x.csv)", "Y: EC0Y";
  // composite types: the parts present, e.g. "L-POS".
  std::vector<std::string> sources;
  std::vector<std::string> missing;  // composite types: the parts absent
};

struct CompensationTypes {
  // The types provided (a composite also when partial), in the order of the digest's table
  // (7.2): L-POS L-STR L-SQU L-ANG L-VOL FOR L-VOL+ R-POS R-RAX R-POR R-ANG R-VOL R-VOL+
  // L-SPEC R-SPEC. Empty for a machine without errors.
  std::vector<CompensationType> types;
  // FOR is possible: two rotary axes, so volkins corrects the tool direction too (with the
  // pole fade). The sentence says why or why not.
  bool orientation_possible = false;
  std::string orientation_reason;
  // Thermal compensation (not an Annex type: the TR asks that it be active while the
  // geometric errors are measured): one entry per temperature input that something reads,
  // e.g. "T_x: X expansion 11.5e-6/K, table x_thermal.csv". Empty: none.
  std::vector<std::string> thermal;

  // The type with `code`, or nullptr if the machine does not provide it.
  const CompensationType* find(std::string_view code) const;
  // True if `code` is provided and complete.
  bool has(std::string_view code) const;
};

CompensationTypes compensation_types(const Model& model);

}  // namespace vc::machine
