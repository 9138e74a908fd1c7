#include "vc/tables/units.hpp"

#include <array>

namespace vc::tables {
namespace {

constexpr double kPi = 3.14159265358979323846;

constexpr std::array<Unit, 8> kUnits{{
    {"mm", Quantity::Length, 1.0},
    {"um", Quantity::Length, 1e-3},
    {"nm", Quantity::Length, 1e-6},
    {"rad", Quantity::Angle, 1.0},
    {"mrad", Quantity::Angle, 1e-3},
    {"urad", Quantity::Angle, 1e-6},
    {"deg", Quantity::Angle, kPi / 180.0},
    {"arcsec", Quantity::Angle, kPi / (180.0 * 3600.0)},
}};

}  // namespace

std::optional<Unit> find_unit(std::string_view name) {
  for (const Unit& u : kUnits)
    if (u.name == name) return u;
  return std::nullopt;
}

std::string_view unit_names(Quantity q) {
  return q == Quantity::Length ? "mm, um, nm" : "deg, arcsec, rad, mrad, urad";
}

}  // namespace vc::tables
