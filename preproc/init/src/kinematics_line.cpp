#include "vc/init/kinematics_line.hpp"

#include <cctype>
#include <sstream>

namespace vc::init {
namespace {

constexpr const char* kKnown = "init knows trivkins, xyzbc-trt-kins, xyzac-trt-kins, xyzab_tdr_kins and 5axiskins; ";
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
  if (module == "millturn")
    return "millturn is refused: its kinematics type 1 (turning, millturn.comp) turns the world against the joints (x = "
           "the Z joint, y = minus the Y joint, z = the X joint) and passes A through as the work spindle: a world "
           "that is neither the joints (volkins' identity) nor the tool tip in the part frame, which A turns "
           "(volkins' TCP). Its type 0 alone is trivkins': a configuration that never switches (no M428/M429) can "
           "load trivkins coordinates=xyza and then run volcomp init";
  return module +
         " is not one of them: describe the machine by hand (machines/README.md) and load volkins yourself "
         "(kins/README.md)";
}

}  // namespace

char trivkins_type(const std::string* kinstype) {
  const char first = kinstype && !kinstype->empty()
                         ? static_cast<char>(std::tolower(static_cast<unsigned char>((*kinstype)[0])))
                         : '1';
  return first == 'b' || first == 'f' || first == 'i' ? first : '1';
}

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
  else if (k.module == "xyzab_tdr_kins")
    k.kind = StockModule::XyzabTdr;
  else
    throw LoadError(k.entry->where(), kKnown + why_not(k.module));

  // trivkins: coordinates, kinstype; the trt modules and 5axiskins (switchkins): coordinates, sparm.
  // xyzab_tdr_kins (a halcompile comp) maps joints 0-4 to X Y Z A B and has no parameter of
  // its own: only halcompile's count= and names=, which make instances of its unused dummy pin.
  if (k.kind == StockModule::XyzabTdr) {
    for (std::string word; words >> word;)
      throw LoadError(k.entry->where(), "`" + word +
                                            "`: xyzab_tdr_kins has no parameter of its own (its joints are "
                                            "X Y Z A B, fixed; halcompile's count= and names= only make instances of "
                                            "its unused dummy pin): write the module alone for init to take it");
    return k;
  }
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
