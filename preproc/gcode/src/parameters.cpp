#include "vc/gcode/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <iterator>

#include "vc/gcode/syntax_error.hpp"

namespace vc::gcode {
namespace {

std::size_t index_of(double n, int offset) {
  const double rounded = std::round(n);
  if (std::abs(n - rounded) > 1e-4) throw SyntaxError(offset, "a parameter number must be a whole number");
  if (rounded < 1 || rounded >= Parameters::kCount)
    throw SyntaxError(offset, "parameter number out of range (1 to 5601)");
  return static_cast<std::size_t>(rounded);
}

}  // namespace

double Parameters::get(double n, int offset) const {
  const std::size_t i = index_of(n, offset);
  if (state_ && (i >= 5400 && i <= 5428 && (i <= 5413 || i >= 5420)))
    if (const auto value = state_->numbered(static_cast<int>(i))) return *value;
  // The controller's state at run time, which a program read offline cannot know.
  if ((i >= 5061 && i <= 5070) || (i >= 5399 && i <= 5428) || i >= 5600)
    throw SyntaxError(offset, "#" + std::to_string(i) +
                                  " is the controller's state at run time (probe result, input, tool data before the "
                                  "program's M6 or after an M61, or the current position): it is not known offline");
  return numbered_[i];
}

void Parameters::set(double n, double value, int offset) { numbered_[index_of(n, offset)] = value; }

double Parameters::get(const std::string& name, int offset) const {
  if (state_ && is_global(name))
    if (const auto value = state_->named(name)) return *value;
  const auto it = named_.find(name);
  if (it == named_.end()) throw SyntaxError(offset, "parameter #<" + name + "> is not set");
  return it->second;
}

bool Parameters::exists(const std::string& name) const {
  return named_.count(name) != 0 || (state_ && is_global(name) && state_->named(name));
}

void Parameters::set(const std::string& name, double value) { named_[name] = value; }

void Parameters::enter_scope(Scope& caller, const std::array<double, kLocals>* arguments) {
  caller.own_numbered = arguments != nullptr;
  if (arguments) {
    std::copy(numbered_.begin() + 1, numbered_.begin() + 1 + kLocals, caller.numbered.begin());
    std::copy(arguments->begin(), arguments->end(), numbered_.begin() + 1);
  }
  caller.named.clear();
  for (auto it = named_.begin(); it != named_.end();) {
    if (is_global(it->first)) {
      ++it;
    } else {
      caller.named.insert(*it);
      it = named_.erase(it);
    }
  }
}

void Parameters::leave_scope(Scope& caller) {
  if (caller.own_numbered) std::copy(caller.numbered.begin(), caller.numbered.end(), numbered_.begin() + 1);
  for (auto it = named_.begin(); it != named_.end();) it = is_global(it->first) ? std::next(it) : named_.erase(it);
  named_.insert(caller.named.begin(), caller.named.end());
}

}  // namespace vc::gcode
