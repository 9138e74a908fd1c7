#include "vc/tables/symbols.hpp"

namespace vc::tables {

std::string ErrorSymbol::name() const {
  std::string s = "E";
  s += kComponentLetters[component];
  if (location) s += '0';
  return s + axis;
}

std::optional<ErrorSymbol> parse_error_symbol(std::string_view text) {
  const bool location = text.size() == 4 && text[2] == '0';
  if (!(text.size() == 3 || location) || text[0] != 'E') return std::nullopt;
  const auto component = kComponentLetters.find(text[1]);
  const char axis = text.back();
  // The spindle line ('S') has location errors only.
  const bool known_axis = kAxisLetters.find(axis) != std::string_view::npos || (location && axis == 'S');
  if (component == std::string_view::npos || !known_axis) return std::nullopt;
  return ErrorSymbol{static_cast<int>(component), axis, location};
}

}  // namespace vc::tables
