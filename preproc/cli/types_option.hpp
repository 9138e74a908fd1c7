// --types LIST: the compensation types (ISO/TR 16907 Annex A, 8.2 and 10.4) a command takes the
// correction to be made of, the same option for predistort, selftune and trace. The list is
// read when the command runs, first, so that a bad one is refused (exit 2, as the commands'
// other option errors) before anything is read or written.
#pragma once

#include <string>

#include "vc/machine/term_types.hpp"

namespace CLI {
class App;
}

namespace vc::cli {

struct TypesOption {
  std::string list = "all";
  // The selection `list` names; throws std::runtime_error("--types LIST: " + the reason).
  machine::TypeSelection selection() const;
};

// Adds --types to `command`; `what` says what the types are there (the help's first words).
void add_types_option(CLI::App& command, TypesOption& option, const std::string& what);

}  // namespace vc::cli
