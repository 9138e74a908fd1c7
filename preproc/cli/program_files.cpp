#include "program_files.hpp"

#include <stdexcept>

#include "vc/predistort/predistort.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::cli {

ProgramFiles::ProgramFiles(const std::string& tool_table, const std::string& var_file) {
  if (!tool_table.empty()) tools = interpreter::read_tool_table(tool_table);
  if (!var_file.empty()) {
    parameters.emplace();
    interpreter::read_var_file(var_file, *parameters);
  }
}

interpreter::Setup ProgramFiles::setup(const std::string& program, const machine::Model& model, bool tcp) const {
  interpreter::Setup setup;
  setup.file = program;
  setup.machine_axes = predistort::program_axes(model);
  setup.tools = tools ? &*tools : nullptr;
  setup.var_file = parameters ? &*parameters : nullptr;
  setup.tool_length_in_world = !tcp;
  return setup;
}

std::optional<predistort::Deflection> ProgramFiles::deflection(const std::string& process,
                                                                const machine::Model& model) const {
  if (process.empty()) return std::nullopt;
  bool stiff = false;
  for (const auto& c : model.compliance) stiff = stiff || !c.mm_per_N.empty();
  if (!stiff) throw LoadError({model.path}, "--process needs a [stiffness] table in the machine file");
  return std::optional<predistort::Deflection>(std::in_place, model,
                                               predistort::load_process(process, tools ? &*tools : nullptr));
}

machine::WorldConvention world_convention(const std::string& name) {
  if (name == "axes") return machine::WorldConvention::Axes;
  if (name == "tcp") return machine::WorldConvention::Tcp;
  throw std::runtime_error("--world must be axes or tcp, not " + name);
}

}  // namespace vc::cli
