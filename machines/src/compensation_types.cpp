// The Annex A types of a machine file (compensation_types.hpp). Each non-zero term of the
// file is sorted into one type by what it is (ISO 230-1 symbol, axis type) and where it sits
// (a table column of an axis, a location error, the spindle line, [stiffness]); composites
// follow from their parts.
//
// Where the digest (seed 002, 7.2 and 7.3) leaves the sorting open, decided here:
//  * A linear axis's location errors about the other two directions (EA0Z, EB0Z, EC0Y) are
//    L-SQU (squareness between linear axes, ISO 230-1 10.3). Its location about its own
//    direction (a constant roll, EA0X) and its position location errors (EX0Y: a constant
//    offset of the line) are no squareness: L-SPEC.
//  * R-RAX is radial and axial error motion: every translational column of a rotary axis's
//    table (EXC, EYC, EZC). R-ANG is tilt: the rotational columns about the other two
//    directions (EAC, EBC); the one about its own direction (ECC) is R-POS, and so is the
//    location error about it (EC0C, the zero position: an angular positioning error, which the
//    digest tells from R-POR's location); its other location errors are R-POR.
//  * A table over another axis's position too (EZZ(z, y)) is a cross-axis table, not named by
//    the Annex (digest 7.3: implied by L-SPEC / R-SPEC); it is listed under the type of its
//    column and under L-SPEC (R-SPEC for a rotary axis). A table over a temperature is
//    thermal compensation, which the TR does not count as a type (digest 7.3, 8.1).
//  * The spindle line's location errors (EX0S .. EB0S) belong to no NC axis, and L-SQU
//    names squareness between linear axes only: L-SPEC.
//  * Cutting-force compliance ([stiffness]) is a non-rigid effect: L-SPEC (digest 7.2's
//    example for the builder-specific types).
//  * FOR is a type provided only where it is possible (two rotary axes, kins/README.md) and
//    there is an orientation error to correct: an angular term of any axis or the spindle.
//    L-VOL+ and R-VOL+ need FOR, and the whole of L-VOL or R-VOL respectively, since the TR
//    writes them as sums (L-VOL+ = L-VOL + FOR).
// The tool length on which L-ANG, L-VOL and most rotary types depend (digest 7.3) is no type:
// the correction is always for the active tool length (model.hpp, the tool-length rule).
#include "vc/machine/compensation_types.hpp"

#include "vc/machine/term_types.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>
#include <utility>

namespace vc::machine {
namespace {

enum Code { LPos, LStr, LSqu, LAng, LVol, For, LVolPlus, RPos, RRax, RPor, RAng, RVol, RVolPlus, LSpec, RSpec, kCodes };

struct TypeName {
  const char* code;
  const char* name;
};
constexpr TypeName kNames[kCodes] = {
    {"L-POS", "positioning of linear axes"},
    {"L-STR", "straightness of linear axes"},
    {"L-SQU", "squareness between linear axes"},
    {"L-ANG", "angular error motions of linear axes, at the tool position"},
    {"L-VOL", "volumetric, linear axes (L-POS + L-STR + L-SQU + L-ANG)"},
    {"FOR", "functional orientation: the tool direction corrected"},
    {"L-VOL+", "L-VOL with the functional orientation (L-VOL + FOR)"},
    {"R-POS", "angular positioning of rotary axes"},
    {"R-RAX", "radial and axial error motions of rotary axes"},
    {"R-POR", "position and orientation of rotary axes (location errors)"},
    {"R-ANG", "tilt error motions of rotary axes, at the tool position"},
    {"R-VOL", "volumetric, rotary axes (R-POS + R-RAX + R-POR + R-ANG)"},
    {"R-VOL+", "R-VOL with the functional orientation (R-VOL + FOR)"},
    {"L-SPEC", "builder-specific, linear axes (terms the Annex does not name)"},
    {"R-SPEC", "builder-specific, rotary axes (terms the Annex does not name)"},
};

// The report's order (Code) of a basic type (term_types.hpp sorts the terms).
Code code_of(BasicType t) {
  constexpr Code kOf[kBasicTypeCount] = {LPos, LStr, LSqu, LAng, RPos, RRax, RPor, RAng, LSpec, RSpec};
  return kOf[static_cast<std::size_t>(t)];
}

std::string file_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool column_nonzero(const tables::ErrorTable& t, int column) {
  for (int n = 0; n < t.node_count(); ++n)
    if (t.value(n, column) != 0.0) return true;
  return false;
}

// The terms of one type, gathered by what provides them and where: ("X", "x.csv") ->
// "EYX, EZX", printed "X: EYX, EZX (x.csv)"; a term without a source (a location error),
// "Y: EC0Y".
class Gathered {
 public:
  // `order` sorts what provides the terms: the joint, then the spindle.
  void add(Code code, int order, const std::string& who, const std::string& term, const std::string& source = "") {
    auto& terms = by_code_[code][Key{order, who, source}];
    if (std::find(terms.begin(), terms.end(), term) == terms.end()) terms.push_back(term);
  }
  bool has(Code code) const { return by_code_.count(code) > 0; }
  std::vector<std::string> sources(Code code) const {
    std::vector<std::string> out;
    const auto it = by_code_.find(code);
    if (it == by_code_.end()) return out;
    for (const auto& [key, terms] : it->second) {
      std::string s = std::get<1>(key) + ":";
      for (std::size_t i = 0; i < terms.size(); ++i) s += (i ? ", " : " ") + terms[i];
      if (!std::get<2>(key).empty()) s += " (" + std::get<2>(key) + ")";
      out.push_back(s);
    }
    return out;
  }

