// What a stock LinuxCNC kinematics module means as a nominal machine in the project's model
// (machines/README.md section 1), exactly, so that volkins with that machine file and zero
// errors moves the joints as the stock module did:
// - trivkins: the world is the joints. X, Y, Z in the tool chain (directions +x, +y, +z);
//   A, B, C (at most two) in the workpiece chain about +x, +y, +z, bed outward. trivkins
//   does not know where a rotary axis is: its pole is a placeholder, said so in the file.
// - xyzbc-trt-kins, xyzac-trt-kins (LinuxCNC's trtfuncs.c): the world is the tool tip in a
//   frame attached to the table (TCP). With xr, yr, zr its x/y/z-rot-point pins and dx, dy, dz
//   its x/y/z-offset pins: tool chain X, Y, Z (+x, +y, +z, poles 0, gauge point 0,
//   tool_length_reference_mm 0: L is the G43 offset, as its tool-offset pin); workpiece chain
//   B about +y with its pole at [xr + dx, yr, zr + dz] carrying C about +z with its pole at
//   [-dx, 0, -dz] (xyzbc), or A about +x at [xr, yr + dy, zr + dz] carrying C at [0, -dy, -dz]
//   (xyzac); fixture origin [-xr, -yr, -zr]. In volkins' TCP world, LinuxCNC's Z is the tool
//   tip's plus the tool length offset, as the stock module's (tests/unit/init checks both
//   directions against trtfuncs.c's equations).
// - xyzab_tdr_kins (xyzab_tdr_kins.comp, a dual rotary table): type 0 the identity, type 1 the
//   tool tip relative to the table (TCP), volkins' default types. With xr, yr, zr its
//   x/y/z-rot-point pins and dz its z-offset (its x-offset cancels out): tool chain X, Y, Z as
//   the trt modules'; workpiece chain B about -y with its pole at [xr, yr, zr], carrying A
//   about -x with its pole at [0, 0, dz]; fixture origin [-xr, -yr, -zr - dz]; L the G43
//   offset, as its tool-offset-z pin. A pin on a signal that a pyvcp slider drives (the
//   sample's) takes the slider's start value (pyvcp_panel.hpp), a remark says so.
// - 5axiskins (5axiskins.c, a bridge mill: head B on C): the world is the tool tip (TCP), its
//   pivot-length Pm plus the tool length offset (pivot_length.hpp). Tool chain X, Y, Z, then C
//   about +z with its pole (the pivot) at [0, 0, Pm], carrying B about -y at [0, 0, 0]; gauge
//   point [0, 0, -Pm], tool_length_reference_mm 0, W the tool_axis_coordinate (the nominal TCP
//   tool is L + w long); no workpiece chain (tests/unit/init checks it against 5axiskins.c's
//   equations, W and the offset included).
#pragma once

#include "vc/init/hal_file.hpp"
#include "vc/init/kinematics_line.hpp"
#include "vc/init/nominal_machine.hpp"

namespace vc::init {

// Throws vc::LoadError (file:line) with what the model cannot take or the INI does not say.
NominalMachine nominal_machine(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& kinematics);

}  // namespace vc::init
