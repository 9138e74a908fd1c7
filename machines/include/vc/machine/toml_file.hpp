// A TOML input file, parsed, and the typed getters every reader of one shares (the machine
// file, a controller description, the deflection file): each problem a LoadError at the
// FILE:LINE:COLUMN of the key or value concerned, as compilers write them.
//
// A target that includes this header links tomlplusplus::tomlplusplus itself (for toml++'s
// compiled-library settings); vc_machine keeps it private so its other users build as before.
#pragma once

#include <string>
#include <string_view>
#include <toml++/toml.h>
#include <vector>

#include "vc/tables/source_error.hpp"

namespace vc::machine {

class TomlFile {
 public:
  // Reads and parses `path`: a syntax error is a LoadError at its FILE:LINE:COLUMN, a file that
  // cannot be read one at FILE.
  explicit TomlFile(std::string path);

  const std::string& path() const { return path_; }
  const toml::table& root() const { return root_; }

  SourceLocation where(const toml::source_region& r) const;
  SourceLocation where(const toml::node& n) const { return where(n.source()); }

  // Every key of `t` is one of `allowed`, else "unknown key 'K' in CONTEXT (expected one of: ...)"
  // at the key.
  void check_keys(const toml::table& t, const std::string& context, const std::vector<std::string_view>& allowed) const;

  // The value of `key`; nullptr if it is absent and not required, else "CONTEXT needs 'KEY'" at
  // the table (an empty context: "needs 'KEY'").
  const toml::node* get(const toml::table& t, std::string_view key, bool required, const std::string& context) const;

  // The table `key`; nullptr if absent and not required, else "CONTEXT needs a [KEY] table".
  const toml::table* table(const toml::table& t, std::string_view key, bool required, const std::string& context) const;

  // A string: "'KEY' must be a string" at the value; absent and not required: "".
  std::string text(const toml::node& n, std::string_view key) const;
  std::string text(const toml::table& t, std::string_view key, bool required, const std::string& context) const;

  // A finite number (an integer or a float): "'KEY' must be a finite number" at the value.
  double scalar(const toml::node& n, std::string_view key) const;

 private:
  std::string path_;
  toml::table root_;
};

}  // namespace vc::machine
