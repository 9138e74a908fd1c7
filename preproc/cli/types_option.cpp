#include "types_option.hpp"

#include <CLI/CLI.hpp>
#include <stdexcept>

namespace vc::cli {

machine::TypeSelection TypesOption::selection() const {
  try {
    return machine::parse_type_selection(list);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("--types " + list + ": " + e.what());
  }
}

void add_types_option(CLI::App& command, TypesOption& option, const std::string& what) {
  command
      .add_option("--types", option.list,
                  what +
                      ": a comma-separated list of ISO/TR 16907 Annex A types, L-POS L-STR L-SQU L-ANG R-POS R-RAX "
                      "R-POR R-ANG L-SPEC R-SPEC, the composites L-VOL R-VOL L-VOL+ R-VOL+, FOR (the tool direction), "
                      "thermal, or all; the others' errors are left as they are (thermal off: the temperatures at "
                      "their references)")
      ->capture_default_str();
}

}  // namespace vc::cli
