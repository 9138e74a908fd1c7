// Helpers of the `volcomp init` tests: scratch folders, files written whole (read: file_text), the
// installed LinuxCNC sample configurations, and `patch -p1` run on a folder.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "test_support.hpp"

namespace vc::test {

namespace fs = std::filesystem;

// LinuxCNC's 5-axis sample configurations, as the linuxcnc-uspace package installs them.
inline const fs::path kSampleConfigs = "/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis/vismach/5axis";

inline bool samples_installed() { return fs::is_directory(kSampleConfigs); }

inline std::string scratch_prefix() { return "vc_init_test_" + std::to_string(::getpid()) + "_"; }

// An empty folder of its own for a test (removed first if a previous run left it); the
// program's folders are removed when it ends.
inline fs::path scratch_folder(const std::string& name) {
  struct Cleanup {
    ~Cleanup() {
      std::error_code ignored;
      for (const auto& entry : fs::directory_iterator(fs::temp_directory_path(), ignored))
        if (entry.path().filename().string().rfind(scratch_prefix(), 0) == 0) fs::remove_all(entry.path(), ignored);
    }
  };
  static Cleanup cleanup;
  const fs::path dir = fs::temp_directory_path() / (scratch_prefix() + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// `patch -p1 -d folder < diff_file`, quietly; its exit code.
inline int apply_patch(const fs::path& folder, const fs::path& diff_file) {
  const std::string command = "patch -s -p1 -d '" + folder.string() + "' < '" + diff_file.string() + "' > '" +
                              (folder / ".patch_output").string() + "' 2>&1";
  const int status = std::system(command.c_str());
  fs::remove(folder / ".patch_output");
  return WEXITSTATUS(status);
}

}  // namespace vc::test
