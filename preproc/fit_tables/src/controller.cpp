#include "vc/fit_tables/controller.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "vc/machine/toml_file.hpp"

namespace vc::fit_tables {
namespace {

namespace fs = std::filesystem;

const char* const kAxisLetters = "XYZABCUVW";

bool is_axis_letter(const std::string& s) {
  return s.size() == 1 && std::string(kAxisLetters).find(s[0]) != std::string::npos;
}
bool is_linear_letter(const std::string& s) {
  return is_axis_letter(s) && std::string("XYZUVW").find(s[0]) != std::string::npos;
}

// The keys a [[table]] entry or [defaults] may set besides the table's axes.
const std::vector<std::string_view> kSettingKeys{"direction_dependent", "modulo",         "max_nodes",
                                                 "default_nodes",       "spacing",        "outside",
                                                 "resolution_um",       "resolution_deg", "resolution_arcsec"};

// The file's typed getters (where, check_keys, text) are TomlFile's.
class ControllerReader : machine::TomlFile {
 public:
  explicit ControllerReader(std::string path) : TomlFile(std::move(path)) {}

  Controller read() {
    const toml::table& root = this->root();
    Controller c;
    c.path = path();
    check_keys(root, "the controller file", {"controller", "defaults", "table"});
    const toml::table* head = root.get_as<toml::table>("controller");
    if (!head) throw LoadError({path(), 1, 1}, "the controller file needs a [controller] table");
    check_keys(*head, "[controller]", {"name", "title", "checked_against", "format"});
    c.name = text(*head, "name", true);
    c.title = text(*head, "title", false);
    c.checked_against = text(*head, "checked_against", false);
    if (c.name.empty()) throw LoadError(where(*head->get("name")), "the controller's name must not be empty");
    c.format = text(*head, "format", false);
    if (!c.format.empty() && c.format != "linuxcnc-comp-file" && c.format != "sinumerik-lec-cec")
      throw LoadError(where(*head->get("format")),
                      "unknown format '" + c.format +
                          "' (the writers there are: linuxcnc-comp-file, sinumerik-lec-cec; "
                          "leave it out for the generic CSV only)");

    TableSpec defaults;
    defaults.max_nodes = 256;
    defaults.default_nodes = 7;
    if (const toml::node* d = root.get("defaults")) {
      if (!d->is_table()) throw LoadError(where(*d), "'defaults' must be a table");
      check_keys(*d->as_table(), "[defaults]", kSettingKeys);
      read_settings(*d->as_table(), defaults);
    }
    const toml::node* list = root.get("table");
    if (!list || !list->is_array_of_tables())
      throw LoadError(list ? where(*list) : SourceLocation{path(), 1, 1},
                      "the controller file needs at least one [[table]] entry");
    for (const toml::node& n : *list->as_array()) c.tables.push_back(read_table(*n.as_table(), defaults));
    return c;
  }

 private:
  using TomlFile::text;
  // A controller file's messages name no table: "needs 'name'".
  std::string text(const toml::table& t, std::string_view key, bool required) const {
    return TomlFile::text(t, key, required, "");
  }

  void read_settings(const toml::table& t, TableSpec& s) const {
    if (const toml::node* n = t.get("direction_dependent")) s.direction_dependent = flag(*n, "direction_dependent");
    if (const toml::node* n = t.get("modulo")) s.modulo = flag(*n, "modulo");
    if (const toml::node* n = t.get("max_nodes")) s.max_nodes = count(*n, "max_nodes");
    if (const toml::node* n = t.get("default_nodes")) s.default_nodes = count(*n, "default_nodes");
    if (const toml::node* n = t.get("spacing"))
      if (text(*n, "spacing") != "equal")
        throw LoadError(where(*n),
                        "'spacing' must be \"equal\" (nodes equally spaced over the input axis's travel: "
                        "the only rule the fit models)");
    if (const toml::node* n = t.get("outside"))
      if (text(*n, "outside") != "hold")
        throw LoadError(where(*n),
                        "'outside' must be \"hold\" (the first and last values held outside the nodes: "
                        "the only rule the fit models)");
    if (const toml::node* n = t.get("resolution_um")) s.resolution_um = resolution(*n, "resolution_um");
    if (const toml::node* n = t.get("resolution_deg")) s.resolution_deg = resolution(*n, "resolution_deg");
    if (const toml::node* n = t.get("resolution_arcsec")) s.resolution_arcsec = resolution(*n, "resolution_arcsec");
  }

