#include "vc/acceptance/tolerances.hpp"

#include <string_view>
#include <utility>
#include <vector>

#include "vc/machine/toml_file.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::acceptance {

Tolerances read_tolerances(const std::string& path) {
  const machine::TomlFile file(path);
  file.check_keys(file.root(), "the tolerances (one table per kind of test)", {"diagonal", "axis", "circle", "rtest"});
  Tolerances t;
  t.path = path;
  // Each table's keys SYMBOL_um (the key's symbol, the figure's symbol) into `limits`.
  const auto read = [&](const char* table, std::vector<std::pair<std::string, std::string>> keys,
                        std::map<std::string, double>& limits) {
    const toml::table* d = file.table(file.root(), table, false, "");
    if (!d) return;
    std::vector<std::string_view> names;
    for (const auto& [key, symbol] : keys) names.push_back(key);
    const std::string context = "[" + std::string(table) + "]";
    file.check_keys(*d, context, names);
    for (const auto& [key, symbol] : keys)
      if (const toml::node* n = file.get(*d, key, false, context)) {
        const double um = file.scalar(*n, key);
        if (!(um > 0)) throw LoadError(file.where(*n), "'" + key + "' must be a limit > 0 um");
        limits[symbol] = um * 1e-3;
      }
  };
  const std::vector<std::pair<std::string, std::string>> iso230_2 = {
      {"A_um", "A"}, {"E_um", "E"}, {"R_um", "R"}, {"B_um", "B"}, {"M_um", "M"}};
  read("diagonal", iso230_2, t.diagonal_mm);
  read("axis", iso230_2, t.axis_mm);
  read("circle", {{"Gb_um", "G(b)"}, {"H_um", "H"}, {"F_um", "F"}}, t.circle_mm);
  read("rtest", {{"X_um", "X"}, {"Y_um", "Y"}, {"Z_um", "Z"}, {"D_um", "D"}}, t.rtest_mm);
  return t;
}

}  // namespace vc::acceptance