 private:
  using Key = std::tuple<int, std::string, std::string>;  // order, who, source
  std::map<Code, std::map<Key, std::vector<std::string>>> by_code_;
};

void gather_tables(const Model& model, int joint, Gathered& g, std::map<int, std::vector<std::string>>& thermal) {
  const Axis& a = model.axes[static_cast<std::size_t>(joint)];
  const bool linear = a.type == AxisType::Linear;
  const std::string who(1, a.letter);
  for (int index : a.tables) {
    const BoundTable& bound = model.tables[static_cast<std::size_t>(index)];
    const tables::ErrorTable& t = bound.table;
    const std::string file = file_name(t.path());
    std::string columns;  // the non-zero ones
    const bool cross_axis = crosses_axes(model, bound, a);
    for (int c = 0; c < static_cast<int>(t.columns().size()); ++c) {
      if (!column_nonzero(t, c)) continue;
      const tables::ErrorSymbol& s = t.columns()[static_cast<std::size_t>(c)].symbol;
      g.add(code_of(column_type(a, s.component)), joint, who, s.name(), file);
      if (cross_axis) g.add(linear ? LSpec : RSpec, joint, who, s.name() + " over another axis", file);
      columns += (columns.empty() ? "" : ", ") + s.name();
    }
    if (columns.empty()) continue;
    for (std::size_t v = 0; v < t.grid().size(); ++v)
      if (t.grid()[v].is_temperature() && bound.input[v] >= 0)
        thermal[bound.input[v]].push_back(who + " " + columns + " (" + file + ")");
  }
}

void gather_locations(const Axis& a, int joint, Gathered& g) {
  const bool linear = a.type == AxisType::Linear;
  const int own = own_component(a);
  const std::string who(1, a.letter);
  for (int k = 0; k < 6; ++k) {  // positions first, then orientations, as ISO 230-1 lists them
    const double value = k < 3 ? a.location_mm[k] : a.location_rad[k - 3];
    if (value == 0.0) continue;
    const std::string term = std::string("E") + "XYZABC"[k] + '0' + a.letter;
    const char* why = k < 3          ? (linear ? " (offset of the axis line)" : "")
                      : k - 3 != own ? ""
                      : linear       ? " (roll of the axis line)"
                                     : " (zero position)";
    g.add(code_of(location_type(a, k)), joint, who, term + why);
  }
}

bool any_angular(const Model& model, const Gathered& g) {
  if (g.has(LSqu) || g.has(LAng) || g.has(RPos) || g.has(RAng)) return true;
  for (const Axis& a : model.axes)
    if (a.type == AxisType::Rotary && a.location_rad.squaredNorm() > 0.0) return true;
  return model.spindle.location_rad.squaredNorm() > 0.0;
}

CompensationType basic(Code code, const Gathered& g) {
  CompensationType t{kNames[code].code, kNames[code].name, true, g.sources(code), {}};
  return t;
}

// A sum of parts: provided when any part is, complete when all are.
void add_composite(Code code, std::initializer_list<Code> parts, const std::vector<bool>& present,
                   std::vector<CompensationType>& out) {
  CompensationType t{kNames[code].code, kNames[code].name, true, {}, {}};
  for (Code p : parts) (present[p] ? t.sources : t.missing).push_back(kNames[p].code);
  t.complete = t.missing.empty();
  if (!t.sources.empty()) out.push_back(std::move(t));
}

}  // namespace

const CompensationType* CompensationTypes::find(std::string_view code) const {
  for (const CompensationType& t : types)
    if (t.code == code) return &t;
  return nullptr;
}

bool CompensationTypes::has(std::string_view code) const {
  const CompensationType* t = find(code);
  return t && t->complete;
}

CompensationTypes compensation_types(const Model& model) {
  CompensationTypes result;
  Gathered g;
  std::map<int, std::vector<std::string>> thermal;  // by temperature input
  for (int joint = 0; joint < model.joint_count(); ++joint) {
    const Axis& a = model.axes[static_cast<std::size_t>(joint)];
    gather_tables(model, joint, g, thermal);
    gather_locations(a, joint, g);
    if (a.thermal.input >= 0 && a.thermal.expansion_per_K != 0.0) {
      char text[64];
      std::snprintf(text, sizeof text, "%.3g/K", a.thermal.expansion_per_K);
      thermal[a.thermal.input].push_back(std::string(1, a.letter) + " expansion " + text);
    }
  }
  for (int k = 0; k < 3; ++k) {
    if (model.spindle.location_mm[k] != 0.0) g.add(LSpec, kMaxAxes, "spindle", std::string("E") + "XYZ"[k] + "0S");
    if (model.spindle.location_rad[k] != 0.0) g.add(LSpec, kMaxAxes, "spindle", std::string("E") + "ABC"[k] + "0S");
  }
  for (std::size_t j = 0; j < model.compliance.size() && j < model.axes.size(); ++j)
    if (!model.compliance[j].mm_per_N.empty())
      g.add(LSpec, static_cast<int>(j), std::string(1, model.axes[j].letter), "cutting-force compliance ([stiffness])");

  result.orientation_possible = model.rotary_count() >= 2;
  result.orientation_reason = result.orientation_possible
                                  ? "two rotary axes: volkins corrects the tool direction too, faded out near the pole"
                                  : "fewer than two rotary axes: only the tool position is corrected";
  const bool orientation = result.orientation_possible && any_angular(model, g);

  std::vector<bool> present(kCodes, false);
  for (int c = 0; c < kCodes; ++c) present[c] = g.has(static_cast<Code>(c));
  present[For] = orientation;
  for (Code c : {LPos, LStr, LSqu, LAng})
    if (present[c]) result.types.push_back(basic(c, g));
  add_composite(LVol, {LPos, LStr, LSqu, LAng}, present, result.types);
  if (orientation) {
    CompensationType t{kNames[For].code, kNames[For].name, true, {result.orientation_reason}, {}};
    result.types.push_back(std::move(t));
  }
  // L-VOL+ where FOR is and some of L-VOL; complete with all of L-VOL.
  if (orientation && result.find("L-VOL"))
    add_composite(LVolPlus, {LPos, LStr, LSqu, LAng, For}, present, result.types);
  for (Code c : {RPos, RRax, RPor, RAng})
    if (present[c]) result.types.push_back(basic(c, g));
  add_composite(RVol, {RPos, RRax, RPor, RAng}, present, result.types);
  if (orientation && result.find("R-VOL"))
    add_composite(RVolPlus, {RPos, RRax, RPor, RAng, For}, present, result.types);
  for (Code c : {LSpec, RSpec})
    if (present[c]) result.types.push_back(basic(c, g));

  for (const auto& [input, terms] : thermal) {
    std::string s = model.temperatures[static_cast<std::size_t>(input)].name + ":";
    for (std::size_t i = 0; i < terms.size(); ++i) s += (i ? "; " : " ") + terms[i];
    result.thermal.push_back(s);
  }
  return result;
}

}  // namespace vc::machine
