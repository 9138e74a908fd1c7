// Which compensation type each error term of the model belongs to, and which types are
// switched on: ISO/TR 16907 asks that each type can be enabled and disabled (digest of seed
// 002, 8.2 and 10.4: an indirect measurement with L-POS, R-POS and thermal alone, R-POR measured
// with the linear types on, acceptance with an agreed subset). The basic types of Annex A are
// what a term is switched by; the composites (L-VOL, R-VOL, L-VOL+, R-VOL+) are their sums; FOR
// (the tool direction) and thermal compensation are switches of their own, not terms.
//
// The sorting (compensation_types.cpp says why where the TR leaves it open):
//   linear axis, table column:  along its own direction L-POS, across it L-STR, angular L-ANG
//   linear axis, location:      about another direction L-SQU; its roll and offset L-SPEC
//   rotary axis, table column:  translations R-RAX, about its own direction R-POS, tilts R-ANG
//   rotary axis, location:      about its own direction (EC0C, the zero) R-POS, others R-POR
//   spindle line:               L-SPEC
// A table over another axis's position too (a cross-axis table, EZZ(z, y)) is switched by its
// column's type and by L-SPEC (R-SPEC for a rotary axis): on only when both are.
//
// The functions marked noexcept are the servo thread's (no allocation).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "vc/machine/model.hpp"

namespace vc::machine {

enum class BasicType : std::uint8_t { LPos, LStr, LSqu, LAng, RPos, RRax, RPor, RAng, LSpec, RSpec };
static_assert(kBasicTypeCount == 10, "model.hpp's count of BasicType");

// "L-POS", "L-STR", ...
std::string_view basic_type_code(BasicType type) noexcept;

// The component (0 X, 1 Y, 2 Z) an axis moves along or turns about: its direction's largest.
int own_component(const Axis& axis) noexcept;

// The type of axis `axis`'s table column or location error of `component` (0..2: X Y Z, a
// translation; 3..5: A B C, a rotation), as sorted above.
BasicType column_type(const Axis& axis, int component) noexcept;
BasicType location_type(const Axis& axis, int component) noexcept;
// A table of `axis` over another axis's position (not only its own and temperatures).
bool crosses_axes(const Model& model, const BoundTable& table, const Axis& axis) noexcept;

// What a term of one type, or a cross-axis one of two, is scaled by: the product of the gains.
inline double type_gain(const Conditions& c, BasicType t) noexcept { return c.type_gain[static_cast<std::size_t>(t)]; }

// A choice of types (volcomp's --types, volkins' pins at rest): the basic types, FOR and
// thermal compensation, each on or off.
struct TypeSelection {
  std::array<bool, kBasicTypeCount> basic{};
  bool orientation = false;  // FOR
  bool thermal = false;

  static TypeSelection all();
  bool is_all() const;
  // "L-POS, R-POS, thermal": the selection in the codes it was given in (composites expanded).
  std::string to_string() const;
};

// A comma-separated list of codes, case-insensitive: basic types (L-POS .. R-SPEC), composites
// (L-VOL = L-POS + L-STR + L-SQU + L-ANG, R-VOL likewise, L-VOL+ and R-VOL+ with FOR), FOR,
// thermal, and all. Throws std::invalid_argument naming the code it cannot read and the codes it
// can.
TypeSelection parse_type_selection(std::string_view list);

// `conditions` with only the selected types applied: the others' gains 0, FOR's orientation
// gain 0 if it is off, and without thermal the temperatures at their references (set after any
// --temperature).
void apply_selection(const Model& model, const TypeSelection& selection, Conditions& conditions) noexcept;

}  // namespace vc::machine
