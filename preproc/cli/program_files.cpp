#include "program_files.hpp"

#include <cctype>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "vc/init/linuxcnc_ini.hpp"
#include "vc/init/linuxcnc_units.hpp"
#include "vc/predistort/predistort.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::cli {

double machine_unit_mm(const std::string& name) {
  if (name == "mm") return 1.0;
  if (name == "inch") return 25.4;
  throw std::runtime_error("--machine-units must be mm or inch (LinuxCNC's [TRAJ]LINEAR_UNITS), not " + name);
}

ProgramFiles::ProgramFiles(const std::string& tool_table, const std::string& var_file, const std::string& machine_units)
    : machine_unit_mm(cli::machine_unit_mm(machine_units)) {
  if (!tool_table.empty()) tools = interpreter::read_tool_table(tool_table, machine_unit_mm);
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
  setup.machine_unit_mm = machine_unit_mm;
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

interpreter::Position start_position(const std::string& value, double unit_mm) {
  interpreter::Position start{};
  if (!std::filesystem::is_regular_file(value)) {
    std::istringstream list(value);
    std::string item;
    for (int i = 0; std::getline(list, item, ','); ++i) {
      std::size_t used = 0;
      if (i >= interpreter::kAxes) throw std::runtime_error("--start: at most 6 values (X,Y,Z,A,B,C)");
      try {
        start[static_cast<std::size_t>(i)] = std::stod(item, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != item.size())
        throw std::runtime_error("--start: '" + item + "' is not a number (give X,Y,Z[,A,B,C] or an INI file)");
    }
    return start;
  }
  // The INI, as LinuxCNC reads it (vc/init/linuxcnc_ini.hpp).
  const init::LinuxcncIni ini = init::LinuxcncIni::read(value);
  // LinuxCNC's LINEAR_UNITS, read as init reads it (vc/init/linuxcnc_units.hpp).
  const init::LinearUnits units = init::read_linear_units(ini);
  if (units.mm_per_unit != unit_mm)
    throw LoadError(ini.find("TRAJ", "LINEAR_UNITS")->where(),
                    "--start: the INI's LINEAR_UNITS is " + std::string(units.name()) + ": give --machine-units " +
                        units.name() + " (the .var file and the tool table are in it)");
  const init::IniEntry* coordinates = ini.find("TRAJ", "COORDINATES");
  if (!coordinates) throw LoadError({value}, "--start: no [TRAJ]COORDINATES in the INI file");
  int joint = 0;
  for (char c : coordinates->value) {
    if (c == ' ' || c == '\t') continue;
    const char* axis = std::strchr(interpreter::kAxisLetters, std::toupper(static_cast<unsigned char>(c)));
    if (!axis) throw LoadError(coordinates->where(), std::string("--start: axis ") + c + " is not one of XYZABC");
    if (const init::IniEntry* home = ini.find("JOINT_" + std::to_string(joint), "HOME")) {
      std::size_t used = 0;
      try {
        const int i = static_cast<int>(axis - interpreter::kAxisLetters);
        start[static_cast<std::size_t>(i)] =
            std::stod(home->value, &used) * (interpreter::is_linear(i) ? unit_mm : 1.0);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0) throw LoadError(home->where(), "--start: HOME is not a number");
    }
    ++joint;
  }
  return start;
}

machine::WorldConvention world_convention(const std::string& name) {
  if (name == "axes") return machine::WorldConvention::Axes;
  if (name == "tcp") return machine::WorldConvention::Tcp;
  throw std::runtime_error("--world must be axes or tcp, not " + name);
}

}  // namespace vc::cli
