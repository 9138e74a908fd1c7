// Numbers in files and messages, locale-proof (std::to_chars: a German locale never writes
// "1,5"): the one place every layer formats a double.
#pragma once

#include <charconv>
#include <string>

namespace vc {

// The shortest text that reads back to the same double, e.g. "100", "-600", "0.5".
inline std::string number_text(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

// Fixed decimals, e.g. fixed_text(23.4449, 1) = "23.4".
inline std::string fixed_text(double v, int decimals) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::fixed, decimals);
  return std::string(buffer, result.ptr);
}

}  // namespace vc
