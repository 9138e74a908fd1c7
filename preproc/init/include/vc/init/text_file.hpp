// A text file as its lines, each with its own line end, so that a patch keeps every line it
// does not change byte for byte (CRLF, trailing spaces, a last line without a newline).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace vc::init {

struct TextLine {
  std::string text;  // without the line end
  std::string end;   // "\n", "\r\n", or "" for a last line without one
};

struct TextFile {
  std::string path;  // absolute
  std::vector<TextLine> lines;

  // Line `number` (1-based).
  const TextLine& line(int number) const { return lines.at(static_cast<std::size_t>(number - 1)); }
};

// Throws vc::LoadError naming the file if it cannot be read; `what` says what it is for
// ("INI file", "HAL file").
TextFile read_text_file(const std::string& path, const std::string& what);

// `s` without leading and trailing blanks (space, tab, CR).
std::string trim(std::string_view s);

// `path` made absolute and normal (no "." or ".." parts).
std::string absolute_path(const std::string& path);

// How a file is named in messages and in the machine file's comments: relative to `folder`
// when it lies inside it, else absolute.
std::string display_path(const std::string& path, const std::string& folder);

// "file:line `text`": where a value comes from, for the machine file's comments and messages.
std::string cite(const std::string& path, int line, const std::string& text, const std::string& folder);

}  // namespace vc::init
