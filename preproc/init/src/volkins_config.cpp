#include "vc/init/volkins_config.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>

#include "vc/init/number.hpp"
#include "vc/tables/number_text.hpp"

namespace vc::init {

VolkinsParameters read_volkins_parameters(const LinuxcncIni& ini) {
  const IniEntry* kins = ini.find("KINS", "KINEMATICS");
  std::istringstream words(kins ? kins->value : "");
  std::string word;
  if (!(words >> word) || word != "volkins")
    throw LoadError(kins ? kins->where() : ini.where_missing("KINS"),
                    "[KINS]KINEMATICS does not load volkins (a stock configuration: apply volcomp init's patch first)");
  VolkinsParameters p;
  std::string units = "mm";
  while (words >> word) {
    if (word.rfind("machine=", 0) == 0)  // rtapi_app starts in the configuration folder
      p.machine = (std::filesystem::path(ini.folder()) / word.substr(8)).lexically_normal().string();
    if (word.rfind("coordinates=", 0) == 0) p.coordinates = word.substr(12);
    if (word == "world=tcp") p.world = machine::WorldConvention::Tcp;
    if (word.rfind("units=", 0) == 0) units = word.substr(6);
  }
  if (units != "mm" && units != "inch")
    throw LoadError(kins->where(), "volkins' units=" + units + " is neither mm nor inch");
  p.units.mm_per_unit = units == "inch" ? 25.4 : 1.0;
  p.units.from = ini.cite(*kins);
  const LinearUnits linuxcnc = read_linear_units(ini);
  if (linuxcnc.mm_per_unit != p.units.mm_per_unit)
    throw LoadError(
        kins->where(),
        std::string("volkins is loaded with units=") + p.units.name() + " (" +
            (units == "mm" && kins->value.find("units=") == std::string::npos ? "its default" : "as written") +
            "), but LinuxCNC runs in " + linuxcnc.name() + " (" + linuxcnc.from + "): add units=" + linuxcnc.name() +
            " to the KINEMATICS line");
  return p;
}

int linuxcnc_joint(const VolkinsParameters& volkins, const machine::Model& model, int j) {
  const char letter = model.axes[static_cast<std::size_t>(j)].letter;
  const std::size_t at =
      std::min(volkins.coordinates.find(static_cast<char>(std::tolower(static_cast<unsigned char>(letter)))),
               volkins.coordinates.find(static_cast<char>(std::toupper(static_cast<unsigned char>(letter)))));
  return at == std::string::npos ? j : static_cast<int>(at);
}

double ini_number(const LinuxcncIni& ini, std::string_view section, std::string_view key, double otherwise,
                  std::string* from) {
  const IniEntry* e = ini.find(section, key);
  if (!e) return otherwise;
  double v = 0.0;
  if (!parse_number(e->value, v)) throw LoadError(e->where(), e->key + " = " + e->value + " is not a number");
  if (from) *from = ini.cite(*e);
  return v;
}

std::string um_or_mdeg(double v, bool rotary) { return fixed_text(v * 1e3, 2) + (rotary ? " mdeg" : " um"); }

}  // namespace vc::init
