// [KINS]KINEMATICS: the kinematics module LinuxCNC loads (`loadrt [KINS]KINEMATICS`) and its
// `name=value` parameters, for the modules init knows; every other module is refused with the
// reason the model cannot express it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "vc/init/linuxcnc_ini.hpp"

namespace vc::init {

enum class StockModule {
  Trivkins,
  XyzbcTrt,
  XyzacTrt,
  XyzabTdr,
  FiveAxis
};  // XyzabTdr: xyzab_tdr_kins; FiveAxis: 5axiskins

struct KinematicsLine {
  const IniEntry* entry = nullptr;
  std::string module;  // as written, e.g. "xyzbc-trt-kins"
  StockModule kind = StockModule::Trivkins;
  std::vector<std::pair<std::string, std::string>> parameters;  // in order

  // The parameter's value, or nullptr.
  const std::string* parameter(const std::string& name) const;
};

// trivkins' kinematics type of a kinstype= value (trivkins.c: by its first letter, any case):
// 'b' KINEMATICS_BOTH, 'f' FORWARD_ONLY, 'i' INVERSE_ONLY, '1' the identity (any other, or none).
char trivkins_type(const std::string* kinstype);

// Throws vc::LoadError (file:line): no [KINS]KINEMATICS, a module init does not know (with the
// reason), a parameter the module does not have (rtapi_app would refuse to load it).
KinematicsLine read_kinematics_line(const LinuxcncIni& ini);

}  // namespace vc::init
