// Output files that are never left half-written, even by a SIGKILL or a power cut: written to a
// temporary file beside the target (same file system), flushed to disk, and renamed over it
// only when complete; on any error the temporary is removed and an existing target is
// untouched. Every file volcomp writes goes through here (tables, machine files, programs,
// reports), so a reader finds the old file or the complete new one, never a part.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace vc::tables {

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace vc::tables
