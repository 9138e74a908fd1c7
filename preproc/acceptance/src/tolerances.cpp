#include "vc/acceptance/tolerances.hpp"

#include "vc/machine/toml_file.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::acceptance {

Tolerances read_tolerances(const std::string& path) {
  const machine::TomlFile file(path);
  file.check_keys(file.root(), "the tolerances (one table per kind of test)", {"diagonal"});
  Tolerances t;
  t.path = path;
  if (const toml::table* d = file.table(file.root(), "diagonal", false, "")) {
    file.check_keys(*d, "[diagonal]", {"A_um", "E_um", "R_um", "B_um", "M_um"});
    for (const char* symbol : {"A", "E", "R", "B", "M"}) {
      const std::string key = std::string(symbol) + "_um";
      if (const toml::node* n = file.get(*d, key, false, "[diagonal]")) {
        const double um = file.scalar(*n, key);
        if (!(um > 0)) throw LoadError(file.where(*n), "'" + key + "' must be a limit > 0 um");
        t.diagonal_mm[symbol] = um * 1e-3;
      }
    }
  }
  return t;
}

}  // namespace vc::acceptance
