#include "vc/init/stock_kinematics.hpp"

#include <cctype>
#include <filesystem>
#include <optional>
#include <utility>

#include "vc/init/linuxcnc_units.hpp"
#include "vc/init/machine_layout.hpp"
#include "vc/init/number.hpp"
#include "vc/init/pin_value.hpp"
#include "vc/init/pivot_length.hpp"
#include "vc/init/pyvcp_panel.hpp"
#include "vc/init/typical_tool.hpp"

namespace vc::init {
namespace {

Vector3 unit(int k) {
  Vector3 u{};
  u[static_cast<std::size_t>(k)] = 1.0;
  return u;
}

int index_of(char letter) { return letter == 'X' || letter == 'A' ? 0 : letter == 'Y' || letter == 'B' ? 1 : 2; }

std::string joint_text(const LayoutAxis& a, const MachineLayout& layout) {
  return std::string(1, a.letter) + ": joint " + std::to_string(a.joint) + " of " + layout.coordinates_from;
}

NominalAxis axis_from(const LayoutAxis& a, const MachineLayout& layout, const std::string& what) {
  NominalAxis axis;
  axis.letter = a.letter;
  axis.rotary = a.rotary;
  axis.direction = unit(index_of(a.letter));
  axis.travel_min = a.travel_min;
  axis.travel_max = a.travel_max;
  axis.about = {joint_text(a, layout), what};
  if (a.continuous)
    axis.about.push_back(
        "without stops (a continuous rotary table): the travel is one turn, and its error tables "
        "are periodic (0 .. 360 deg, first and last rows equal)");
  axis.type_from = a.type_from;
  axis.travel_from = a.travel_from;
  return axis;
}

// X, Y, Z carry the tool: +X moves it along +x relative to the part (both modules' world).
void linear_axes(const MachineLayout& layout, const std::string& module, const std::string& world, NominalMachine& m) {
  for (char l : std::string("XYZ")) {
    NominalAxis axis = axis_from(*layout.axis(l), layout,
                                 module + world + ": the joint moves the tool along +" +
                                     std::string(1, static_cast<char>(std::tolower(l))) + " relative to the part");
    axis.direction_from = "the tool's motion relative to the part (machines/README.md section 1)";
    axis.pole_from = {"the bed frame's origin (" + module + " places X, Y, Z nowhere in particular)"};
    m.tool_chain.push_back(axis);
  }
}

void trivkins(const MachineLayout& layout, NominalMachine& m) {
  linear_axes(layout, "trivkins", " (the world is the joints)", m);
  std::string rotary;
  for (const LayoutAxis& a : layout.axes) {
    if (!a.rotary) continue;
    rotary += rotary.empty() ? std::string(1, a.letter) : std::string(" and ") + a.letter;
    NominalAxis axis = axis_from(a, layout, "a rotary axis carrying the part, bed outward in ABC order");
    axis.direction_from = "about +" + std::string(1, "xyz"[index_of(a.letter)]);
    axis.pole_from = {"A PLACEHOLDER: trivkins does not know where the rotary axes are. Give the pole (where the",
                      "axis's error table is measured, machines/README.md section 1) or measure it with",
                      "`volcomp probe-plan` and `volcomp identify sphere` (preproc/identify/README.md)."};
    m.workpiece_chain.push_back(axis);
  }
  if (!rotary.empty())
    m.remarks.push_back("trivkins does not know where " + rotary +
                        (rotary.size() > 1 ? " are: their pole_mm are placeholders; measure them"
                                           : " is: its pole_mm is a placeholder; measure it") +
                        " (volcomp identify sphere).");
  m.gauge_point_from = "trivkins knows no spindle: the tool tip is L below the Z frame's origin";
  m.fixture_from = {"trivkins: the part frame is the bed frame"};
}

// A geometry pin of the trt and tdr modules, with where its value comes from.
struct Pin {
  std::string name;
  double value = 0.0;
  std::string from;
};

// A stock module's geometry pins as LinuxCNC holds them once the HAL files ran (pin_value.hpp),
// or as a pyvcp slider on the pin's signal drives it from the start (pyvcp_panel.hpp: the
// xyzab-tdr sample's sliders; the panel is read only if a pyvcp pin is on such a signal).
class GeometryPins {
 public:
  GeometryPins(const LinuxcncIni& ini, const HalConfig& hal, const std::string& module)
      : ini_(ini), hal_(hal), module_(module), units_(read_linear_units(ini)) {}

