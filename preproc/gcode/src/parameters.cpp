#include "vc/gcode/parameters.hpp"

#include <cmath>

#include "vc/gcode/syntax_error.hpp"

namespace vc::gcode {
namespace {

std::size_t index_of(double n, int offset) {
  const double rounded = std::round(n);
  if (std::abs(n - rounded) > 1e-4)
    throw SyntaxError(offset, "a parameter number must be a whole number");
  if (rounded < 1 || rounded >= Parameters::kCount)
    throw SyntaxError(offset, "parameter number out of range (1 to 5601)");
  return static_cast<std::size_t>(rounded);
}

}  // namespace

double Parameters::get(double n, int offset) const { return numbered_[index_of(n, offset)]; }

void Parameters::set(double n, double value, int offset) { numbered_[index_of(n, offset)] = value; }

double Parameters::get(const std::string& name, int offset) const {
  const auto it = named_.find(name);
  if (it == named_.end()) throw SyntaxError(offset, "parameter #<" + name + "> is not set");
  return it->second;
}

bool Parameters::exists(const std::string& name) const { return named_.count(name) != 0; }

void Parameters::set(const std::string& name, double value) { named_[name] = value; }

}  // namespace vc::gcode
