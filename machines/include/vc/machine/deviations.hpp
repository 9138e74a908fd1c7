// The primary deviations of a machine, named by their ISO 230-1 symbols: component errors
// (EXX, EYX, ..., one per table column) and location errors (EC0Y, EA0Z, ..., EX0S for the
// spindle). Used to see what each deviation contributes (the source's "see-why" analysis,
// seeds/000 L4633-4640) and by the tests. Load time only: allocates and throws.
#pragma once

#include <string>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::machine {

// Every deviation the model carries, in joint order: its table columns, then its location
// errors that are not zero.
std::vector<std::string> deviation_symbols(const Model& model);

// A copy of `model` in which every deviation not named in `keep` is zero. Throws
// std::invalid_argument for a symbol that names no axis of the machine (or the spindle, S).
Model keep_only(const Model& model, const std::vector<std::string>& keep);

}  // namespace vc::machine
