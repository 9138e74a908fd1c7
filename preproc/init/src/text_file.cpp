#include "vc/init/text_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "vc/tables/source_error.hpp"

namespace vc::init {

namespace fs = std::filesystem;

std::string unreadable_reason(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (status.type() == fs::file_type::not_found) return "no such file";
  if (status.type() == fs::file_type::directory) return "a directory, not a file";
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return std::strerror(errno);
  std::fclose(file);
  return "";
}

TextFile read_text_file(const std::string& path, const std::string& what) {
  if (const std::string why = unreadable_reason(path); !why.empty())
    throw LoadError({path}, "cannot read the " + what + ": " + why);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw LoadError({path}, "cannot read the " + what + ": " + std::strerror(errno));
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  TextFile file{absolute_path(path), {}};
  for (std::size_t start = 0; start < content.size();) {
    const std::size_t newline = content.find('\n', start);
    TextLine line;
    if (newline == std::string::npos) {
      line.text = content.substr(start);
      start = content.size();
    } else {
      line.text = content.substr(start, newline - start);
      line.end = "\n";
      start = newline + 1;
    }
    if (!line.end.empty() && !line.text.empty() && line.text.back() == '\r') {
      line.text.pop_back();
      line.end = "\r\n";
    }
    if (const std::size_t nul = line.text.find('\0'); nul != std::string::npos)
      throw LoadError({path, static_cast<int>(file.lines.size()) + 1, static_cast<int>(nul) + 1},
                      "a NUL byte in " + quoted_line(line.text) + ": LinuxCNC reads the line only up to it (the " +
                          what + " must be text: remove the byte)");
    file.lines.push_back(std::move(line));
  }
  return file;
}

std::string printable(std::string_view text) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    // A UTF-8 sequence: its lead byte says how many continuation bytes (10xxxxxx) follow.
    const std::size_t length = byte >= 0xf0 && byte < 0xf5 ? 4 : byte >= 0xe0 ? 3 : byte >= 0xc2 ? 2 : 1;
    if (byte >= 0x80 && length > 1 && i + length <= text.size()) {
      bool valid = true;
      for (std::size_t k = 1; k < length; ++k)
        valid = valid && (static_cast<unsigned char>(text[i + k]) & 0xc0) == 0x80;
      if (valid) {
        out.append(text.substr(i, length));
        i += length;
        continue;
      }
    }
    if (byte == '\t' || (byte >= 0x20 && byte < 0x7f)) {
      out += static_cast<char>(byte);
    } else if (byte == 0) {  // \0, or \x00 before a digit (\00 would read as octal)
      out += i + 1 < text.size() && text[i + 1] >= '0' && text[i + 1] <= '9' ? "\\x00" : "\\0";
    } else if (byte == '\r') {
      out += "\\r";
    } else {
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 0xf];
    }
    ++i;
  }
  return out;
}

std::string quoted_line(std::string_view text) { return "`" + printable(text) + "`"; }

std::string trim(std::string_view s) {
  constexpr const char* kBlanks = " \t\r";
  const std::size_t first = s.find_first_not_of(kBlanks);
  if (first == std::string_view::npos) return {};
  return std::string(s.substr(first, s.find_last_not_of(kBlanks) - first + 1));
}

std::string absolute_path(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

std::string display_path(const std::string& path, const std::string& folder) {
  const fs::path relative = fs::path(path).lexically_relative(folder);
  if (relative.empty() || *relative.begin() == "..") return path;
  return relative.string();
}

std::string cite(const std::string& path, int line, const std::string& text, const std::string& folder) {
  return display_path(path, folder) + ":" + std::to_string(line) + " " + quoted_line(text);
}

}  // namespace vc::init
