// RS274/NGC parameters: numbered #1..#5601 (#5161.. hold G28/G30 homes, #5221.. the work
// offsets, as in a LinuxCNC .var file) and named ones (#<name> local to the program here,
// #<_name> global; names compared lower case without spaces, as LinuxCNC does).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

namespace vc::gcode {

class Parameters {
 public:
  static constexpr int kCount = 5602;  // RS274NGC_MAX_PARAMETERS: #0 .. #5601

  // Throws SyntaxError(offset) if n is not an integer in 1..5601.
  double get(double n, int offset) const;
  void set(double n, double value, int offset);
  // Unset named parameters: get throws SyntaxError(offset), "unknown parameter #<name>".
  double get(const std::string& name, int offset) const;
  bool exists(const std::string& name) const;
  void set(const std::string& name, double value);

  // Direct access for the interpreter (work offsets, homes): no checks.
  double& operator[](int n) { return numbered_[static_cast<std::size_t>(n)]; }
  double operator[](int n) const { return numbered_[static_cast<std::size_t>(n)]; }

 private:
  std::array<double, kCount> numbered_{};
  std::unordered_map<std::string, double> named_;
};

}  // namespace vc::gcode
