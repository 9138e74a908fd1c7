// What the simulated instruments (simsphere, simrtest) share: their number parameters read at
// load time, and reproducible Gaussian noise for the servo thread (no allocation, no locks).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace vc::sim {

// A module parameter as a number, `fallback` where it is not given. Throws std::runtime_error.
inline double number(const char* text, const char* name, double fallback) {
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (*end || !std::isfinite(v)) throw std::runtime_error(std::string(name) + "=" + text + " is not a number");
  return v;
}

// A standard normal draw (xorshift64 and Box-Muller): reproducible from its state's seed.
inline double normal(std::uint64_t& state) {
  const auto uniform = [&] {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return (static_cast<double>(state >> 11) + 0.5) / 9007199254740992.0;  // (0, 1)
  };
  const double u = uniform(), v = uniform();
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * M_PI * v);
}

// The state a module's `seed` parameter starts.
inline std::uint64_t noise_state(int seed) {
  return 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(static_cast<std::uint32_t>(seed));
}

}  // namespace vc::sim
