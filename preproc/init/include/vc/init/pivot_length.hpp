// 5axiskins' mechanical pivot length, as a LinuxCNC configuration sets it.
//
// 5axiskins (5axiskins.c) places its controlled point at (x, y, z + P) + (P + w) d, d the tool
// direction and P its pin pivot-length (default 250). LinuxCNC's G43 adds the tool length
// offset L to world Z only, so for the world to be the tool tip however the head tilts, P must
// be the mechanical pivot length Pm plus L (5axiskins.c's note 1; the bridgemill sample: a sum2
// of 5axisgui's pivot_len and motion.tooloffset.z). init follows exactly that chain:
// pivot-length netted to a sum2's out (`loadrt sum2 names=a,b` or `count=N`: sum2.0 ...), one
// input on the signal motion.tooloffset.z drives, with gain exactly 1, the other a constant: set
// by setp or sets (pin_value.hpp), or a signal driven by 5axisgui's pin pivot_len (the
// `pivot_len=V` of its `loadusr` line, else 250, 5axisgui's default). Pm = gain x constant +
// sum2's offset.
//
// Anything else (an unconnected or constant pivot-length, another driver, another gain, a
// second live input) is refused with its file and line: with a pivot length that does not
// follow motion.tooloffset.z, G43 moves world Z only, which volkins' TCP world does not express.
#pragma once

#include <string>
#include <vector>

#include "vc/init/hal_file.hpp"
#include "vc/init/kinematics_line.hpp"

namespace vc::init {

struct PivotLength {
  double mechanical_mm = 0.0;     // Pm
  std::string sum2;               // the sum2 instance whose out pivot-length follows
  std::vector<std::string> from;  // where Pm comes from, step by step (for the machine file)
};

// Throws vc::LoadError (file:line) for a pivot length init cannot follow (above).
PivotLength pivot_length(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& kinematics);

}  // namespace vc::init
