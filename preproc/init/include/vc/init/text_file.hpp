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

// Throws vc::LoadError naming the file and why it cannot be read (no such file, a directory,
// the system's reason), and at a NUL byte (file:line:column): LinuxCNC's readers take a line
// only up to it. `what` says what it is for ("INI file", "HAL file").
TextFile read_text_file(const std::string& path, const std::string& what);

// Why `path` cannot be opened for reading ("no such file", "a directory", errno's text), or ""
// if it can.
std::string unreadable_reason(const std::string& path);

// A line (or part of one) of a user's file as a message or a comment may show it: every byte
// that is not printable (control characters, DEL, bytes that are not UTF-8) escaped as \0,
// \r or \xNN; tabs and UTF-8 text kept. Every message that quotes a line goes through it.
std::string printable(std::string_view text);
// "`text`", printable.
std::string quoted_line(std::string_view text);

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
