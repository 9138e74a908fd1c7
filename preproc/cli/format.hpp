// Locale-proof number output for the commands (vc/tables/number_text.hpp), so a German locale
// can never write "1,5" into a CSV file.
#pragma once

#include <string>

#include "vc/tables/number_text.hpp"

namespace vc::cli {

// The shortest text that reads back to the same double.
inline std::string format_number(double v) { return number_text(v); }

// Fixed decimals, for human-readable summaries.
inline std::string format_fixed(double v, int decimals) { return fixed_text(v, decimals); }

}  // namespace vc::cli
