// What the file readers' fuzzers share. The readers take a path, so each input is written to
// a file first, in a scratch folder of this process ($TMPDIR, which run_fuzzer.sh points into
// the build folder), under the name a reader expects; and a finding is reported by aborting,
// which libFuzzer records as a crash with the input that caused it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <unistd.h>

namespace vc::fuzz {

// The input as text (the readers get it byte for byte, NULs and all).
inline std::string_view text_of(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// A folder of this process's own, made on first use.
inline const std::filesystem::path& scratch() {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d = std::filesystem::temp_directory_path() / ("vc_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

// Writes `text` to `path` (binary: no line-end translation) and returns the path as a string.
inline std::string write_file(const std::filesystem::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path.string();
}

// A file of the source tree (VC_FUZZ_SOURCE_DIR: the repository root, set by CMakeLists.txt).
inline std::filesystem::path source_path(const std::string& relative) {
  return std::filesystem::path(VC_FUZZ_SOURCE_DIR) / relative;
}

// A reader broke a promise: say which, and abort so that libFuzzer keeps the input.
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "\n==fuzz finding== %s\n", what.c_str());
  std::abort();
}

}  // namespace vc::fuzz
