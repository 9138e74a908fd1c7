// Edits to one text file (line replacements, deletions, insertions) and the unified diff that
// makes them (`patch -p1`): hunks with 3 lines of context, merged when they overlap or touch.
// Every line not edited stays byte for byte (its line end too); a replaced line keeps its end,
// an inserted one takes the end of the line it follows (CRLF stays CRLF).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "vc/init/text_file.hpp"

namespace vc::init {

class FileEdits {
 public:
  explicit FileEdits(const TextFile& file) : file_(&file) {}

  const TextFile& file() const { return *file_; }
  void replace(int line, std::string text);  // 1-based
  void remove(int line);
  void insert_after(int line, const std::vector<std::string>& texts);  // 0: before the first line
  bool removed(int line) const;
  bool empty() const { return changed_.empty() && inserted_.empty(); }

  // Lines the diff removes and adds (a replaced line counts in both).
  struct Counts {
    int removed = 0, added = 0;
  };
  Counts counts() const;

  // The file's lines after the edits.
  std::vector<TextLine> result() const;
  // `--- a/NAME`, `+++ b/NAME` and the hunks; "" without a change.
  std::string unified_diff(const std::string& name, int context = 3) const;

 private:
  struct Op {
    char kind;  // ' ' kept, '-' removed, '+' added
    TextLine line;
  };
  std::vector<Op> operations() const;

  const TextFile* file_;
  std::map<int, std::optional<std::string>> changed_;  // line -> new text (nullopt: removed)
  std::map<int, std::vector<std::string>> inserted_;   // after line
};

// The diff that creates NAME with `lines` (`--- /dev/null`, `+++ b/NAME`, one hunk).
std::string creation_diff(const std::string& name, const std::vector<TextLine>& lines);

}  // namespace vc::init
