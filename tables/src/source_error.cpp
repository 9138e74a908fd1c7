#include "vc/tables/source_error.hpp"

namespace vc {

std::string SourceLocation::to_string() const {
  std::string s = path;
  if (line > 0) {
    s += ':' + std::to_string(line);
    if (column > 0) s += ':' + std::to_string(column);
  }
  return s;
}

LoadError::LoadError(SourceLocation where, const std::string& message)
    : std::runtime_error(where.to_string() + ": error: " + message), where_(std::move(where)), message_(message) {}

std::string Warning::to_string() const { return where.to_string() + ": warning: " + message; }

}  // namespace vc
