// Locale-proof number output: shortest text that reads back to the same double
// (std::to_chars), so a German locale can never write "1,5" into a CSV file.
#pragma once

#include <charconv>
#include <string>

namespace vc::cli {

inline std::string format_number(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

// Fixed decimals, for human-readable summaries.
inline std::string format_fixed(double v, int decimals) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::fixed, decimals);
  return std::string(buffer, result.ptr);
}

}  // namespace vc::cli
