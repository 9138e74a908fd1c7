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

// Values the interpreter works out when a program reads them (LinuxCNC's read-only
// parameters): the tool number #5400, the position #5420-#5428, and named ones such as
// #<_x>, #<_metric>, #<_feed>. nullopt: not one of them, or not known offline.
class StateParameters {
 public:
  virtual std::optional<double> numbered(int n) const = 0;
  virtual std::optional<double> named(const std::string& name) const = 0;

 protected:
  ~StateParameters() = default;
};

class Parameters {
 public:
  static constexpr int kCount = 5602;  // RS274NGC_MAX_PARAMETERS: #0 .. #5601

  // Throws SyntaxError(offset) if n is not an integer in 1..5601, or if it is one of the
  // controller's run-time values (#5061-#5070 probe, #5399 input, #5400-#5413 tool data,
  // #5420-#5428 current position, #5600-#5601 tool changer), unknown offline unless the state
  // (set_state) knows them.
  double get(double n, int offset) const;
  void set(double n, double value, int offset);
  // Unset named parameters: get throws SyntaxError(offset), "unknown parameter #<name>".
  double get(const std::string& name, int offset) const;
  bool exists(const std::string& name) const;
  void set(const std::string& name, double value);
  // Where the read-only values come from (null: nowhere).
  void set_state(const StateParameters* state) { state_ = state; }

  // A subroutine call's scope. LinuxCNC gives each O-word call its own #1..#30 (the call's
  // arguments, 0 after them) and every call its own names without a leading '_'; an M98 call
  // shares the caller's #1..#30. enter_scope keeps the caller's in `caller`, leave_scope puts
  // them back.
  static constexpr int kLocals = 30;
  struct Scope {
    std::array<double, kLocals> numbered{};
    bool own_numbered = false;
    std::unordered_map<std::string, double> named;
  };
  // `arguments`: the new #1..#30, or null to share the caller's.
  void enter_scope(Scope& caller, const std::array<double, kLocals>* arguments);
  void leave_scope(Scope& caller);
  static bool is_global(std::string_view name) { return !name.empty() && name[0] == '_'; }

  // Direct access for the interpreter (work offsets, homes): no checks.
  double& operator[](int n) { return numbered_[static_cast<std::size_t>(n)]; }
  double operator[](int n) const { return numbered_[static_cast<std::size_t>(n)]; }

 private:
  std::array<double, kCount> numbered_{};
  std::unordered_map<std::string, double> named_;
  const StateParameters* state_ = nullptr;
};

}  // namespace vc::gcode
