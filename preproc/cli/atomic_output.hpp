// Output files that are never left half-written: written to a temporary file beside the
// target (same file system) and renamed over it only when complete; on any error the
// temporary is removed and an existing target is untouched.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace vc::cli {

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace vc::cli
