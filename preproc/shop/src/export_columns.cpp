#include "export_columns.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace vc::shop {
namespace {

template <std::size_t N>
bool among(std::string_view word, const std::array<std::string_view, N>& words) {
  return std::find(words.begin(), words.end(), word) != words.end();
}

constexpr std::array<std::string_view, 10> kNominal{"nominal", "nom", "theoretical", "theo", "target",
                                                    "design",  "cad", "reference",   "ref",  "nominals"};
constexpr std::array<std::string_view, 7> kActual{"actual",      "act",  "measured", "meas",
                                                  "measurement", "real", "actuals"};
constexpr std::array<std::string_view, 6> kNormal{"normal", "norm", "vector", "vec", "direction", "dir"};
constexpr std::array<std::string_view, 5> kDeviation{"deviation", "dev", "deviations", "error", "err"};
constexpr std::array<std::string_view, 11> kId{"id",   "name", "point",  "pt",         "label", "feature",
                                               "feat", "no",   "number", "identifier", "nr"};
// Understood and not needed: a cell with one of these is not used.
constexpr std::array<std::string_view, 29> kNotNeeded{
    "tol",  "tolerance", "tols",  "utol",   "ltol",     "upper", "lower", "uppertol", "lowertol", "outtol",
    "out",  "max",       "min",   "status", "type",     "date",  "time",  "sigma",    "result",   "pass",
    "fail", "comment",   "angle", "radius", "diameter", "dia",   "size",  "probe",    "form"};
// Words that say nothing about the role.
constexpr std::array<std::string_view, 14> kFiller{"value", "val",      "coord",   "coordinate", "coordinates",
                                                   "pos",   "position", "surface", "of",         "along",
                                                   "at",    "in",       "3d",      "n"};

enum Role : unsigned { kNom = 1, kAct = 2, kNor = 4, kDev = 8, kNomOrNor = 16 };

std::optional<unsigned> role_word(std::string_view w) {
  if (among(w, kNominal)) return kNom;
  if (among(w, kActual)) return kAct;
  if (among(w, kNormal)) return kNor;
  if (among(w, kDeviation)) return kDev;
  return std::nullopt;
}

int axis_letter(char c) {
  switch (c) {
    case 'x':
    case 'i':
      return 0;
    case 'y':
    case 'j':
      return 1;
    case 'z':
    case 'k':
      return 2;
    default:
      return -1;
  }
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

std::string trimmed(std::string_view s) {
  const std::size_t b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  return std::string(s.substr(b, s.find_last_not_of(" \t") - b + 1));
}

}  // namespace

std::optional<LengthUnit> length_unit(std::string_view word) {
  const std::string w = lower(word);
  if (w == "mm" || w == "millimeter" || w == "millimeters" || w == "millimetre" || w == "millimetres")
    return LengthUnit{"mm", 1.0};
  if (w == "um" || w == "\xC2\xB5m" || w == "\xCE\xBCm" || w == "\xB5m" || w == "micron" || w == "microns" ||
      w == "micrometer" || w == "micrometre")
    return LengthUnit{"um", 1e-3};
  if (w == "in" || w == "inch" || w == "inches") return LengthUnit{"inch", 25.4};
  return std::nullopt;
}

ColumnName column_name(std::string_view header_cell) {
  ColumnName name;
  std::string text = lower(header_cell);
  if (trimmed(text) == "#") return {ColumnRole::Id, -1, std::nullopt, ""};
  // A unit in brackets: "x [mm]", "dev (um)".
  for (const auto& [open, close] : {std::pair{'[', ']'}, std::pair{'(', ')'}}) {
    const std::size_t a = text.find(open), b = text.find(close, a == std::string::npos ? 0 : a);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string unit = trimmed(std::string_view(text).substr(a + 1, b - a - 1));
    name.unit = length_unit(unit);
    if (!name.unit) name.bad_unit = unit;
    text.erase(a, b - a + 1);
  }
  // Words: runs of letters and digits (bytes above 127 count as letters: "µm").
  std::vector<std::string> words;
  std::string word;
  for (const char c : text + ' ') {
    const auto u = static_cast<unsigned char>(c);
    if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || u > 127) {
      word += c;
    } else if (!word.empty()) {
      words.push_back(word);
      word.clear();
    }
  }
  unsigned roles = 0;
  bool id_word = false, not_needed = false, unknown = false, axis_word = false;
  int axis = -1, axes = 0;
  bool ijk = false;
  for (const std::string& w : words) {
    if (w != "in" && length_unit(w)) {  // "in" as a word is "deviation in mm"
      if (!name.unit) name.unit = length_unit(w);
    } else if (const auto r = role_word(w)) {
      roles |= *r;
    } else if (among(w, kId)) {
      id_word = true;
    } else if (among(w, kNotNeeded)) {
      not_needed = true;
    } else if (among(w, kFiller)) {
    } else if (w == "axis") {
      axis_word = true;
    } else if (w.size() == 1 && axis_letter(w[0]) >= 0) {
      axis = axis_letter(w[0]), ijk = w[0] >= 'i' && w[0] <= 'k', ++axes;
    } else if (w.size() >= 2 && axis_letter(w.back()) >= 0 &&
               (w.size() > 2 || w[0] == 'n' || w[0] == 'm' || w[0] == 'd') &&
               (w.size() == 2 || role_word(w.substr(0, w.size() - 1)))) {
      // "nx" (nominal or normal), "mx" (measured), "dx" (deviation), "nomx", "measy", "devz".
      const std::string prefix = w.substr(0, w.size() - 1);
      roles |= prefix == "n" ? kNomOrNor : prefix == "m" ? kAct : prefix == "d" ? kDev : *role_word(prefix);
      axis = axis_letter(w.back()), ijk = w.back() >= 'i' && w.back() <= 'k', ++axes;
    } else if (w.size() > 2 && axis_letter(w[0]) >= 0 && role_word(w.substr(1))) {
      // "xnom", "yact", "zdev".
      roles |= *role_word(w.substr(1));
      axis = axis_letter(w[0]), ijk = w[0] >= 'i' && w[0] <= 'k', ++axes;
    } else {
      unknown = true;
    }
  }
  name.axis = axis;
  const auto only = [&](unsigned r) { return roles == r; };
  if (unknown || axes > 1) {
    name.role = ColumnRole::Unknown;
  } else if (not_needed) {
    name.role = ColumnRole::Ignored;
  } else if (axis >= 0 && ijk) {
    // I, J, K: the normal, unless measured or a deviation.
    name.role = (roles & (kAct | kDev)) ? ColumnRole::Ignored : ColumnRole::Normal;
  } else if (axis >= 0) {
    if (roles == 0)
      name.role = ColumnRole::Coordinate;
    else if (only(kNom))
      name.role = ColumnRole::Nominal;
    else if (only(kAct))
      name.role = ColumnRole::Actual;
    else if (only(kNor) || only(kNom | kNor))
      name.role = ColumnRole::Normal;
    else if (only(kNomOrNor))
      name.role = ColumnRole::NominalOrNormal;
    else if ((roles & kDev) && !(roles & kNor))
      name.role = ColumnRole::DeviationComponent;
    else if (roles & kAct)
      name.role = ColumnRole::Ignored;  // a measured normal
    else
      name.role = ColumnRole::Unknown;
  } else if (roles & kDev) {
    name.role = ColumnRole::Deviation;
  } else if (axis_word || only(kNom) || only(kAct)) {
    name.role = ColumnRole::LongLayout;
  } else if (id_word && roles == 0) {
    name.role = ColumnRole::Id;
  } else {
    name.role = words.empty() ? ColumnRole::Ignored : ColumnRole::Unknown;
  }
  if (name.role != ColumnRole::Coordinate && name.role != ColumnRole::Nominal && name.role != ColumnRole::Actual &&
      name.role != ColumnRole::Normal && name.role != ColumnRole::NominalOrNormal &&
      name.role != ColumnRole::DeviationComponent)
    name.axis = -1;
  return name;
}

}  // namespace vc::shop
