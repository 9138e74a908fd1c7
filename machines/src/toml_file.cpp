#include "vc/machine/toml_file.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

namespace vc::machine {
namespace {

std::string join(const std::vector<std::string_view>& words) {
  std::string s;
  for (auto w : words) s += (s.empty() ? "" : ", ") + std::string(w);
  return s;
}

}  // namespace

TomlFile::TomlFile(std::string path) : path_(std::move(path)) {
  try {
    root_ = toml::parse_file(path_);
  } catch (const toml::parse_error& e) {
    throw LoadError(where(e.source()), std::string(e.description()));
  } catch (const std::exception& e) {
    throw LoadError({path_}, e.what());
  }
}

SourceLocation TomlFile::where(const toml::source_region& r) const {
  return {path_, static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
}

void TomlFile::check_keys(const toml::table& t, const std::string& context,
                          const std::vector<std::string_view>& allowed) const {
  for (auto&& [key, value] : t)
    if (std::find(allowed.begin(), allowed.end(), key.str()) == allowed.end())
      throw LoadError(where(key.source()), "unknown key '" + std::string(key.str()) + "' in " + context +
                                               " (expected one of: " + join(allowed) + ")");
}

const toml::node* TomlFile::get(const toml::table& t, std::string_view key, bool required,
                                const std::string& context) const {
  const toml::node* n = t.get(key);
  if (!n && required)
    throw LoadError(where(t), (context.empty() ? "" : context + " ") + "needs '" + std::string(key) + "'");
  return n;
}

const toml::table* TomlFile::table(const toml::table& t, std::string_view key, bool required,
                                   const std::string& context) const {
  const toml::node* n = t.get(key);
  if (!n) {
    if (required) throw LoadError(where(t), context + " needs a [" + std::string(key) + "] table");
    return nullptr;
  }
  if (!n->is_table()) throw LoadError(where(*n), "'" + std::string(key) + "' must be a table");
  return n->as_table();
}

std::string TomlFile::text(const toml::node& n, std::string_view key) const {
  if (!n.is_string()) throw LoadError(where(n), "'" + std::string(key) + "' must be a string");
  return n.as_string()->get();
}

std::string TomlFile::text(const toml::table& t, std::string_view key, bool required,
                           const std::string& context) const {
  const toml::node* n = get(t, key, required, context);
  return n ? text(*n, key) : std::string();
}

double TomlFile::scalar(const toml::node& n, std::string_view key) const {
  const auto v = n.value<double>();
  if (!v || !std::isfinite(*v)) throw LoadError(where(n), "'" + std::string(key) + "' must be a finite number");
  return *v;
}

}  // namespace vc::machine
