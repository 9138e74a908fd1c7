// Which squareness term of a circular test's plane takes the measured squareness (volcomp
// identify circle --machine-out): one squareness in the file, so one term changes and the
// others stay as they are.
#pragma once

#include <string>
#include <vector>

#include "vc/identify/iso230_4.hpp"

namespace vc::identify {

// `symbol` when given (e.g. EC0Y), else the term the file already uses (a non-zero value; the
// last of several), else the first; nullptr when there is none or `symbol` is not among them.
const SquarenessTerm* chosen_squareness_term(const std::vector<SquarenessTerm>& terms, const std::string& symbol);

}  // namespace vc::identify
