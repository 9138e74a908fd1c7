// init never writes a file it reads: the machine file and the patch are checked against every
// input (the INI, its #INCLUDEs, the HAL files and the files they source, the tool table, the
// folder's other INIs) and against each other before anything is written.
#pragma once

#include <string>
#include <vector>

namespace vc::init {

// A file init reads, and what it is for the message ("the INI file", "a HAL file (x.ini:12
// `HALFILE = x.hal`)").
struct InputFile {
  std::string path;  // absolute
  std::string what;
};

// The same file: std::filesystem::equivalent where both exist (a symlink or hard link to it
// counts), else the same absolute path with symlinks of the existing part resolved.
bool same_file(const std::string& a, const std::string& b);

// Throws std::runtime_error naming the option, the file and which input it is if `path`
// (given with `option`, "-o" or "--patch") is one of `inputs`.
void refuse_input_as_output(const std::vector<InputFile>& inputs, const std::string& option, const std::string& path);

}  // namespace vc::init
