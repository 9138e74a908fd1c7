// The compensation types of a model's terms sorted from their ISO 230-1 names, apart from the
// code under test (vc/machine/term_types.hpp), and the model with only some types' terms: what
// the tests compare a switched correction with (unit/machines/term_types_test.cpp, the sessions).
#pragma once

#include <set>
#include <string>
#include <vector>

#include "vc/machine/deviations.hpp"
#include "vc/machine/model.hpp"

namespace vc::test {

inline const char* const kBasicCodes[] = {"L-POS", "L-STR", "L-SQU", "L-ANG",  "R-POS",
                                          "R-RAX", "R-POR", "R-ANG", "L-SPEC", "R-SPEC"};

// The type of a deviation by its name: E<c><a> is a component error of axis a, E<c>0<a> a
// location error; c in X Y Z is a translation, in A B C a rotation. An axis's own direction is
// its letter's (X and A: x; Y and B: y; Z and C: z).
inline std::string type_by_name(const machine::Model& model, const std::string& symbol) {
  const bool location = symbol.size() == 4;
  const char c = symbol[1], a = symbol.back();
  if (a == 'S') return "L-SPEC";
  const bool rotary = model.axes[static_cast<std::size_t>(model.joint_of(a))].type == machine::AxisType::Rotary;
  const bool translation = c == 'X' || c == 'Y' || c == 'Z';
  const int own = rotary ? a - 'A' : a - 'X';
  const int direction = translation ? c - 'X' : c - 'A';
  if (!rotary && !location) return !translation ? "L-ANG" : direction == own ? "L-POS" : "L-STR";
  if (!rotary) return translation || direction == own ? "L-SPEC" : "L-SQU";
  if (!location) return translation ? "R-RAX" : direction == own ? "R-POS" : "R-ANG";
  return !translation && direction == own ? "R-POS" : "R-POR";
}

// The model with only the selected types' terms; a table over two axes (a cross-axis table) only
// where L-SPEC (R-SPEC) is selected too.
inline machine::Model with_only(const machine::Model& model, const std::set<std::string>& types) {
  std::vector<std::string> keep;
  for (const std::string& s : machine::deviation_symbols(model))
    if (types.count(type_by_name(model, s))) keep.push_back(s);
  machine::Model out = machine::keep_only(model, keep);
  for (const machine::Axis& axis : out.axes) {
    const bool rotary = axis.type == machine::AxisType::Rotary;
    for (int t : axis.tables) {
      tables::ErrorTable& table = out.tables[static_cast<std::size_t>(t)].table;
      int positions = 0;
      for (const auto& v : table.grid()) positions += !v.is_temperature();
      if (positions < 2 || types.count(rotary ? "R-SPEC" : "L-SPEC")) continue;
      for (int n = 0; n < table.node_count(); ++n)
        for (int c = 0; c < static_cast<int>(table.columns().size()); ++c) table.set_value(n, c, 0.0);
    }
  }
  return out;
}

}  // namespace vc::test
