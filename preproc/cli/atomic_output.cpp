#include "atomic_output.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace vc::cli {

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path output(path);
  std::string temporary = (output.parent_path().empty() ? fs::path(".") : output.parent_path()) /
                          ("." + output.filename().string() + ".XXXXXX");
  const int fd = mkstemp(temporary.data());
  if (fd < 0) throw std::runtime_error("cannot create a temporary file beside " + path);
  close(fd);
  try {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    write(out);
    out.close();
    if (!out) throw std::runtime_error("cannot write " + temporary);
    fs::permissions(temporary, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                                   fs::perms::others_read);
    fs::rename(temporary, output);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

}  // namespace vc::cli
