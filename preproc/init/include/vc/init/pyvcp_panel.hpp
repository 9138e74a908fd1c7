// The sliders of the panel that [DISPLAY]PYVCP names (a pyvcp XML file, shown by AXIS as the
// HAL component `pyvcp`), as LinuxCNC 2.9's pyvcp_widgets.py makes them: a <scale> with
// <halpin>"NAME"</halpin> has the out pins pyvcp.NAME-f and pyvcp.NAME-i, which drive their
// signals with the slider's value from the moment the panel starts (a `sets` on the signal
// before is overwritten): <initval>, pyvcp's default 0, held within <min_> .. <max_> (defaults
// 0 and 10). The xyzab-tdr sample sets its geometry pins so.
#pragma once

#include <string>
#include <vector>

#include "vc/init/linuxcnc_ini.hpp"

namespace vc::init {

struct PyvcpSlider {
  std::string halpin;  // NAME: its pins are pyvcp.NAME-f and pyvcp.NAME-i
  double initial = 0.0;
  std::string from;  // where the initial value is written ("panel.xml:253 `<initval>-20</initval>`")
  SourceLocation where;
};

// The panel's sliders with a <halpin>, in the file's order; none if the INI names no panel.
// Throws vc::LoadError (file:line) for a panel that cannot be read and for a slider whose
// initial value init cannot take as pyvcp does: not a number, or a <param_pin> (its value is
// then set from outside the panel).
std::vector<PyvcpSlider> pyvcp_sliders(const LinuxcncIni& ini);

// The slider whose float out pin `pin` is ("pyvcp.NAME-f"), or nullptr. (Its -i pin is an s32:
// halcmd nets no float pin, as the stock modules' geometry pins are, to its signal.)
const PyvcpSlider* slider_of_pin(const std::vector<PyvcpSlider>& sliders, const std::string& pin);

}  // namespace vc::init
