#include "vc/init/text_file.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include "vc/tables/source_error.hpp"

namespace vc::init {

namespace fs = std::filesystem;

TextFile read_text_file(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in || fs::is_directory(path)) throw LoadError({path}, "cannot read the " + what);
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
    file.lines.push_back(std::move(line));
  }
  return file;
}

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
  return display_path(path, folder) + ":" + std::to_string(line) + " `" + text + "`";
}

}  // namespace vc::init
