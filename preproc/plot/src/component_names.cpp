#include "vc/plot/component_names.hpp"

#include <cctype>

namespace vc::plot {
namespace {

// The component's letter (X..C) and the direction it acts along/about (x..z).
char letter(int component) { return "XYZABC"[component]; }
char direction(int component) { return "xyzxyz"[component]; }

// Which of X, Y, Z (0, 1, 2) an axis letter moves along or turns about; U V W are parallel to X Y Z.
int own_direction(char axis) {
  switch (axis) {
    case 'X':
    case 'A':
    case 'U':
      return 0;
    case 'Y':
    case 'B':
    case 'V':
      return 1;
    default:
      return 2;
  }
}

}  // namespace

std::string component_meaning(const tables::ErrorSymbol& s) {
  const bool rotary = s.axis == 'A' || s.axis == 'B' || s.axis == 'C';
  const int own = own_direction(s.axis);
  const bool translation = s.component < 3;
  const int along = s.component % 3;
  if (rotary) {
    if (translation) return along == own ? "axial run-out" : std::string("radial run-out in ") + letter(along);
    return along == own ? "angular positioning" : std::string("tilt about ") + letter(along);
  }
  if (translation) return along == own ? "positioning" : std::string("straightness in ") + letter(along);
  if (along == own) return "roll";
  if (own == 2) return std::string("tilt about ") + letter(along);  // a vertical axis has no pitch or yaw
  return along == 2 ? "yaw" : "pitch";
}

std::string location_meaning(const tables::ErrorSymbol& s, bool rotary_axis) {
  const std::string line = s.axis == 'S' ? std::string("spindle line") : std::string(1, s.axis) + " line";
  const int own = own_direction(s.axis);
  const bool translation = s.component < 3;
  const int along = s.component % 3;
  if (translation) {
    if (s.axis != 'S' && along == own)
      return rotary_axis ? "position of the " + line + " along its own line"
                         : "zero offset of " + std::string(1, s.axis);
    return "position of the " + line + " along " + direction(s.component);
  }
  if (s.axis == 'S') return "tilt of the spindle line about " + std::string(1, direction(s.component));
  if (along == own)
    return rotary_axis ? "angular zero offset of " + std::string(1, s.axis) : "turn of the " + line + " about itself";
  return rotary_axis ? "tilt of the " + line + " about " + std::string(1, direction(s.component))
                     : "squareness: the " + line + " turned about " + std::string(1, direction(s.component));
}

}  // namespace vc::plot