  bool flag(const toml::node& n, std::string_view key) const {
    if (!n.is_boolean()) throw LoadError(where(n), "'" + std::string(key) + "' must be true or false");
    return n.as_boolean()->get();
  }
  int count(const toml::node& n, std::string_view key) const {
    if (!n.is_integer() || n.as_integer()->get() < 2 || n.as_integer()->get() > 100000)
      throw LoadError(where(n), "'" + std::string(key) + "' must be a whole number of nodes, 2 .. 100000");
    return static_cast<int>(n.as_integer()->get());
  }
  double resolution(const toml::node& n, std::string_view key) const {
    const auto v = n.value<double>();
    if (!v || !std::isfinite(*v) || *v < 0)
      throw LoadError(where(n), "'" + std::string(key) + "' must be a number >= 0 (0: values stored exactly)");
    return *v;
  }

  TableSpec read_table(const toml::table& t, const TableSpec& defaults) const {
    TableSpec s = defaults;
    s.where = where(t);
    const std::string kind = text(t, "kind", true);
    std::vector<std::string_view> allowed = kSettingKeys;
    allowed.push_back("kind");
    if (kind == "positioning") {
      s.kind = TableKind::Positioning;
      allowed.push_back("axis");
      check_keys(t, "a positioning [[table]]", allowed);
      s.input = text(t, "axis", true);
      if (s.input != "all" && !is_axis_letter(s.input))
        throw LoadError(where(*t.get("axis")),
                        "'axis' must be an axis letter (X Y Z A B C U V W) or \"all\", not '" + s.input + "'");
    } else if (kind == "cross" || kind == "squareness") {
      s.kind = kind == "cross" ? TableKind::Cross : TableKind::Squareness;
      allowed.push_back("input");
      allowed.push_back("output");
      check_keys(t, "a " + kind + " [[table]]", allowed);
      s.input = text(t, "input", true);
      s.output = text(t, "output", true);
      const bool linear_only = s.kind == TableKind::Squareness;
      for (const char* key : {"input", "output"}) {
        const std::string& letter = std::string(key) == "input" ? s.input : s.output;
        if (linear_only ? !is_linear_letter(letter) : !is_axis_letter(letter))
          throw LoadError(where(*t.get(key)), "'" + std::string(key) + "' must be " +
                                                  (linear_only ? "a linear axis letter (X Y Z U V W)"
                                                               : "an axis letter (X Y Z A B C U V W)") +
                                                  ", not '" + letter + "'");
      }
      if (s.input == s.output)
        throw LoadError(where(*t.get("output")), "a " + kind + " table's output must be another axis than its input");
    } else {
      const toml::node* n = t.get("kind");
      throw LoadError(n ? where(*n) : where(t),
                      "unknown kind '" + kind + "' (expected positioning, cross or squareness)");
    }
    read_settings(t, s);
    if (s.default_nodes > s.max_nodes)
      throw LoadError(s.where, "default_nodes (" + std::to_string(s.default_nodes) + ") is above max_nodes (" +
                                   std::to_string(s.max_nodes) + ")");
    return s;
  }
};

fs::path controllers_folder() { return fs::path(VC_FIT_TABLES_CONTROLLERS_DIR); }

}  // namespace

const char* kind_name(TableKind kind) {
  switch (kind) {
    case TableKind::Positioning:
      return "positioning";
    case TableKind::Cross:
      return "cross";
    case TableKind::Squareness:
      return "squareness";
  }
  return "?";
}

Controller load_controller(const std::string& path) { return ControllerReader(path).read(); }

std::vector<std::string> shipped_controllers() {
  std::vector<std::string> names;
  std::error_code ignored;
  for (const auto& entry : fs::directory_iterator(controllers_folder(), ignored))
    if (entry.path().extension() == ".toml") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string controller_file(const std::string& name_or_path) {
  if (name_or_path.find('/') != std::string::npos ||
      (name_or_path.size() > 5 && name_or_path.compare(name_or_path.size() - 5, 5, ".toml") == 0))
    return name_or_path;
  const fs::path file = controllers_folder() / (name_or_path + ".toml");
  if (!fs::exists(file)) {
    std::string known;
    for (const std::string& n : shipped_controllers()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("--controller " + name_or_path + ": no such controller (shipped: " + known +
                                "; or give the path of a controller file)");
  }
  return file.string();
}

}  // namespace vc::fit_tables
