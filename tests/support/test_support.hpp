// Helpers shared by the tests: where the source tree is, and a CSV reader for reference data.
#pragma once

#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::test {

inline std::string source_path(const std::string& relative) { return std::string(VC_SOURCE_DIR) + "/" + relative; }

inline std::string machine_path(const std::string& name) { return source_path("machines/data/" + name + ".toml"); }

// The machines shipped in machines/data.
inline const std::vector<std::string>& shipped_machines() {
  static const std::vector<std::string> names{"mc300", "mill3", "ac_trunnion", "knee_mill"};
  return names;
}

// A numeric CSV file with a header line: rows of named columns.
class CsvTable {
 public:
  explicit CsvTable(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open " + path);
    std::string line;
    std::getline(in, line);
    std::stringstream header(line);
    for (std::string cell; std::getline(header, cell, ',');) names_.push_back(cell);
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      std::stringstream s(line);
      std::vector<double> row;
      for (std::string cell; std::getline(s, cell, ',');) row.push_back(std::stod(cell));
      rows_.push_back(row);
    }
  }
  std::size_t size() const { return rows_.size(); }
  double at(std::size_t row, const std::string& name) const {
    for (std::size_t c = 0; c < names_.size(); ++c)
      if (names_[c] == name) return rows_[row][c];
    throw std::out_of_range("no column " + name);
  }
  machine::Joints joints(std::size_t row, const std::string& letters) const {
    machine::Joints q(static_cast<int>(letters.size()));
    for (std::size_t j = 0; j < letters.size(); ++j) q[static_cast<int>(j)] = at(row, std::string(1, letters[j]));
    return q;
  }

 private:
  std::vector<std::string> names_;
  std::vector<std::vector<double>> rows_;
};

// The text a command prints on stdout, and its exit code.
struct CommandResult {
  std::string out;
  int exit_code;
};

// Runs a shell command; what it writes to stdout, and its exit code.
inline CommandResult run_command(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (std::size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = pclose(pipe);
  return {out, WEXITSTATUS(status)};
}

// Runs the volcomp just built with `args`; stdout and stderr together.
inline CommandResult run_volcomp(const std::string& args) {
  return run_command(std::string(VC_VOLCOMP) + " " + args + " 2>&1");
}

// The same with stdout alone (stderr to `stderr_file`).
inline CommandResult run_volcomp_stdout(const std::string& args, const std::string& stderr_file) {
  return run_command(std::string(VC_VOLCOMP) + " " + args + " 2>'" + stderr_file + "'");
}

// A file's bytes; empty if it cannot be read (a test that expects the file says so itself).
inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline std::string trimmed(const std::string& s) {
  const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  const auto begin = std::find_if_not(s.begin(), s.end(), space);
  const auto end = std::find_if_not(s.rbegin(), s.rend(), space).base();
  return begin < end ? std::string(begin, end) : std::string();
}

// The regular files of `folder` whose name ends in `extension` (".ini"), sorted.
inline std::vector<std::filesystem::path> files_with_extension(const std::filesystem::path& folder,
                                                               const std::string& extension) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.is_regular_file() && entry.path().extension() == extension) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// The message with "<source tree>/" removed wherever it occurs.
inline std::string relative_message(std::string message) {
  const std::string root = std::filesystem::path(VC_SOURCE_DIR).lexically_normal().string() + "/";
  for (std::size_t at; (at = message.find(root)) != std::string::npos;) message.erase(at, root.size());
  return message;
}

}  // namespace vc::test
