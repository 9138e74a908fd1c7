#include "vc/report/base64.hpp"

namespace vc::report {

std::string base64(const std::string& bytes) {
  static const char* const alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t at = 0;
  for (; at + 3 <= bytes.size(); at += 3) {
    const unsigned v = static_cast<unsigned char>(bytes[at]) << 16 | static_cast<unsigned char>(bytes[at + 1]) << 8 |
                       static_cast<unsigned char>(bytes[at + 2]);
    out += alphabet[v >> 18 & 63];
    out += alphabet[v >> 12 & 63];
    out += alphabet[v >> 6 & 63];
    out += alphabet[v & 63];
  }
  if (const std::size_t rest = bytes.size() - at; rest > 0) {
    const unsigned v =
        static_cast<unsigned char>(bytes[at]) << 16 | (rest == 2 ? static_cast<unsigned char>(bytes[at + 1]) << 8 : 0u);
    out += alphabet[v >> 18 & 63];
    out += alphabet[v >> 12 & 63];
    out += rest == 2 ? alphabet[v >> 6 & 63] : '=';
    out += '=';
  }
  return out;
}

}  // namespace vc::report
