// The compensation type of each error term, and the selection of types (term_types.hpp).
#include "vc/machine/term_types.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace vc::machine {
namespace {

constexpr std::array<std::string_view, kBasicTypeCount> kCodes{"L-POS", "L-STR", "L-SQU", "L-ANG",  "R-POS",
                                                               "R-RAX", "R-POR", "R-ANG", "L-SPEC", "R-SPEC"};

// The parts of each composite, as the TR writes its sums.
struct Composite {
  std::string_view code;
  std::array<BasicType, 4> parts;
  bool orientation;
};
constexpr Composite kComposites[] = {
    {"L-VOL", {BasicType::LPos, BasicType::LStr, BasicType::LSqu, BasicType::LAng}, false},
    {"L-VOL+", {BasicType::LPos, BasicType::LStr, BasicType::LSqu, BasicType::LAng}, true},
    {"R-VOL", {BasicType::RPos, BasicType::RRax, BasicType::RPor, BasicType::RAng}, false},
    {"R-VOL+", {BasicType::RPos, BasicType::RRax, BasicType::RPor, BasicType::RAng}, true},
};

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string_view basic_type_code(BasicType type) noexcept { return kCodes[static_cast<std::size_t>(type)]; }

int own_component(const Axis& axis) noexcept {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(axis.direction[i]) > std::abs(axis.direction[k])) k = i;
  return k;
}

BasicType column_type(const Axis& axis, int component) noexcept {
  const bool translation = component < 3;
  const bool own = component % 3 == own_component(axis);
  if (axis.type == AxisType::Linear) return !translation ? BasicType::LAng : own ? BasicType::LPos : BasicType::LStr;
  return translation ? BasicType::RRax : own ? BasicType::RPos : BasicType::RAng;
}

BasicType location_type(const Axis& axis, int component) noexcept {
  const bool translation = component < 3;
  const bool own = component % 3 == own_component(axis);
  if (axis.type == AxisType::Linear) return translation || own ? BasicType::LSpec : BasicType::LSqu;
  return !translation && own ? BasicType::RPos : BasicType::RPor;
}

bool crosses_axes(const Model& model, const BoundTable& table, const Axis& axis) noexcept {
  for (std::size_t v = 0; v < table.table.grid().size(); ++v)
    if (table.joint[v] >= 0 && model.axes[static_cast<std::size_t>(table.joint[v])].letter != axis.letter) return true;
  return false;
}

TypeSelection TypeSelection::all() {
  TypeSelection s;
  s.basic.fill(true);
  s.orientation = s.thermal = true;
  return s;
}

bool TypeSelection::is_all() const {
  return orientation && thermal && std::all_of(basic.begin(), basic.end(), [](bool b) { return b; });
}

std::string TypeSelection::to_string() const {
  if (is_all()) return "all";
  std::string out;
  auto add = [&](std::string_view code) { out += (out.empty() ? "" : ", ") + std::string(code); };
  for (int t = 0; t < kBasicTypeCount; ++t)
    if (basic[static_cast<std::size_t>(t)]) add(kCodes[static_cast<std::size_t>(t)]);
  if (orientation) add("FOR");
  if (thermal) add("thermal");
  return out.empty() ? "none" : out;
}

TypeSelection parse_type_selection(std::string_view list) {
  TypeSelection s;
  std::size_t begin = 0;
  bool any = false;
  while (begin <= list.size()) {
    const std::size_t comma = std::min(list.find(',', begin), list.size());
    const std::string code = upper(trimmed(list.substr(begin, comma - begin)));
    begin = comma + 1;
    if (code.empty()) continue;
    any = true;
    if (code == "ALL") {
      s = TypeSelection::all();
      continue;
    }
    if (code == "FOR") {
      s.orientation = true;
      continue;
    }
    if (code == "THERMAL") {
      s.thermal = true;
      continue;
    }
    const auto basic = std::find(kCodes.begin(), kCodes.end(), code);
    if (basic != kCodes.end()) {
      s.basic[static_cast<std::size_t>(basic - kCodes.begin())] = true;
      continue;
    }
    const auto composite = std::find_if(std::begin(kComposites), std::end(kComposites),
                                        [&](const Composite& c) { return c.code == code; });
    if (composite == std::end(kComposites))
      throw std::invalid_argument("'" + code +
                                  "' is no compensation type: give L-POS, L-STR, L-SQU, L-ANG, L-VOL, L-VOL+, R-POS, "
                                  "R-RAX, R-POR, R-ANG, R-VOL, R-VOL+, L-SPEC, R-SPEC, FOR, thermal or all "
                                  "(ISO/TR 16907 Annex A), separated by commas");
    for (BasicType t : composite->parts) s.basic[static_cast<std::size_t>(t)] = true;
    s.orientation |= composite->orientation;
  }
  if (!any) throw std::invalid_argument("no compensation type given (e.g. L-POS,R-POS,thermal, or all)");
  return s;
}

void apply_selection(const Model& model, const TypeSelection& selection, Conditions& conditions) noexcept {
  for (int t = 0; t < kBasicTypeCount; ++t)
    conditions.type_gain[static_cast<std::size_t>(t)] = selection.basic[static_cast<std::size_t>(t)] ? 1.0 : 0.0;
  conditions.fade.orientation = selection.orientation ? 1.0 : 0.0;
  if (!selection.thermal)
    for (std::size_t i = 0; i < model.temperatures.size() && i < conditions.temperature_degC.size(); ++i)
      conditions.temperature_degC[i] = model.temperatures[i].reference_degC;
}

}  // namespace vc::machine
