#include "vc/init/init.hpp"

#include <filesystem>
#include <cctype>
#include <sstream>

#include "vc/init/hal_file.hpp"
#include "vc/init/kinematics_line.hpp"
#include "vc/init/machine_file_writer.hpp"
#include "vc/init/shared_files.hpp"
#include "vc/init/stock_kinematics.hpp"

namespace vc::init {

std::string machine_parameter(const std::string& machine_file, const std::string& folder) {
  const std::string path = absolute_path(machine_file);
  return display_path(path, folder);
}

namespace {

std::vector<InputFile> inputs_of(const LinuxcncIni& ini, const HalConfig& hal, const SharedFiles& shared) {
  std::vector<InputFile> inputs{{ini.path(), "the INI file"}};
  for (const IniInclude& include : ini.includes())
    inputs.push_back({include.path, "a file the INI includes (" + display_path(ini.path(), ini.folder()) + ":" +
                                        std::to_string(include.line) + ")"});
  for (const HalFileUse& use : hal.uses)
    inputs.push_back({use.path, std::string(use.read ? "a HAL file" : "a Tcl HAL file") + " (" + use.cite + ")"});
  for (const HalSource& source : hal.sources)
    inputs.push_back({source.path, "a HAL file run by source (" + source.cite + ")"});
  if (const IniEntry* table = ini.find("EMCIO", "TOOL_TABLE"))
    inputs.push_back({absolute_path((std::filesystem::path(ini.folder()) / table->value).string()),
                      "the tool table (" + ini.cite(*table) + ")"});
  for (const std::string& other : shared.inis)
    inputs.push_back({other, "another configuration's INI file in the folder"});
  return inputs;
}

// What becomes of trivkins' kinematics type (kinstype=, trivkins.c: KINEMATICS_IDENTITY unless it
// starts with b/B: BOTH, f/F: FORWARD_ONLY, i/I: INVERSE_ONLY): volkins is always KINEMATICS_BOTH.
// LinuxCNC's planner never reads the type; what it changes is kins/README.md's "The kinematics
// type", with LinuxCNC's lines.
std::string kinematics_type_remark(const KinematicsLine& kinematics) {
  const std::string* type = kinematics.parameter("kinstype");
  const std::string where = type ? kinematics.entry->where().to_string() + ": kinstype=" + *type
                                 : std::string("no kinstype=: trivkins' default");
  const char first = trivkins_type(type);
  if (first == 'b')
    return "the kinematics type stays KINEMATICS_BOTH (" + where + "), volkins' own: volkins' line needs no kinstype=.";
  const std::string stock = first == 'f'   ? "KINEMATICS_FORWARD_ONLY"
                            : first == 'i' ? "KINEMATICS_INVERSE_ONLY"
                                           : "KINEMATICS_IDENTITY";
  return "the kinematics type changes from " + stock + " (" + where +
         ") to volkins' KINEMATICS_BOTH. The planned path stays the same (LinuxCNC's planner does not read the "
         "type); what changes: MDI, programs and world jogs need every joint homed first (\"all joints must be "
         "homed before going into coordinated mode\"), and the GUIs jog joints, not axes, in joint mode "
         "(kins/README.md, \"The kinematics type\").";
}

}  // namespace

InitResult run_init(const InitRequest& request) {
  const LinuxcncIni ini = LinuxcncIni::read(request.ini);
  const KinematicsLine kinematics = read_kinematics_line(ini);
  const HalConfig hal = read_hal(ini);
  const SharedFiles shared = files_shared_in_folder(ini);
  InitResult result;
  result.folder = ini.folder();
  result.inputs = inputs_of(ini, hal, shared);
  result.machine = nominal_machine(ini, hal, kinematics);
  result.machine.remarks.insert(result.machine.remarks.end(), ini.remarks().begin(), ini.remarks().end());
  if (kinematics.kind == StockModule::Trivkins) result.machine.remarks.push_back(kinematics_type_remark(kinematics));
  for (const HalFileUse& use : hal.uses)
    if (!use.read)
      result.not_read.push_back(use.path + " (" + use.cite + "): a Tcl file; check that it sets no " +
                                kinematics.module + " pin and nets motion.tooloffset.z nowhere");
  result.machine_path = machine_parameter(request.machine_file, ini.folder());
  result.patch =
      patch_config(ini, hal, kinematics, result.machine, result.machine_path, {request.edit_shared, shared.files});
  result.remarks = shared.remarks;
  result.remarks.insert(result.remarks.end(), result.patch.remarks.begin(), result.patch.remarks.end());
  std::ostringstream text;
  write_machine_file(result.machine, {ini.path(), request.date, result.not_read}, text);
  result.machine_text = text.str();
  return result;
}

}  // namespace vc::init
