#include "vc/init/kinematics_line.hpp"

#include <sstream>

namespace vc::init {
namespace {

constexpr const char* kKnown = "init knows trivkins, xyzbc-trt-kins, xyzac-trt-kins and 5axiskins; ";
constexpr const char* kNotASerialChain =
    ": not a serial chain of linear axes plus a rotary table or head, which is what the model expresses";

// Why a module LinuxCNC ships is not one init can describe.
std::string why_not(const std::string& module) {
  if (module == "maxkins")
    return "maxkins is refused: it maps joints by number (0-8 = X Y Z A B C U V W, no coordinates parameter), passes "
           "joint 3 (A) through as a third rotary axis and moves the tool with joints 6-8 (U along the tilted head, V "
           "along y, W along the tool axis): further linear axes; the model has three linear and at most two rotary axes";
  if (module == "volkins") return "this configuration already loads volkins";
  if (module == "genserkins" || module == "pumakins" || module == "scorbot-kins")
    return module + " is a serial robot arm of revolute joints" + kNotASerialChain;
  if (module == "scarakins") return module + " is a SCARA arm (revolute joints in a plane)" + kNotASerialChain;
  if (module == "lineardeltakins" || module == "rotarydeltakins")
    return module + " is a delta robot (three arms driving one platform)" + kNotASerialChain;
  if (module == "tripodkins" || module == "genhexkins" || module == "pentakins")
    return module + " is a parallel machine (struts of variable length: tripod, hexapod, pentapod)" + kNotASerialChain;
  if (module == "corexykins") return module + " drives X and Y together by two belts" + kNotASerialChain;
  if (module == "rosekins") return module + " is a rose engine (a radius and an angle)" + kNotASerialChain;
  return module +
         " is not one of them: describe the machine by hand (machines/README.md) and load volkins yourself "
         "(kins/README.md)";
}

}  // namespace

const std::string* KinematicsLine::parameter(const std::string& name) const {
  for (const auto& [key, value] : parameters)
    if (key == name) return &value;
  return nullptr;
}

KinematicsLine read_kinematics_line(const LinuxcncIni& ini) {
  KinematicsLine k;
  k.entry = ini.find("KINS", "KINEMATICS");
  if (!k.entry || k.entry->value.empty())
    throw LoadError(ini.where_missing("KINS"),
                    "no [KINS]KINEMATICS: LinuxCNC 2.9 loads the kinematics module it names; init reads which "
                    "module it is");
  std::istringstream words(k.entry->value);
  words >> k.module;
  if (k.module == "trivkins")
    k.kind = StockModule::Trivkins;
  else if (k.module == "xyzbc-trt-kins")
    k.kind = StockModule::XyzbcTrt;
  else if (k.module == "xyzac-trt-kins")
    k.kind = StockModule::XyzacTrt;
  else if (k.module == "5axiskins")
    k.kind = StockModule::FiveAxis;
  else
    throw LoadError(k.entry->where(), kKnown + why_not(k.module));

  // trivkins: coordinates, kinstype; the trt modules and 5axiskins (switchkins): coordinates, sparm.
  const std::string second = k.kind == StockModule::Trivkins ? "kinstype" : "sparm";
  for (std::string word; words >> word;) {
    const std::size_t equals = word.find('=');
    const std::string name = word.substr(0, equals);
    if (equals == std::string::npos || (name != "coordinates" && name != second))
      throw LoadError(k.entry->where(), "`" + word + "` is not a parameter of " + k.module +
                                            " (it has coordinates= and " + second +
                                            "=): rtapi_app would refuse to load it");
    k.parameters.emplace_back(name, word.substr(equals + 1));
  }
  return k;
}

}  // namespace vc::init
