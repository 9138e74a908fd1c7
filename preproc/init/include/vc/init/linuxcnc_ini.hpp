// A LinuxCNC 2.9 INI file read as LinuxCNC reads it, every value with its file and line.
//
// Rules (src/libnml/inifile/inifile.cc, scripts/linuxcnc's handle_includes):
// - `[SECTION]` starts a section; `KEY = VALUE` (blanks around '=' and before the key allowed)
//   gives a value, trailing blanks and a CR removed; a line whose first non-blank character is
//   '#' or ';' is a comment; a line ending in '\' continues on the next one.
// - A key may repeat (HALFILE, HALCMD): every entry is kept, in order.
// - Only the first section of a name is read, as LinuxCNC's lookups stop at the next '['.
// - `#INCLUDE file` in the INI file itself inserts that file (relative to the INI's folder,
//   `~` expanded); an #INCLUDE inside an included file is a comment, as LinuxCNC's expansion
//   does not recurse. A bare `#INCLUDE` (no file) is skipped with a remark: handle_includes
//   only warns about it.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "vc/init/text_file.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::init {

struct IniEntry {
  std::string section, key, value;
  std::string path;              // the file it is written in (the INI or an included file)
  int line = 0;                  // its first line
  int last_line = 0;             // its last line (a value continued with '\' spans several)
  std::size_t value_offset = 0;  // where the value starts in the first line's text
  std::string text;              // the first line, trimmed: for messages and comments

  SourceLocation where() const { return {path, line}; }
};

struct IniSection {
  std::string name;
  std::string path;
  int line = 0;  // of the [NAME] line
  std::vector<IniEntry> entries;
};

// An `#INCLUDE file` line of the INI file and the file it inserts.
struct IniInclude {
  int line = 0;                 // in the INI file
  std::string written;          // the name as written
  std::size_t name_offset = 0;  // where the name starts in the line's text
  std::string path;             // the file, absolute
};

class LinuxcncIni {
 public:
  // Throws vc::LoadError for a file (or an #INCLUDE) that cannot be read.
  static LinuxcncIni read(const std::string& path);

  const std::string& path() const { return path_; }      // absolute
  const std::string& folder() const { return folder_; }  // the configuration folder
  // The INI file and the files it includes, as read.
  const std::vector<TextFile>& files() const { return files_; }
  const std::vector<IniInclude>& includes() const { return includes_; }
  // What was read differently from how it is written, as LinuxCNC does (a bare #INCLUDE).
  const std::vector<std::string>& remarks() const { return remarks_; }

  // The first section of this name (the one LinuxCNC reads), or nullptr.
  const IniSection* section(std::string_view name) const;
  // The first entry of `key` in `section`, or nullptr; every entry, in order. An empty
  // `section` searches every section (halcmd's `[]KEY`).
  const IniEntry* find(std::string_view section, std::string_view key) const;
  std::vector<const IniEntry*> find_all(std::string_view section, std::string_view key) const;
  // Where a missing value would be written: the section's [NAME] line, else the INI file.
  SourceLocation where_missing(std::string_view section) const;

  // "file:line `text`" of an entry, file named relative to the configuration folder.
  std::string cite(const IniEntry& entry) const;

 private:
  std::string path_, folder_;
  std::vector<TextFile> files_;
  std::vector<IniInclude> includes_;
  std::vector<std::string> remarks_;
  std::vector<IniSection> sections_;
};

}  // namespace vc::init
