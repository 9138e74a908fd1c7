// Where a problem in an input file is, and the exception that carries it.
//
// Every message a loader produces names the file, line and column, formatted as compilers do
// ("machines/data/mc300.toml:12:5: error: ...") so editors can jump to it.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace vc {

struct SourceLocation {
  std::string path;
  int line = 0;    // 1-based; 0 if the problem concerns the whole file
  int column = 0;  // 1-based; 0 if the problem concerns the whole line

  std::string to_string() const;  // "path:line:column", omitting unknown parts
};

// A file cannot be used. Thrown by the loaders (never in the servo thread).
class LoadError : public std::runtime_error {
 public:
  LoadError(SourceLocation where, const std::string& message);
  const SourceLocation& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

// Something the user should know that does not stop the machine from being used.
struct Warning {
  SourceLocation where;
  std::string message;
  std::string to_string() const;  // "path:line:column: warning: message"
};

using Warnings = std::vector<Warning>;

}  // namespace vc
