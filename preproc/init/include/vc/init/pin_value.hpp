// What an input pin of the stock kinematics module holds once LinuxCNC has run the
// configuration's HAL commands (hal_file.hpp gives them in LinuxCNC's order).
//
// A `setp` on the pin, or a `sets` on the signal it is netted to, gives it a value; when both
// happen, or one twice, the last one in LinuxCNC's order wins. A signal that no `sets` gives a
// value and that carries another pin not marked as a reader (`=> PIN`) may be driven by that
// pin: the value is then live (it follows that pin at run time), as the tool-offset pin that
// follows motion.tooloffset.z. Not set anywhere: the module's default.
#pragma once

#include <string>

#include "vc/init/hal_file.hpp"

namespace vc::init {

struct PinValue {
  enum class Source { Default, Setp, Sets, Live };
  Source source = Source::Default;
  double value = 0.0;
  const HalCommand* command = nullptr;  // Setp, Sets: the command that gave the value
  const HalCommand* net = nullptr;      // the net that puts the pin on its signal, or nullptr
  std::string signal;                   // that signal, or ""
  std::string driver;                   // Live: the pin that may drive the signal
};

// Throws vc::LoadError at a setp or sets whose value is not a number.
PinValue pin_value(const HalConfig& hal, const std::string& pin, double default_value);

}  // namespace vc::init
