// Reads a machine description file (TOML) and its error tables into a Model.
// Load time only: allocates and throws LoadError naming file, line and column.
//
// The format is documented by example in machines/data/mc300.toml and in machines/README.md.
#pragma once

#include <string>

#include "vc/machine/model.hpp"

namespace vc::machine {

Model load_machine(const std::string& path);

}  // namespace vc::machine
