#include "program_files.hpp"

#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
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

interpreter::Position start_position(const std::string& value) {
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
  // The INI: sections, "NAME = value" lines, '#' and ';' comments.
  std::ifstream in(value);
  std::map<std::string, std::pair<std::string, int>> entries;  // "SECTION.NAME" -> value, line
  std::string section, line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#' || line[first] == ';') continue;
    if (line[first] == '[') {
      section = line.substr(first + 1, line.find(']') - first - 1);
      continue;
    }
    const std::size_t equals = line.find('=');
    if (equals == std::string::npos) continue;
    auto trim = [](std::string t) {
      t.erase(0, t.find_first_not_of(" \t\r"));
      t.erase(t.find_last_not_of(" \t\r") + 1);
      return t;
    };
    entries.try_emplace(section + "." + trim(line.substr(0, equals)), trim(line.substr(equals + 1)), number);
  }
  const auto coordinates = entries.find("TRAJ.COORDINATES");
  if (coordinates == entries.end()) throw LoadError({value}, "--start: no [TRAJ]COORDINATES in the INI file");
  int joint = 0;
  for (char c : coordinates->second.first) {
    if (c == ' ' || c == '\t') continue;
    const char* axis = std::strchr(interpreter::kAxisLetters, std::toupper(static_cast<unsigned char>(c)));
    if (!axis) throw LoadError({value, coordinates->second.second}, std::string("--start: axis ") + c + " is not one of XYZABC");
    const auto home = entries.find("JOINT_" + std::to_string(joint) + ".HOME");
    if (home != entries.end()) {
      std::size_t used = 0;
      try {
        start[static_cast<std::size_t>(axis - interpreter::kAxisLetters)] = std::stod(home->second.first, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0) throw LoadError({value, home->second.second}, "--start: HOME is not a number");
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