  Pin read(const std::string& name) {
    const std::string pin = module_ + "." + name;
    const PinValue v = pin_value(hal_, pin, 0.0);
    auto at = [&](const HalCommand& c) { return cite(c.path, c.line, c.text, ini_.folder()); };
    if (const auto slider = slider_on(v.signal)) {
      const auto& [s, net] = *slider;
      sliders_.push_back(s->halpin);
      return {name, units_.to_mm(s->initial),
              value_text(name, s->initial) + "the pyvcp slider " + s->halpin + "'s start, " + s->from + " (pyvcp." +
                  s->halpin + "-f drives " + v.signal + ", " + at(*net) + ")"};
    }
    if (v.source == PinValue::Source::Live)
      throw LoadError(v.net->where(), pin + " follows " + v.driver + " at run time (both are on signal " + v.signal +
                                          ", which no sets gives a value); volkins takes the geometry from the "
                                          "machine file: set it with setp");
    Pin p{name, units_.to_mm(v.value), value_text(name, v.value)};
    if (v.source == PinValue::Source::Default)
      p.from += "not set in the HAL files read (the module's default)";
    else
      p.from += at(*v.command);
    if (v.source == PinValue::Source::Sets) p.from += " (its signal, " + at(*v.net) + ")";
    return p;
  }

  // The sliders read, for the remark that they no longer move the geometry.
  const std::vector<std::string>& sliders() const { return sliders_; }

 private:
  // "name = v: ", or "name = v inch (w mm): ": the pins are in LinuxCNC's length unit, the
  // machine file in mm.
  std::string value_text(const std::string& name, double v) const {
    return name + " = " + format_number(v) +
           (units_.inch() ? " inch (" + format_number(units_.to_mm(v)) + " mm)" : "") + ": ";
  }

  // The pyvcp slider driving `signal` and the net that puts it there, if any.
  std::optional<std::pair<const PyvcpSlider*, const HalCommand*>> slider_on(const std::string& signal) {
    if (signal.empty()) return std::nullopt;
    for (const HalCommand& c : hal_.commands) {
      const auto net = net_of(c);
      if (!net || net->signal != signal) continue;
      for (const NetPin& p : net->pins) {
        if (p.name.rfind("pyvcp.", 0) != 0) continue;
        if (!panel_) panel_ = pyvcp_sliders(ini_);
        if (const PyvcpSlider* s = slider_of_pin(*panel_, p.name)) return std::make_pair(s, &c);
      }
    }
    return std::nullopt;
  }

