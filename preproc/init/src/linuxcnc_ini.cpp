#include "vc/init/linuxcnc_ini.hpp"

#include <cstdlib>
#include <filesystem>
#include <optional>

namespace vc::init {
namespace {

namespace fs = std::filesystem;

constexpr const char* kBlanks = " \t\r";

// A physical line of the flattened INI: the file it is in and its number there.
struct SourceLine {
  const TextFile* file;
  int number;
  const std::string& text() const { return file->line(number).text; }
};

// The file an #INCLUDE line names (the shell's `eval echo` of it: `~` expanded) and where the
// name starts; nullopt if the line is not an #INCLUDE, "" for a bare one.
std::optional<std::pair<std::string, std::size_t>> included_name(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos || text.compare(first, 8, "#INCLUDE") != 0) return std::nullopt;
  const std::size_t after = first + 8;
  if (after < text.size() && text[after] != ' ' && text[after] != '\t') return std::nullopt;
  const std::size_t start = std::min(text.size(), text.find_first_not_of(" \t", after));
  std::string name = trim(std::string_view(text).substr(after));
  if (!name.empty() && name[0] == '~')
    if (const char* home = std::getenv("HOME")) name = home + name.substr(1);
  return std::make_pair(name, start);
}

}  // namespace

LinuxcncIni LinuxcncIni::read(const std::string& path) {
  LinuxcncIni ini;
  ini.path_ = absolute_path(path);
  ini.folder_ = fs::path(ini.path_).parent_path().string();
  ini.files_.push_back(read_text_file(ini.path_, "INI file"));

  // Flatten #INCLUDEs first (files_ must not grow while lines point into it).
  const TextFile& main = ini.files_.front();
  for (int n = 1; n <= static_cast<int>(main.lines.size()); ++n) {
    const auto name = included_name(main.line(n).text);
    if (!name) continue;
    if (name->first.empty()) {  // handle_includes warns and goes on; the line is a comment
      ini.remarks_.push_back(init::cite(ini.path_, n, trim(main.line(n).text), ini.folder_) +
                             ": #INCLUDE without a file name, skipped (LinuxCNC warns \"found #INCLUDE with no "
                             "filename\" and goes on)");
      continue;
    }
    const fs::path file =
        fs::path(name->first).is_absolute() ? fs::path(name->first) : fs::path(ini.folder_) / name->first;
    const std::string why = unreadable_reason(file.string());
    if (!why.empty())
      throw LoadError({ini.path_, n}, "#INCLUDE " + printable(name->first) + ": cannot read " +
                                          absolute_path(file.string()) + ": " + why);
    ini.includes_.push_back(
        {n, main.line(n).text.substr(name->second, std::string::npos), name->second, absolute_path(file.string())});
    ini.includes_.back().written = trim(ini.includes_.back().written);
  }
  ini.files_.reserve(1 + ini.includes_.size());
  for (const IniInclude& include : ini.includes_) ini.files_.push_back(read_text_file(include.path, "#INCLUDE file"));
  std::vector<SourceLine> lines;
  std::size_t next_include = 0;
  for (int n = 1; n <= static_cast<int>(ini.files_.front().lines.size()); ++n) {
    if (next_include < ini.includes_.size() && ini.includes_[next_include].line == n) {
      const TextFile& included = ini.files_[++next_include];
      for (int k = 1; k <= static_cast<int>(included.lines.size()); ++k) lines.push_back({&included, k});
      continue;
    }
    lines.push_back({&ini.files_.front(), n});
  }

  IniSection* section = nullptr;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const SourceLine& first = lines[i];
    std::string text = first.text();
    int last = first.number;
    // A line ending in '\' continues on the next line of the same file.
    while (!text.empty() && text.back() == '\\' && i + 1 < lines.size() && lines[i + 1].file == first.file) {
      text.pop_back();
      text += lines[++i].text();
      last = lines[i].number;
    }
    const std::size_t start = text.find_first_not_of(kBlanks);
    if (start == std::string::npos || text[start] == '#' || text[start] == ';') continue;
    if (text[start] == '[') {
      const std::size_t close = text.find(']', start);
      ini.sections_.push_back(
          {text.substr(start + 1, close == std::string::npos ? std::string::npos : close - start - 1),
           first.file->path,
           first.number,
           {}});
      section = &ini.sections_.back();
      continue;
    }
    const std::size_t equals = text.find('=', start);
    if (!section || equals == std::string::npos) continue;
    IniEntry entry;
    entry.section = section->name;
    entry.key = text.substr(start, text.find_first_of(" \t=", start) - start);
    entry.value_offset = text.find_first_not_of(" \t", equals + 1);
    if (entry.value_offset == std::string::npos) entry.value_offset = text.size();
    entry.value = trim(std::string_view(text).substr(entry.value_offset));
    entry.path = first.file->path;
    entry.line = first.number;
    entry.last_line = last;
    entry.text = trim(first.text());
    section->entries.push_back(std::move(entry));
  }
  return ini;
}

const IniSection* LinuxcncIni::section(std::string_view name) const {
  for (const IniSection& s : sections_)
    if (s.name == name) return &s;
  return nullptr;
}

const IniEntry* LinuxcncIni::find(std::string_view section_name, std::string_view key) const {
  const std::vector<const IniEntry*> all = find_all(section_name, key);
  return all.empty() ? nullptr : all.front();
}

std::vector<const IniEntry*> LinuxcncIni::find_all(std::string_view section_name, std::string_view key) const {
  std::vector<const IniEntry*> found;
  for (const IniSection& s : sections_) {
    if (!section_name.empty() && &s != section(section_name)) continue;
    for (const IniEntry& e : s.entries)
      if (e.key == key) found.push_back(&e);
  }
  return found;
}

SourceLocation LinuxcncIni::where_missing(std::string_view section_name) const {
  if (const IniSection* s = section(section_name)) return {s->path, s->line};
  return {path_};
}

std::string LinuxcncIni::cite(const IniEntry& entry) const {
  return init::cite(entry.path, entry.line, entry.text, folder_);
}

}  // namespace vc::init
