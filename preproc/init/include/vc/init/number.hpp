// Numbers as LinuxCNC's files write them ("-20", "+1.5", "1e3"), read and written
// locale-proof (std::from_chars, vc::number_text).
#pragma once

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

#include "vc/tables/number_text.hpp"

namespace vc::init {

// The whole of `text` as a finite number, or false.
inline bool parse_number(std::string_view text, double& value) {
  if (!text.empty() && text[0] == '+') text.remove_prefix(1);
  if (text.empty() || text[0] == '+') return false;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

// The shortest text that reads back to `v` ("-20", "0.1"); -0 is written 0. An alias of
// vc::number_text (the one formatter) for the init files and preproc/cli, which call it so.
inline std::string format_number(double v) { return without_negative_zero(number_text(v)); }

// "[x, y, z]", a TOML array.
inline std::string format_vector(const std::array<double, 3>& v) {
  return "[" + format_number(v[0]) + ", " + format_number(v[1]) + ", " + format_number(v[2]) + "]";
}

}  // namespace vc::init
