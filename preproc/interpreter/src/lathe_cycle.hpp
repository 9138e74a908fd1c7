// A lathe cycle while its profile is read (lathe_cycles.cpp); private to preproc/interpreter/src.
#pragma once

#include <vector>

#include "lathe_passes.hpp"
#include "vc/interpreter/interpreter.hpp"

namespace vc::interpreter {

struct Interpreter::LatheCycle {
  int code = 0;  // 700, 710, 711, 712, 720, 721, 722
  int line = 0;
  int offset = 0;                                            // of the cycle's G word
  lathe::Point from;                                         // the block's Z X (program units): where the rapid went
  lathe::Point at;                                           // the profile's current point
  double d = 0, e = 0, i = 1, p = 1, r = 0.5, u = 0, w = 0;  // LinuxCNC's defaults
  Position start;                                            // position_ before the profile moved it (for #<_x>)
  std::vector<lathe::Segment> profile;
};

}  // namespace vc::interpreter
