// ISO 230-1 symbols of the errors of an axis.
//
// Component error "EXY": E, the component (X, Y, Z: translation along; A, B, C: rotation
// about), then the axis that moves (EXY = error in X of the Y axis: its straightness).
// Location error "EC0Y": E, the component, 0, the axis (EC0Y = squareness of Y about Z,
// ISO's E_C(0X)Y); the position and orientation of an axis line, constant over its travel.
// Location symbols may also name the spindle line, 'S' (EX0S ... EB0S).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "vc/tables/units.hpp"

namespace vc::tables {

// Letters that name machine axes, in LinuxCNC's coordinate order.
inline constexpr std::string_view kAxisLetters = "XYZABCUVW";
// Letters that name an error component: translations X, Y, Z then rotations A, B, C.
inline constexpr std::string_view kComponentLetters = "XYZABC";

struct ErrorSymbol {
  int component;  // 0..5: X, Y, Z (translation, length), A, B, C (rotation, angle)
  char axis;      // upper-case axis letter
  bool location;  // "EC0Y" (constant location error) rather than "ECY" (component error)

  Quantity quantity() const { return component < 3 ? Quantity::Length : Quantity::Angle; }
  std::string name() const;  // "EXY" or "EC0Y"
};

// Parses "EXY" or "EC0Y" (upper case); nothing if `text` is not such a symbol.
std::optional<ErrorSymbol> parse_error_symbol(std::string_view text);

}  // namespace vc::tables
