// Running real LinuxCNC programs (halrun, linuxcnc) from a test: each run gets its own folder
// (also its HOME, where LinuxCNC keeps its tool table map), its own rtapi FIFO path, and, as
// root, the fallback uid rtapi_app needs. HAL's shared memory keys are fixed, so runs must not
// meet: CTest runs the tests using this through tests/support/isolated_linuxcnc.sh (their own
// namespaces, or one at a time: tests/README.md).
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace vc::test {

// Where run_folder(name) is: /tmp/volcomp-test-runs/<name>.
inline std::filesystem::path run_folder_path(const std::string& name) {
  return std::filesystem::temp_directory_path() / "volcomp-test-runs" / name;
}

// A fresh, empty folder /tmp/volcomp-test-runs/<name>, open to everyone: as root, rtapi_app
// runs under another uid, which must reach it wherever the checkout lives.
inline std::filesystem::path run_folder(const std::string& name) {
  const std::filesystem::path dir = run_folder_path(name);
  const std::filesystem::path base = dir.parent_path();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::permissions(base, std::filesystem::perms::all);
  std::filesystem::permissions(dir, std::filesystem::perms::all);
  return dir;
}

// Copies the source folders rtapi_app reads (machine files, tables, golden bad machines, HAL test data) to
// <dir>/src, keeping their relative layout; returns <dir>/src.
inline std::filesystem::path stage_sources(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  const fs::path src = dir / "src";
  for (const char* folder : {"machines/data", "tables/data", "tests/golden/bad_machines", "tests/hal/data"}) {
    fs::create_directories(src / folder);
    fs::copy(source_path(folder), src / folder, fs::copy_options::recursive);
  }
  for (const auto& e : fs::recursive_directory_iterator(dir)) fs::permissions(e.path(), fs::perms::all);
  return src;
}

// Runs `command` in `dir` with the LinuxCNC environment; stdout and stderr together.
inline CommandResult run_in(const std::filesystem::path& dir, const std::string& command, int timeout_s = 300) {
  std::string env = "HOME='" + dir.string() + "' RTAPI_FIFO_PATH=\"$(mktemp -u /tmp/vc-rtapi.XXXXXX)\"";
  if (geteuid() == 0) env += " RTAPI_UID=65534";
  const std::string full = "cd '" + dir.string() + "' && env " + env + " timeout " + std::to_string(timeout_s) + " " +
                           command + " 2>&1 </dev/null";
  FILE* pipe = popen(full.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  CommandResult result{"", 0};
  std::array<char, 4096> buffer;
  for (std::size_t n; (n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) result.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// halrun -k -f script (keep going after a failed command, so later lines can inspect the state)
// in the run folder `name`, whose sources stage_sources() copied to <folder>/src: the script
// writes @SRC@ for that path, and the output has it replaced by nothing again, so paths in
// messages read relative to the source tree.
inline CommandResult halrun(const std::string& name, std::string script) {
  const std::filesystem::path dir = run_folder(name);
  const std::string src = stage_sources(dir).string() + "/";
  for (std::size_t at; (at = script.find("@SRC@")) != std::string::npos;) script.replace(at, 5, src);
  std::ofstream(dir / "test.hal") << script;
  CommandResult r = run_in(dir, "halrun -k -f test.hal", 120);
  for (std::size_t at; (at = r.out.find(src)) != std::string::npos;) r.out.erase(at, src.size());
  return r;
}

// The number of [section] key in the INI file `ini` (relative to the source tree).
inline double ini_value(const std::string& ini, const std::string& section, const std::string& key) {
  std::ifstream in(test::source_path(ini));
  std::string line, current;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '[') current = line.substr(1, line.find(']') - 1);
    std::smatch m;
    if (current == section && std::regex_match(line, m, std::regex(key + R"(\s*=\s*(\S+)\s*)"))) return std::stod(m[1]);
  }
  throw std::runtime_error("no [" + section + "] " + key + " in " + ini);
}

// The values a halrun script's `getp PIN` lines printed, in order (TRUE, FALSE or a number).
inline std::vector<std::string> getp_values(const std::string& out) {
  std::vector<std::string> values;
  const std::regex line(R"((?:^|\n)(TRUE|FALSE|-?[0-9][0-9.e+-]*)(?=\n))");
  for (auto it = std::sregex_iterator(out.begin(), out.end(), line); it != std::sregex_iterator(); ++it)
    values.push_back((*it)[1]);
  return values;
}

}  // namespace vc::test
