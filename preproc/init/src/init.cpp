#include "vc/init/init.hpp"

#include <sstream>

#include "vc/init/hal_file.hpp"
#include "vc/init/kinematics_line.hpp"
#include "vc/init/machine_file_writer.hpp"
#include "vc/init/stock_kinematics.hpp"

namespace vc::init {

std::string machine_parameter(const std::string& machine_file, const std::string& folder) {
  const std::string path = absolute_path(machine_file);
  return display_path(path, folder);
}

InitResult run_init(const InitRequest& request) {
  const LinuxcncIni ini = LinuxcncIni::read(request.ini);
  const KinematicsLine kinematics = read_kinematics_line(ini);
  const HalConfig hal = read_hal(ini);
  InitResult result;
  result.folder = ini.folder();
  result.machine = nominal_machine(ini, hal, kinematics);
  for (const HalFileUse& use : hal.uses)
    if (!use.read)
      result.not_read.push_back(use.path + " (" + use.cite + "): a Tcl file; check that it sets no " +
                                kinematics.module + " pin and nets motion.tooloffset.z nowhere");
  result.machine_path = machine_parameter(request.machine_file, ini.folder());
  result.patch = patch_config(ini, hal, kinematics, result.machine, result.machine_path);
  std::ostringstream text;
  write_machine_file(result.machine, {ini.path(), request.date, result.not_read}, text);
  result.machine_text = text.str();
  return result;
}

}  // namespace vc::init
