// Running real LinuxCNC programs (halrun, linuxcnc) from a test: each run gets its own folder
// (also its HOME, where LinuxCNC keeps its tool table map), its own rtapi FIFO path, and, as
// root, the fallback uid rtapi_app needs. HAL's shared memory keys are fixed, so runs must not
// overlap: the CTest tests using this carry RESOURCE_LOCK linuxcnc.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "test_support.hpp"

namespace vc::test {

// A fresh, empty folder build/tests/runs/<name>.
inline std::filesystem::path run_folder(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(VC_RUN_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::permissions(dir, std::filesystem::perms::all);  // rtapi_app may run as another uid
  return dir;
}

// Runs `command` in `dir` with the LinuxCNC environment; stdout and stderr together.
inline CommandResult run_in(const std::filesystem::path& dir, const std::string& command, int timeout_s = 300) {
  std::string env = "HOME='" + dir.string() + "' RTAPI_FIFO_PATH=\"$(mktemp -u /tmp/vc-rtapi.XXXXXX)\"";
  if (geteuid() == 0) env += " RTAPI_UID=65534";
  const std::string full = "cd '" + dir.string() + "' && env " + env + " timeout " + std::to_string(timeout_s) +
                           " " + command + " 2>&1 </dev/null";
  FILE* pipe = popen(full.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  CommandResult result{"", 0};
  std::array<char, 4096> buffer;
  for (std::size_t n; (n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) result.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// halrun -k -f script (keep going after a failed command, so later lines can inspect the state).
inline CommandResult halrun(const std::string& name, const std::string& script) {
  const std::filesystem::path dir = run_folder(name);
  std::ofstream(dir / "test.hal") << script;
  return run_in(dir, "halrun -k -f test.hal", 120);
}

}  // namespace vc::test
