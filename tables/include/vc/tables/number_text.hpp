// Numbers in files and messages, locale-proof (std::to_chars: a German locale never writes
// "1,5"): the one place every layer formats a double. The texts are printf's in the C locale
// (%g, %.Nf, %.Ng, %.Ne: std::to_chars is specified as printf), and the last three functions shape
// such a text as some files and messages want it.
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

// Fixed decimals, e.g. fixed_text(23.4449, 1) = "23.4" (printf's %.1f).
inline std::string fixed_text(double v, int decimals) {
  char buffer[400];  // 1e308 written out in full, and decimals
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::fixed, decimals);
  return std::string(buffer, result.ptr);
}

// `digits` significant digits, trailing zeros dropped, e.g. significant_text(1234567, 6) =
// "1.23457e+06", significant_text(0.1 + 0.2, 6) = "0.3" (printf's %.6g, an ostream's default).
inline std::string significant_text(double v, int digits) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, digits);
  return std::string(buffer, result.ptr);
}

// Scientific notation, e.g. scientific_text(0.000123, 1) = "1.2e-04" (printf's %.1e).
inline std::string scientific_text(double v, int decimals) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::scientific, decimals);
  return std::string(buffer, result.ptr);
}

// A number's text without the sign of a zero: "-0" is "0", "-0.000" (a small negative value
// in 3 decimals) is "0.000"; any other text is kept.
inline std::string without_negative_zero(std::string text) {
  if (text.size() > 1 && text[0] == '-' && text.find_first_not_of("0.", 1) == std::string::npos) text.erase(0, 1);
  return text;
}

// A number's text with its sign always written (printf's %+): "+1.500", "-2", "+0".
inline std::string with_sign(std::string text) { return text[0] == '-' ? text : '+' + text; }

// A fixed text without the zeros that end its decimals, keeping at least `min_decimals`
// (added if missing): ("7.100", 0) is "7.1", ("5.000", 0) is "5", ("5", 1) is "5.0".
inline std::string without_trailing_zeros(std::string text, int min_decimals = 0) {
  std::size_t point = text.find('.');
  if (point == std::string::npos) {
    if (min_decimals == 0) return text;
    point = text.size();
    text += '.';
  }
  const std::size_t keep = point + 1 + static_cast<std::size_t>(min_decimals);
  if (text.size() < keep) text.append(keep - text.size(), '0');
  while (text.size() > keep && text.back() == '0') text.pop_back();
  if (min_decimals == 0 && text.back() == '.') text.pop_back();
  return text;
}

}  // namespace vc
