// Units of the file formats and their conversion to the units the core computes in.
//
// Inside the core every length is in mm and every angle in rad; rotary axis positions are in
// deg (as LinuxCNC gives them). Files may use any unit below, always declared next to the
// value (CSV header "EXX[um]", TOML key suffix "_arcsec"); conversion happens here, once, at
// load time.
#pragma once

#include <optional>
#include <string_view>

namespace vc::tables {

enum class Quantity { Length, Angle };

struct Unit {
  std::string_view name;  // as written in files: "mm", "um", "arcsec", ...
  Quantity quantity;
  double to_core;  // multiply a value in this unit by this to get mm (length) or rad (angle)
};

// The unit named `name`, or nothing if the name is not one we accept.
std::optional<Unit> find_unit(std::string_view name);

// The accepted unit names of one quantity, for messages: "mm, um, nm".
std::string_view unit_names(Quantity q);

// Position units of an axis: mm for a linear axis, deg for a rotary one.
inline constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

}  // namespace vc::tables