  const LinuxcncIni& ini_;
  const HalConfig& hal_;
  const std::string module_;
  const LinearUnits units_;
  std::optional<std::vector<PyvcpSlider>> panel_;
  std::vector<std::string> sliders_;
};

// The remark for geometry pins that pyvcp sliders set.
void slider_remark(const GeometryPins& pins, const std::string& module, NominalMachine& m) {
  if (pins.sliders().empty()) return;
  std::string names;
  for (const std::string& s : pins.sliders()) names += (names.empty() ? "" : ", ") + s;
  m.remarks.push_back("The pyvcp sliders " + names + " set " + module +
                      "'s geometry at run time; volkins takes it from this file, at the sliders' start values: "
                      "moving a slider no longer changes the kinematics (change the poles here instead).");
}

// The switchable modules (switchkins.c): sparm=identityfirst makes type 0 the identity
// (volkins: the same parameter); else type 0 is the TCP kinematics (volkins: world=tcp).
void switchkins_types(const KinematicsLine& k, NominalMachine& m) {
  const std::string* sparm = k.parameter("sparm");
  m.identity_first = sparm && sparm->find("identityfirst") != std::string::npos;
  m.world = m.identity_first ? "" : "tcp";
}

void trt(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& k, const MachineLayout& layout,
         NominalMachine& m) {
  const bool bc = k.kind == StockModule::XyzbcTrt;
  const char tilt = bc ? 'B' : 'A';
  const std::string& mod = k.module;
  linear_axes(layout, mod, " (the world is the tool tip relative to the table)", m);
  m.pins = {"x-rot-point", "y-rot-point", "z-rot-point", "x-offset", "y-offset", "z-offset", "tool-offset"};
  m.tool_offset_pin = "tool-offset";
  GeometryPins pins(ini, hal, mod);
  const Pin xr = pins.read("x-rot-point"), yr = pins.read("y-rot-point"), zr = pins.read("z-rot-point"),
            dx = pins.read("x-offset"), dy = pins.read("y-offset"), dz = pins.read("z-offset");
  slider_remark(pins, mod, m);
  const Pin& unused = bc ? dy : dx;
  m.remarks.push_back(mod + " does not use its " + unused.name + " pin (trtfuncs.c): " + unused.from + ".");

  NominalAxis t = axis_from(*layout.axis(tilt), layout, "the tilting table, carrying the rotary table C");
  t.direction_from = mod + " tilts the table about +" + std::string(1, bc ? 'y' : 'x') + " (trtfuncs.c)";
  if (bc) {
    t.pole_mm = {xr.value + dx.value, yr.value, zr.value + dz.value};
    t.pole_from = {"[x-rot-point + x-offset, y-rot-point, z-rot-point + z-offset]: B's line is the rotation point's",
                   "moved by the x and z offsets (trtfuncs.c), with"};
  } else {
    t.pole_mm = {xr.value, yr.value + dy.value, zr.value + dz.value};
    t.pole_from = {"[x-rot-point, y-rot-point + y-offset, z-rot-point + z-offset]: A's line is the rotation point's",
                   "moved by the y and z offsets (trtfuncs.c), with"};
  }
  for (const Pin* p :
       bc ? std::vector<const Pin*>{&xr, &yr, &zr, &dx, &dz} : std::vector<const Pin*>{&xr, &yr, &zr, &dy, &dz})
    t.pole_from.push_back("  " + p->from);
  m.workpiece_chain.push_back(t);

  NominalAxis c = axis_from(*layout.axis('C'), layout, "the rotary table, on the tilting table");
  c.direction_from = mod + " turns the rotary table about its +z (trtfuncs.c)";
  c.pole_mm = bc ? Vector3{-dx.value, 0.0, -dz.value} : Vector3{0.0, -dy.value, -dz.value};
  c.pole_from = {std::string(bc ? "[-x-offset, 0, -z-offset]" : "[0, -y-offset, -z-offset]") + " in " + tilt +
                 "'s frame: C's line passes through the rotation point (trtfuncs.c), with the offsets above"};
  m.workpiece_chain.push_back(c);

  m.fixture_origin_mm = {-xr.value, -yr.value, -zr.value};
  m.fixture_from = {"[-x-rot-point, -y-rot-point, -z-rot-point] in C's frame: the part frame is the bed frame at " +
                    std::string(1, tilt) + " = C = 0, as the world of " + mod +
                    " (the tool tip relative to the table)"};
  m.gauge_point_from = "the tool tip of " + mod + " is tool-offset below the spindle point, the Z frame's origin";
  m.tool_length_reference_from =
      "L = the active G43 offset (motion.tooloffset.z), exactly as the tool-offset pin of " + mod;

  switchkins_types(k, m);
}

// xyzab_tdr_kins (xyzab_tdr_kins.comp), type 1: with r = (xr, yr, zr) its rot-point pins and dz
// its z-offset, the joints (the spindle point, the tool dt = tool-offset-z long below it) of
// LinuxCNC's world w (the tool tip relative to the table, dt added to Z) are
//   j = r + Ry(-b) ((0, 0, dz) + Rx(-a) (w - dt ez - r - (0, 0, dz))) + dt ez,
// its forward the exact inverse; its x-offset cancels out of both (A's line runs along x). Bed
// outward: B about -y with its pole at r, carrying A about -x with its pole at (0, 0, dz) in B's
// frame; the part frame at [-xr, -yr, -zr - dz] in A's, the bed frame at A = B = 0. Type 0 is
// the identity, type 1 TCP: volkins' default types.
void tdr(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& k, const MachineLayout& layout,
         NominalMachine& m) {
  const std::string& mod = k.module;
  linear_axes(layout, mod, " (the world is the tool tip relative to the table)", m);
  m.pins = {"x-rot-point", "y-rot-point", "z-rot-point", "x-offset", "z-offset", "tool-offset-z"};
  m.tool_offset_pin = "tool-offset-z";
  GeometryPins pins(ini, hal, mod);
  const Pin xr = pins.read("x-rot-point"), yr = pins.read("y-rot-point"), zr = pins.read("z-rot-point"),
            dx = pins.read("x-offset"), dz = pins.read("z-offset");
  slider_remark(pins, mod, m);
  m.remarks.push_back(mod + "'s x-offset cancels out of its equations (A's line runs along x): " + dx.from + ".");

  NominalAxis b =
      axis_from(*layout.axis('B'), layout, "the rotary assembly's axis along y, carrying the rotary table A");
  b.direction = {0.0, -1.0, 0.0};
  b.direction_from = mod + " turns the table by Ry(-B) (xyzab_tdr_kins.comp): about -y";
  b.pole_mm = {xr.value, yr.value, zr.value};
  b.pole_from = {
      "[x-rot-point, y-rot-point, z-rot-point]: B's line passes through the rotation point "
      "(xyzab_tdr_kins.comp), with"};
  for (const Pin* p : {&xr, &yr, &zr}) b.pole_from.push_back("  " + p->from);
  m.workpiece_chain.push_back(b);

  NominalAxis a = axis_from(*layout.axis('A'), layout, "the rotary table, on B");
  a.direction = {-1.0, 0.0, 0.0};
  a.direction_from = mod + " turns the table by Rx(-A) (xyzab_tdr_kins.comp): about -x";
  a.pole_mm = {0.0, 0.0, dz.value};
  a.pole_from = {
      "[0, 0, z-offset] in B's frame: A's line is z-offset above the rotation point "
      "(xyzab_tdr_kins.comp), " +
      dz.from};
  m.workpiece_chain.push_back(a);

  m.fixture_origin_mm = {-xr.value, -yr.value, -zr.value - dz.value};
  m.fixture_from = {
      "[-x-rot-point, -y-rot-point, -z-rot-point - z-offset] in A's frame: the part frame is the bed "
      "frame at A = B = 0, as the world of " +
      mod + " (the tool tip relative to the table)"};
  m.gauge_point_from = "the tool tip of " + mod + " is tool-offset-z below the spindle point, the Z frame's origin";
  m.tool_length_reference_from =
      "L = the active G43 offset (motion.tooloffset.z), exactly as the tool-offset-z pin of " + mod;
  // Type 0 the identity, type 1 TCP: volkins' default (no world=, no sparm).
  m.world = "";
  m.identity_first = false;
}

// 5axiskins (5axiskins.c): the controlled point is (x, y, z + P) + (P + w) d, with d = (sin B
// cos C, sin B sin C, -cos B) (s2r(P + w, C, 180 - B)) and P = Pm + L (pivot_length.hpp: the
// mechanical pivot plus the G43 offset); LinuxCNC's world Z has L added, so the tool tip is
// (x, y, z + Pm) + (Pm + L + w) d: a head. X, Y, Z carry C about +z, its pole (the pivot, on
// B's line) at [0, 0, Pm]; C carries B about -y (at C = 0, +B swings the tool tip towards +x);
// the spindle point Pm below the pivot: gauge point [0, 0, -Pm] in B's frame; L the G43 offset;
// W the tool-axis coordinate, the tool w longer.
void five_axis(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& k, const MachineLayout& layout,
               NominalMachine& m) {
  const std::string& mod = k.module;
  linear_axes(layout, mod, " (the world is the tool tip)", m);
  m.pins = {"pivot-length"};
  const PivotLength pivot = pivot_length(ini, hal, k);
  const double pm = layout.units.to_mm(pivot.mechanical_mm);  // the sum2's numbers are in LinuxCNC's unit

  NominalAxis c = axis_from(*layout.axis('C'), layout, "the head's vertical axis, carrying B");
  c.direction_from = mod + " turns the head about +z (s2r's azimuth C, 5axiskins.c)";
  c.pole_mm = {0.0, 0.0, pm};
  c.pole_from = {"[0, 0, Pm] in Z's frame: the pivot (where B's line crosses C's) is Pm above the X, Y, Z joints'",
                 "point (5axiskins.c: z + pivot-length, pivot-length = Pm + the G43 offset), with"};
  for (const std::string& line : pivot.from) c.pole_from.push_back("  " + line);
  m.tool_chain.push_back(c);

  NominalAxis b = axis_from(*layout.axis('B'), layout, "the head's tilting axis, on C, carrying the spindle");
  b.direction = {0.0, -1.0, 0.0};
  b.direction_from = mod + " tilts the tool from -z by B, towards +x at C = 0 (s2r's polar angle 180 - B): about -y";
  b.pole_from = {"the pivot, C's frame's origin"};
  m.tool_chain.push_back(b);

  m.gauge_point_mm = {0.0, 0.0, -pm};
  m.gauge_point_from =
      "[0, 0, -Pm]: the spindle point is Pm below the pivot along the tool (5axiskins.c: s2r(pivot-length "
      "+ w, C, 180 - B)); Pm " +
      format_number(pm) + ", C's pole below";
  m.tool_length_reference_from =
      "L = the active G43 offset (motion.tooloffset.z), which 5axiskins' pivot-length adds "
      "through " +
      pivot.sum2;
  m.tool_axis_coordinate = layout.tool_axis;
  m.tool_axis_from =
      "joint " + std::to_string(layout.tool_axis_joint) + " of " + layout.coordinates_from +
      ": 5axiskins' W moves the tool along its own axis by the X, Y, Z joints (s2r(pivot-length + w, ...))";
  m.fixture_from = {mod + ": the part frame is the bed frame"};
  m.remarks.push_back(mod + ".pivot-length follows " + pivot.sum2 + ".out, the mechanical pivot length " +
                      format_number(pm) +
                      " plus the tool offset: the pivot is C's pole and the gauge point below. The patch takes " + mod +
                      ".pivot-length off its net; " + pivot.sum2 + " stays, driving nothing.");
  switchkins_types(k, m);
}

}  // namespace

NominalMachine nominal_machine(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& k) {
  const MachineLayout layout = read_layout(ini, k);
  NominalMachine m;
  m.module = k.module;
  m.coordinates = layout.coordinates;
  m.units = layout.units;
  if (m.units.inch())
    m.remarks.push_back("LinuxCNC runs in inches (" + m.units.from +
                        "): this file is in mm, as it declares (every length converted, x 25.4); volkins is loaded "
                        "with units=inch and converts the joints, the world and the tool length offset it gets.");
  if (const IniEntry* name = ini.find("EMC", "MACHINE"); name && !name->value.empty()) {
    m.name = name->value;
    m.name_from = "[EMC] " + ini.cite(*name);
  } else {
    m.name = std::filesystem::path(ini.path()).stem().string();
    m.name_from = "the INI file's name: it has no [EMC]MACHINE";
  }
  const TypicalTool tool = longest_tool(ini, layout.units);
  m.tool_length_mm = tool.length_mm;
  m.tool_length_from = tool.from;
  if (tool.unreadable) m.remarks.push_back("tool_length_mm is 0: " + tool.from);
  m.tool_length_reference_from = "L = the active G43 offset (motion.tooloffset.z): the tool table holds gauge lengths";
  if (k.kind == StockModule::Trivkins)
    trivkins(layout, m);
  else if (k.kind == StockModule::FiveAxis)
    five_axis(ini, hal, k, layout, m);
  else if (k.kind == StockModule::XyzabTdr)
    tdr(ini, hal, k, layout, m);
  else
    trt(ini, hal, k, layout, m);
  return m;
}

}  // namespace vc::init
