// Modal state that moves the program's frame and keeps the machine still: tool length
// offsets (G43, G43.1, G49), work coordinate systems (G54..G59.3), G10 L2/L20, G92/G52, and
// G28/G30 (rapids to positions stored in the parameters).
#include "words.hpp"

namespace vc::interpreter {

void Interpreter::set_tool_length(const Words& w, int line) {
  const Position world = world_position();
  const auto* g = w.find_g({G_43, G_43_1, G_49});
  if (g->code == G_49) {
    tool_offset_ = 0.0;
    tool_offset_from_ = ToolOffsetFrom::None;
  } else if (g->code == G_43_1) {
    if (!w.has('Z')) refuse(line, g->offset, "G43.1 needs a Z word (tool length)");
    tool_offset_ = w.get('Z') * (inches_ ? kInch : 1.0);
    tool_offset_from_ = ToolOffsetFrom::G43_1;
  } else {
    int tool = tool_in_spindle_;
    if (w.has('H')) tool = w.whole('H');
    if (w.has('H') && tool < 0)
      refuse(line, w['H'].offset, "H must be a whole number >= 0");
    else if (tool < 0)
      refuse(line, g->offset, "G43 without H and no tool in the spindle yet (use G43 Hn, or M6 Tn first)");
    if (tool == 0 && !(tools_ && tools_->count(0))) {
      tool_offset_ = 0.0;  // tool 0: no tool, LinuxCNC's empty spindle with zero offsets
    } else {
      if (!tools_) refuse(line, g->offset, "G43 needs the tool table: pass --tool-table FILE (LinuxCNC's .tbl)");
      const auto it = tools_->find(tool);
      if (it == tools_->end())
        refuse(line, w.has('H') ? w['H'].offset : g->offset,
               "tool " + std::to_string(tool) + " is not in the tool table");
      if (const char other = it->second.other_offset())
        refuse(line, w.has('H') ? w['H'].offset : g->offset,
               "tool " + std::to_string(tool) + " has an offset in " + other +
                   " in the tool table, which LinuxCNC's G43 applies too: the pre-distorter takes the Z "
                   "(length) offset only (not translated yet)");
      tool_offset_ = it->second.z_offset();
    }
    tool_offset_from_ = ToolOffsetFrom::G43;
    tool_offset_tool_ = tool;
  }
  set_world_position(world);  // LinuxCNC keeps the machine still; the program position changes
}

void Interpreter::set_coordinate_system(int index) {
  const Position world = world_position();
  coordinate_system_ = index;
  set_world_position(world);
}

void Interpreter::set_offsets(const Words& w, int line) {
  const auto* g10 = w.find_g({G_10});
  if (!w.has('L')) refuse(line, g10->offset, "G10 needs an L word");
  const int l = w.whole('L');
  if (l == 1 || l == 10 || l == 11) return set_tool_entry(w, l, line);
  if (l != 2 && l != 20)
    refuse(line, w['L'].offset, "G10 L" + std::to_string(l) + " is not supported (G10 L1, L2, L10, L11 and L20 are)");
  if (!w.has('P')) refuse(line, g10->offset, "G10 L" + std::to_string(l) + " needs a P word (1..9, or 0)");
  int system = w.whole('P');
  if (system < 0 || system > 9) refuse(line, w['P'].offset, "G10 P must be 0..9");
  if (system == 0) system = coordinate_system_;
  const Position world = world_position();
  const double scale = inches_ ? kInch : 1.0;
  if (w.has('R')) {
    if (l != 2) refuse(line, w['R'].offset, "R (rotation) only with G10 L2");
    parameters_[rotation_parameter(system)] = w.get('R');
  }
  // L20 (convert_setup): the current position, in that system's coordinates, becomes the
  // values given; X and Y are set in the system's rotated frame.
  const Position current = frame_for(system).program(world);
  Position wanted = current;
  for (int i = 0; i < kAxes; ++i) {
    const char letter = kAxisLetters[i];
    if (!w.has(letter)) continue;
    const double value = w.get(letter) * (is_linear(i) ? scale : 1.0);
    if (l == 2) {
      parameters_[offset_parameter(system, i)] = value / machine_unit(i);
      continue;
    }
    if (!(known_ >> i & 1u))
      refuse(line, w[letter].offset, std::string("G10 L20: the current ") + letter + " is not known yet");
    wanted[i] = value;
  }
  if (l == 20) {
    const Frame rotation{{}, parameters_[rotation_parameter(system)]};
    const Position now = rotation.world(current), then = rotation.world(wanted);
    for (int i = 0; i < kAxes; ++i)
      if (w.has(kAxisLetters[i]) || (i < 2 && (w.has('X') || w.has('Y'))))
        parameters_[offset_parameter(system, i)] += (now[i] - then[i]) / machine_unit(i);
  }
  offsets_set_ |= 1u << system;
  if (system == coordinate_system_) set_world_position(world);
}

void Interpreter::set_tool_entry(const Words& w, int l, int line) {
  // G10 L1 / L10 / L11 P<tool> (LinuxCNC's convert_setup_tool) changes the interpreter's copy of
  // the tool table, for later G43s and #5401..: L1 sets the offsets given; L10 sets them so that
  // the current point, in the active coordinate system without the tool length offset, has the
  // coordinates given; L11 the same in G59.3 without G92 (a touch-off fixture). R: radius, I J:
  // a lathe tool's angles, Q: its orientation. X Y A B C offsets are kept, and a G43 with them
  // is refused (set_tool_length).
  const auto* g10 = w.find_g({G_10});
  const std::string name = "G10 L" + std::to_string(l);
  if (!w.has('P')) refuse(line, g10->offset, name + " needs a P word (the tool number)");
  const int number = w.whole('P');
  if (!tools_) refuse(line, g10->offset, name + " changes the tool table: pass --tool-table FILE (LinuxCNC's .tbl)");
  const auto it = tools_->find(number);
  if (number < 0 || it == tools_->end())
    refuse(line, w['P'].offset, "tool " + std::to_string(number) + " is not in the tool table");
  bool any = false;
  for (char c : {'X', 'Y', 'Z', 'A', 'B', 'C', 'R', 'I', 'J', 'Q'}) any |= w.has(c);
  if (!any) refuse(line, g10->offset, name + " without offsets has no effect");  // LinuxCNC's words
  Tool& tool = it->second;
  const double scale = inches_ ? kInch : 1.0;
  const auto given = [&](int axis) { return w.get(kAxisLetters[axis]) * (is_linear(axis) ? scale : 1.0); };
  if (l == 1) {
    for (int i = 0; i < kAxes; ++i)
      if (w.has(kAxisLetters[i])) tool.offset[static_cast<std::size_t>(i)] = given(i);
  } else {
    if (compensation_.offsets()) refuse(line, g10->offset, name + " with cutter compensation on is not translated");
    for (int i = 0; i < kAxes; ++i)
      if (w.has(kAxisLetters[i]) && !(known_ >> i & 1u))
        refuse(line, w[kAxisLetters[i]].offset,
               name + std::string(": the current ") + kAxisLetters[i] + " is not known yet");
    // LinuxCNC's find_current_in_system_without_tlo: where the controlled point is, with the
    // tool length offset, in the destination system's coordinates without it.
    const int system = l == 11 ? 9 : coordinate_system_;
    Position world = world_position();
    if (!setup_.tool_length_in_world) world[2] += tool_offset_;
    const Frame destination = frame_for(system, /*with_g92=*/l != 11, /*with_tool_length=*/false);
    Position t = destination.program(world);
    const Frame rotation{{}, destination.rotation_deg};
    const auto rotated = [&](double x, double y) { return rotation.world({x, y, 0, 0, 0, 0}); };
    if (w.has('X') || w.has('Y')) {
      // X alone keeps the offset's component along the system's (rotated) Y, and Y alone X's.
      const Position kept = rotation.program({tool.offset[0], tool.offset[1], 0, 0, 0, 0});
      const double x = w.has('X') ? t[0] - given(0) : kept[0], y = w.has('Y') ? t[1] - given(1) : kept[1];
      const Position offset = rotated(x, y);
      tool.offset[0] = offset[0];
      tool.offset[1] = offset[1];
    }
    for (int i = 2; i < kAxes; ++i)
      if (w.has(kAxisLetters[i])) tool.offset[static_cast<std::size_t>(i)] = t[i] - given(i);
  }
  if (w.has('R')) tool.diameter = 2 * w.get('R') * scale;
  if (w.has('I')) tool.front_angle = w.get('I');
  if (w.has('J')) tool.back_angle = w.get('J');
  if (w.has('Q')) {
    const double q = w.get('Q');
    if (q != std::floor(q) || q < 0 || q > 9) refuse(line, w['Q'].offset, "invalid tool orientation (Q 0..9)");
    tool.orientation = static_cast<int>(q);
  }
}

void Interpreter::set_axis_offsets(const Words& w, int code, int line) {
  // LinuxCNC's convert_axis_offsets (interp_convert.cc): the machine stays where it is. G92:
  // the current point gets the given coordinates; G52: the offset is the given values; G92.1
  // and G92.2 take the offsets off (G92.1 also zeroes #5211..), G92.3 puts #5211.. back on.
  const Position world = world_position();
  const std::array<double, 2> xy = program_xy();
  const double scale = inches_ ? kInch : 1.0;
  if (code == G_92 || code == G_52) {
    bool any = false;
    for (int i = 0; i < kAxes; ++i) {
      const char letter = kAxisLetters[i];
      if (!w.has(letter)) continue;
      any = true;
      if (!(setup_.machine_axes >> i & 1u))
        refuse(line, w[letter].offset, std::string("this machine has no ") + letter + " axis");
      if (code == G_92 && !(known_ >> i & 1u))
        refuse(line, w[letter].offset, std::string("G92: the current ") + letter + " is not known yet");
      const double value = w.get(letter) * (is_linear(i) ? scale : 1.0);
      g92_[i] = code == G_92 ? position_[i] + g92_[i] - value : value;
    }
    if (!any) refuse(line, w.find_g({code})->offset, g_name(code) + " needs at least one axis word");
    parameters_[kG92Applied] = 1.0;
    for (int i = 0; i < kAxes; ++i) parameters_[kG92 + i] = g92_[i] / machine_unit(i);
  } else if (code == G_92_1 || code == G_92_2) {
    g92_ = {};
    parameters_[kG92Applied] = 0.0;
    if (code == G_92_1)
      for (int i = 0; i < kAxes; ++i) parameters_[kG92 + i] = 0.0;
  } else {  // G92.3
    parameters_[kG92Applied] = 1.0;
    for (int i = 0; i < kAxes; ++i) g92_[i] = parameters_[kG92 + i] * machine_unit(i);
  }
  set_world_position(world);
  if (code == G_92)  // LinuxCNC's current X Y are then the words as written
    note_program_xy(w.has('X') ? w.get('X') : xy[0], w.has('Y') ? w.get('Y') : xy[1]);
}

void Interpreter::go_home(const Words& w, int code, int line, Effect& effect) {
  // G28/G30: rapid to the intermediate point (axis words), then to the stored home
  // (machine coordinates) on those axes, or on all axes if none is given. The pre-distorter
  // writes these lines as they are: rapids away from the part, to a position stored in the
  // controller.
  const int base = code == G_28 ? kG28Home : kG30Home;
  if (!setup_.var_file && !(offsets_set_ & 1u))
    refuse(line, w.find_g({code})->offset,
           g_name(code) + " goes to a position stored in the parameter file: pass --var FILE");
  unsigned named = 0;
  for (int i = 0; i < kAxes; ++i)
    if (w.has(kAxisLetters[i])) named |= 1u << i;
  if (named) {
    const Position intermediate = end_point(w, line);
    position_ = intermediate;
    known_ |= named;
  } else {
    named = setup_.machine_axes;
  }
  Position world = world_position();
  for (int i = 0; i < kAxes; ++i)
    if (named >> i & 1u) world[i] = parameters_[base + i] * machine_unit(i);
  set_world_position(world);
  known_ |= named;
  effect.moved_as_written = true;
}

}  // namespace vc::interpreter
