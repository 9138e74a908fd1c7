// The blocks' meaning in LinuxCNC's order of execution, and the moves they make.
#include "vc/interpreter/interpreter.hpp"

#include <algorithm>
#include <cmath>

#include "lathe_cycle.hpp"
#include "words.hpp"
#include "vc/gcode/evaluate.hpp"
#include "vc/gcode/parser.hpp"
#include "vc/interpreter/line_text.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::interpreter {

void Effect::clear() {
  moves.clear();
  translate = false;
  motion_words.clear();
  stop_words.clear();
  g64_word = g64_p_word = g64_q_word = f_word = motion_code_word = -1;
  moved_as_written = false;
  profile_subroutine.clear();
  after_tool_change_words.clear();
  dropped_words.clear();
  after_moves.clear();
  exact_path = false;
  modal_motion = G_80;
  inches = incremental = arc_absolute = program_end = false;
}

Interpreter::Interpreter(Setup setup) : setup_(std::move(setup)) {
  if (setup_.tools) tools_ = *setup_.tools;
  if (setup_.var_file) {
    parameters_ = *setup_.var_file;
    const double system = parameters_[kCoordinateSystem];
    if (system >= 1 && system <= 9) coordinate_system_ = static_cast<int>(system);
    offsets_known_ = true;
    // LinuxCNC restores the G92 offsets at start if they were on (rs274ngc_pre.cc, init).
    if (parameters_[kG92Applied] != 0.0)
      for (int i = 0; i < kAxes; ++i) g92_[i] = parameters_[kG92 + i] * machine_unit(i);
  }
  parameters_.set_state(&state_view_);
  if (setup_.start_world) {
    set_world_position(*setup_.start_world);
    known_ = kAllAxes;
  }
}

Interpreter::~Interpreter() = default;

void Interpreter::refuse(int line, int offset, const std::string& message) const {
  throw LoadError({setup_.file, line, offset + 1}, message);
}

void Interpreter::read(std::string& raw, int line, gcode::Block& block, Effect& effect) {
  if (!raw.empty() && raw.back() == '\r') raw.pop_back();  // DOS line ends
  try {
    pin_line_number(raw, line, parameters_);
    gcode::parse_block(raw, block);
  } catch (const gcode::SyntaxError& e) {
    throw LoadError({setup_.file, line, e.offset + 1}, e.what());
  }
  execute(block, line, effect);
}

Frame Interpreter::frame() const { return frame_for(coordinate_system_); }

Frame Interpreter::frame_for(int system, bool with_g92, bool with_tool_length) const {
  Frame f;
  for (int i = 0; i < kAxes; ++i) f.offset[i] = parameters_[offset_parameter(system, i)] * machine_unit(i);
  f.rotation_deg = parameters_[rotation_parameter(system)];
  // G92/G52 offsets are added to program coordinates before the rotation (LinuxCNC's canon:
  // world = rotate(program + G92) + G5x + tool length).
  if (with_g92) {
    const Position g92 = Frame{{}, f.rotation_deg}.world(g92_);
    for (int i = 0; i < kAxes; ++i) f.offset[i] += g92[i];
  }
  if (with_tool_length && setup_.tool_length_in_world) f.offset[2] += tool_offset_;
  return f;
}

Position Interpreter::world_position() const { return frame().world(position_); }

void Interpreter::set_world_position(const Position& world) { position_ = frame().program(world); }

Interpreter::Words Interpreter::evaluate(const gcode::Block& block, int line) const {
  Words w;
  for (int i = 0; i < static_cast<int>(block.words.size()); ++i) {
    const gcode::Word& word = block.words[static_cast<std::size_t>(i)];
    double value = 0.0;
    try {
      value = gcode::evaluate(word.value, parameters_, word.begin);
    } catch (const gcode::SyntaxError& e) {  // division by zero, unknown parameter, ...
      refuse(line, e.offset, e.what());
    }
    if (word.letter == 'G' || word.letter == 'M') {
      const double tenths = value * 10.0;
      const double rounded = std::round(tenths);
      if (std::abs(tenths - rounded) > 1e-6 || rounded < 0 || rounded > 10000)
        refuse(line, word.begin, std::string("unknown ") + word.letter + " code");
      (word.letter == 'G' ? w.g : w.m).push_back({static_cast<int>(rounded), i, word.begin});
      continue;
    }
    Words::Value& v = w.letters[Words::slot(word.letter)];
    if (v.has) refuse(line, word.begin, std::string("word ") + word.letter + " appears twice on the line");
    v = {true, value, i, word.begin};
  }
  return w;
}

void Interpreter::assign(const gcode::Block& block, int line) {
  try {
    gcode::apply_assignments(block, parameters_);
  } catch (const gcode::SyntaxError& e) {
    refuse(line, e.offset, e.what());
  }
}

void Interpreter::execute(const gcode::Block& block, int line, Effect& effect) {
  effect.clear();
  ++sequence_;
  released_.clear();
  if (block.percent) return;
  if (block.o_word >= 0)
    refuse(line, block.o_word,
           "O-word control flow (subroutines, loops, conditions) is not translated: expand it in the "
           "post-processor");

  const Words w = evaluate(block, line);  // before this line's assignments take effect
  assign(block, line);
  effect.f_word = w['F'].index;

  // Codes this tool refuses, with the reason.
  for (const Words::Code& c : w.g) {
    const int g = c.code;
    const char* reason = nullptr;
    if (g == G_76)
      reason = "G76 is spindle-synchronised threading: it cannot be pre-distorted honestly";
    else if (g == G_87)
      reason =
          "the back boring cycle G87 is not translated (the other canned cycles are): expand it into G0/G1 "
          "moves in the post-processor";
    else if (g == G_33 || g == G_33_1)
      reason =
          "spindle-synchronised motion (threading, rigid tapping) cannot be pre-distorted honestly: the pieces "
          "of a corrected move would each wait for the spindle";
    else if (g >= G_38_2 && g <= G_38_5)
      reason =
          "probing: where the probe stops is known only when the program runs, so the moves after it cannot be "
          "corrected offline";
    else if (g == G_7)
      reason = "lathe diameter mode (G7) is not translated: program radii (G8)";
    else if (g == G_43_2 || g == G_17_1 || g == G_18_1 || g == G_19_1)
      reason = "not supported by the pre-distorter (G43.2, G17.1-G19.1)";
    if (reason) refuse(line, c.offset, g_name(g) + ": " + reason);
    static constexpr int kKnown[] = {
        G_0,    G_1,    G_2,    G_3,    G_4,    G_10,   G_17,  G_18,  G_19,   G_20, G_21, G_28,   G_28_1,
        G_30,   G_30_1, G_40,   G_43,   G_43_1, G_49,   G_53,  G_54,  G_55,   G_56, G_57, G_58,   G_59,
        G_59_1, G_59_2, G_59_3, G_61,   G_61_1, G_64,   G_80,  G_90,  G_90_1, G_91, G_41, G_41_1, G_42,
        G_42_1, G_91_1, G_92,   G_92_1, G_92_2, G_92_3, G_52,  G_93,  G_94,   G_95, G_96, G_97,   G_98,
        G_99,   G_73,   G_74,   G_81,   G_82,   G_83,   G_84,  G_85,  G_86,   G_88, G_89, G_70,   G_71,
        G_71_1, G_71_2, G_72,   G_72_1, G_72_2, G_5,    G_5_1, G_5_2, G_5_3,  // splines and NURBS (splines.cpp)
        G_8};  // G8: lathe radius mode, LinuxCNC's default (G7 is refused)
    if (std::find(std::begin(kKnown), std::end(kKnown), g) == std::end(kKnown))
      refuse(line, c.offset, "unknown G code " + g_name(g));
  }
  for (const Words::Code& c : w.m) {
    const int m = c.code / 10;
    if (c.code % 10 != 0) refuse(line, c.offset, "unknown M code");
    if (m == 98 || m == 99)
      refuse(line, c.offset, "M98/M99 subprograms are not translated: expand them in the post-processor");
    const bool known = m <= 9 || m == 19 || m == 30 || (m >= 70 && m <= 73) || (m >= 48 && m <= 53) ||
                       (m >= 60 && m <= 68) || (m >= 100 && m <= 199);
    if (!known) refuse(line, c.offset, "unknown M code M" + std::to_string(m));
  }
  if (w.has('E') && !w.find_g({G_70})) refuse(line, w['E'].offset, "E word without G70 or G76");
  for (char c : {'U', 'V', 'W'})
    if (w.has(c))
      refuse(line, w[c].offset, std::string("the ") + c + " axis is not supported (machines have X Y Z A B C)");
  if (block.block_delete) {
    // Whether LinuxCNC runs this line depends on the block-delete switch: the path after it
    // would be unknown if the line moved or changed the modal state.
    for (char c : {'X', 'Y', 'Z', 'A', 'B', 'C', 'I', 'J', 'K', 'R', '@', '^'})
      if (w.has(c)) refuse(line, 0, "a block-delete ('/') line may not move the machine");
    if (!w.g.empty()) refuse(line, 0, "a block-delete ('/') line may not change G modes");
  }

  compensation_rules(block, w, line);
  spline_rules(w, line);
  state_codes(w, line, effect);

  // LinuxCNC's order of execution (RS274/NGC 3.8, LinuxCNC docs "Order of Execution").
  if (w.find_g({G_93})) inverse_time_ = true;
  if (w.find_g({G_94, G_95})) inverse_time_ = false;
  if (w.find_g({G_95})) refuse(line, w.find_g({G_95})->offset, "G95 (feed per revolution) is not supported");
  if (w.has('F')) feed_ = w.get('F');
  if (w.has('S')) spindle_rpm_ = w.get('S');
  if (w.has('T')) {
    selected_tool_ = w.whole('T');
    if (selected_tool_ < 0) refuse(line, w['T'].offset, "T must be a whole number >= 0");
  }
  if (w.find_m({M_6})) {
    tool_in_spindle_ = selected_tool_;
    tool_data_known_ = true;
  }
  if (const auto* m61 = w.find_m({M_61})) {
    if (!w.has('Q')) refuse(line, m61->offset, "M61 needs a Q word (tool number)");
    tool_in_spindle_ = w.whole('Q');
    tool_data_known_ = false;
    if (tool_in_spindle_ < 0) refuse(line, w['Q'].offset, "M61 Q must be a whole number >= 0");
  }
  const bool p_on = !w.has('P') || w.get('P') != 0;  // M50-M53 P0 switches off, P1 or none on
  for (const Words::Code& c : w.m) switch (c.code) {
      case M_3:
        spindle_on_ = spindle_clockwise_ = true;
        break;
      case M_4:
        spindle_on_ = true;
        spindle_clockwise_ = false;
        break;
      case M_5:
        spindle_on_ = false;
        break;
      case M_7:
        mist_ = true;
        break;
      case M_8:
        flood_ = true;
        break;
      case M_9:
        mist_ = flood_ = false;
        break;
      case M_48:
        feed_override_ = spindle_override_ = true;
        break;
      case M_49:
        feed_override_ = spindle_override_ = false;
        break;
      case M_50:
        feed_override_ = p_on;
        break;
      case M_51:
        spindle_override_ = p_on;
        break;
      case M_52:
        adaptive_feed_ = p_on;
        break;
      case M_53:
        feed_hold_ = p_on;
        break;
      default:
        break;
    }
  if (w.find_g({G_96})) constant_surface_speed_ = true;
  if (w.find_g({G_97})) constant_surface_speed_ = false;
  if (w.find_g({G_17})) plane_ = G_17;
  if (w.find_g({G_18})) plane_ = G_18;
  if (w.find_g({G_19})) plane_ = G_19;
  const bool was_inches = inches_;
  if (w.find_g({G_20})) inches_ = true;
  if (w.find_g({G_21})) inches_ = false;
  if (inches_ != was_inches && program_xy_.known) {  // LinuxCNC's convert_length_units
    const double factor = inches_ ? 1.0 / kInch : kInch;
    program_xy_.x *= factor;
    program_xy_.y *= factor;
    program_xy_.inches = inches_;
  }
  set_compensation(w, line, effect);
  if (w.find_g({G_43, G_43_1, G_49})) set_tool_length(w, line);
  if (const auto* c = w.find_g({G_54, G_55, G_56, G_57, G_58, G_59, G_59_1, G_59_2, G_59_3})) {
    static constexpr int kSystems[] = {G_54, G_55, G_56, G_57, G_58, G_59, G_59_1, G_59_2, G_59_3};
    const int index =
        static_cast<int>(std::find(std::begin(kSystems), std::end(kSystems), c->code) - std::begin(kSystems)) + 1;
    set_coordinate_system(index);
  }
  if (const auto* mode = w.find_g({G_61, G_61_1, G_64})) {
    path_mode_ = mode->code;
    path_p_ = mode->code == G_64 && w.has('P') ? w.get('P') * (inches_ ? kInch : 1.0) : -1.0;
  }
  if (w.find_g({G_98})) retract_to_r_ = false;
  if (w.find_g({G_99})) retract_to_r_ = true;
  if (const auto* g64 = w.find_g({G_64})) {
    effect.g64_word = g64->index;
    effect.g64_p_word = w['P'].index;
    effect.g64_q_word = w['Q'].index;
  }
  if (w.find_g({G_90})) incremental_ = false;
  if (w.find_g({G_91})) incremental_ = true;
  if (w.find_g({G_90_1})) arc_absolute_ = true;
  if (w.find_g({G_91_1})) arc_absolute_ = false;
  if (w.find_g({G_10})) set_offsets(w, line);
  if (const auto* g92 = w.find_g({G_52, G_92, G_92_1, G_92_2, G_92_3})) set_axis_offsets(w, g92->code, line);
  if (const auto* home = w.find_g({G_28, G_30})) go_home(w, home->code, line, effect);
  if (const auto* store = w.find_g({G_28_1, G_30_1})) {
    const Position world = world_position();
    const int base = store->code == G_28_1 ? kG28Home : kG30Home;
    for (int i = 0; i < kAxes; ++i) parameters_[base + i] = world[i] / machine_unit(i);
  }
  // G80 with a motion code on the same line: the motion code is the mode (rs274 reads it so).
  const Words::Code* motion = w.motion_code();
  const int previous_motion = motion_;
  if (motion) motion_ = motion->code;
  if (w.find_g({G_28, G_30, G_10, G_43_1, G_52, G_92})) {
    // their axis words are not motion
  } else if (is_spline(motion_) || w.find_g({G_5_3})) {  // (G5.3 ends a NURBS whatever the line's mode)
    spline(w, previous_motion, line, effect);
  } else if (is_cycle(motion_)) {
    cycle(w, previous_motion, motion != nullptr, line, effect);
  } else if (is_lathe_cycle(motion_)) {
    lathe_cycle(w, line, effect);
  } else {
    move(w, line, effect);
    if (effect.translate || effect.moved_as_written) cycle_start_z_known_ = false;  // LinuxCNC's cycle_il_flag
  }
  for (const Words::Code& c : w.m)
    if (c.code == M_0 || c.code == M_1 || c.code == M_2 || c.code == M_30 || c.code == M_60) {
      effect.stop_words.push_back(c.index);
      if (c.code == M_2 || c.code == M_30) effect.program_end = true;
    }
  if (!effect.stop_words.empty()) {  // LinuxCNC's convert_stop: the held moves end where they are
    compensating(line, 0, effect, [&] {
      if (effect.program_end)
        compensation_.stop(own_);
      else
        compensation_.flush(own_);
    });
  }
  if (const auto* code = w.find_g({G_0, G_1, G_2, G_3})) effect.motion_code_word = code->index;
  const auto* length_code = w.find_g({G_43, G_43_1, G_49});
  if (length_code && w.find_m({M_6, M_61}) && effect.moves.empty() && !effect.moved_as_written) {
    std::vector<int>& words = effect.after_tool_change_words;
    words.push_back(length_code->index);
    if (w.has('H')) words.push_back(w['H'].index);
    if (length_code->code == G_43_1)
      for (int i = 0; i < kAxes; ++i)
        if (w.has(kAxisLetters[i])) words.push_back(w[kAxisLetters[i]].index);
    words.insert(words.end(), effect.stop_words.begin(), effect.stop_words.end());
  }
  if (tool_elsewhere_ && w.find_m({M_6, M_61}))  // LinuxCNC reads its position back after a tool change
    position_ = take_move_start(frame(), position_);
  effect.modal_motion = motion_;
  effect.inches = inches_;
  effect.incremental = incremental_;
  effect.arc_absolute = arc_absolute_;
}

Move Interpreter::new_move(int line, const Frame& in) const {
  Move m;
  m.line = line;
  m.start = position_;
  m.known_start = known_;
  m.frame = in;
  m.tool_offset_mm = tool_offset_;
  m.tool_offset_from = tool_offset_from_;
  m.tool_offset_tool = tool_offset_tool_;
  m.tool = tool_in_spindle_;
  m.inverse_time = inverse_time_;
  m.feed = feed_;
  m.spindle_on = spindle_on_;
  m.spindle_rpm = spindle_rpm_;
  return m;
}

Position Interpreter::end_point(const Words& w, int line) const {
  Position end = position_;
  const double scale = inches_ ? kInch : 1.0;
  for (int i = 0; i < kAxes; ++i) {
    const char letter = kAxisLetters[i];
    if (!w.has(letter)) continue;
    if (!(setup_.machine_axes >> i & 1u))
      refuse(line, w[letter].offset, std::string("this machine has no ") + letter + " axis");
    const double value = w.get(letter) * (is_linear(i) ? scale : 1.0);
    end[i] = incremental_ ? end[i] + value : value;
  }
  if (w.polar()) polar_end_point(w, line, end[0], end[1]);
  return end;
}

std::array<double, 2> Interpreter::program_xy() const {
  const ProgramXY& p = program_xy_;
  // (Within 1e-9 mm: a frame change that keeps the point, such as a tool length, may move
  // position_ in its last bits where LinuxCNC's current X Y stay as they were.)
  if (p.known && p.inches == inches_ && std::abs(p.mm_x - position_[0]) <= 1e-9 &&
      std::abs(p.mm_y - position_[1]) <= 1e-9)
    return {p.x, p.y};
  const double scale = inches_ ? kInch : 1.0;
  return {position_[0] / scale, position_[1] / scale};
}

void Interpreter::note_program_xy(double x, double y) {
  program_xy_ = {x, y, position_[0], position_[1], inches_, true};
}

void Interpreter::polar_end_point(const Words& w, int line, double& x, double& y) const {
  // LinuxCNC's find_ends: '@' distance and '^' angle (deg) about the origin of the XY plane;
  // the one not given is the current point's; in G91 both are increments of the current point's.
  const int at = w.has('@') ? w['@'].offset : w['^'].offset;
  if (w.has('X') || w.has('Y')) refuse(line, at, "X or Y words with polar coordinates");
  if (plane_ != G_17) refuse(line, at, "polar coordinates are translated in the XY plane (G17) only");
  const double px = position_[0], py = position_[1];
  const double r0 = std::hypot(px, py), t0 = std::atan2(py, px);
  const double scale = inches_ ? kInch : 1.0;
  double r = w.has('@') ? w.get('@') * scale : r0, t = w.has('^') ? w.get('^') * M_PI / 180.0 : t0;
  if (incremental_) {
    if (px == 0 && py == 0) refuse(line, at, "LinuxCNC refuses G91 polar coordinates at the origin");
    r = r0 + (w.has('@') ? w.get('@') * scale : 0.0);
    t = t0 + (w.has('^') ? w.get('^') * M_PI / 180.0 : 0.0);
  } else if (!w.has('^') && px == 0 && py == 0) {
    refuse(line, at, "LinuxCNC needs the angle (^) of a polar point at the origin");
  }
  x = r * std::cos(t);
  y = r * std::sin(t);
}

void Interpreter::move(const Words& w, int line, Effect& effect) {
  unsigned named = 0;
  for (int i = 0; i < kAxes; ++i)
    if (w.has(kAxisLetters[i])) named |= 1u << i;
  if (w.polar()) named |= 0b11u;
  const auto* g53 = w.find_g({G_53});
  if (g53 && w.polar()) refuse(line, g53->offset, "LinuxCNC refuses polar coordinates with G53");
  const bool arc_words =
      w.has('I') || w.has('J') || w.has('K') || (w.has('R') && !w.find_m({M_19}));  // M19 R: an angle
  if (!named && !arc_words) {
    if (g53) refuse(line, g53->offset, "G53 without axis words");
    return;
  }
  if (no_motion_mode())
    refuse(line, w.first_motion_offset(),
           std::string("axis words without a motion mode (G0, G1, G2 or G3)") +
               (motion_ == -1 ? ": G5.3 leaves none, as LinuxCNC" : ""));
  if (!g53) require_known_offsets(line, w.first_motion_offset());

  Move m = new_move(line, frame());
  m.kind = motion_ == G_0 ? MoveKind::Rapid : motion_ == G_1 ? MoveKind::Line : MoveKind::Arc;

  if (g53) {
    if (m.kind == MoveKind::Arc) refuse(line, g53->offset, "G53 is only allowed with G0 or G1");
    if (incremental_) refuse(line, g53->offset, "G53 is only allowed in absolute mode (G90)");
    // Machine coordinates: the given axes are world positions; the others stay where they are.
    Frame machine;
    if (!setup_.tool_length_in_world) machine.offset[2] = -tool_offset_;
    Position world_start = m.frame.world(m.start), world_end = world_start;
    for (int i = 0; i < kAxes; ++i)
      if (named >> i & 1u) {
        if (!(setup_.machine_axes >> i & 1u))
          refuse(line, w[kAxisLetters[i]].offset, std::string("this machine has no ") + kAxisLetters[i] + " axis");
        world_end[i] = w.get(kAxisLetters[i]) * (is_linear(i) && inches_ ? kInch : 1.0) - machine.offset[i];
      }
    m.frame = machine;
    m.machine_coordinates = true;
    m.start = machine.program(world_start);
    m.end = machine.program(world_end);
    position_ = frame().program(world_end);
  } else {
    const std::array<double, 2> xy = program_xy();
    m.end = end_point(w, line);
    if (m.kind == MoveKind::Arc && arc_not_allowed_)
      refuse(line, w.first_motion_offset(),
             "the move just after exiting cutter compensation mode must be straight, not an arc");
    if (m.kind == MoveKind::Arc)
      arc_geometry(w, m.end, line, m);
    else if (arc_words)
      refuse(line,
             w[w.has('I')   ? 'I'
               : w.has('J') ? 'J'
               : w.has('K') ? 'K'
                            : 'R']
                 .offset,
             "I, J, K or R words without G2/G3");
    position_ = m.end;
    if (!w.polar())
      note_program_xy(w.has('X') ? (incremental_ ? xy[0] + w.get('X') : w.get('X')) : xy[0],
                      w.has('Y') ? (incremental_ ? xy[1] + w.get('Y') : w.get('Y')) : xy[1]);
  }
  known_ |= named;

  arc_not_allowed_ = false;
  const unsigned needed = setup_.machine_axes;
  const bool start_known = (m.known_start & needed) == needed;
  const bool end_known = (known_ & needed) == needed;
  if (compensation_.offsets() && !g53) {
    if (!start_known || !end_known)
      refuse(line, w.first_motion_offset(),
             "cannot compensate the cutter radius from an unknown position: move every axis first, or give the start "
             "position (volcomp predistort --start)");
    compensated_move(w, m, line, effect);
    motion_words(w, m, effect);
    return;
  }
  const Position programmed_start = m.start;
  m.start = take_move_start(m.frame, m.start);  // the first move after G40 starts where the tool is
  if (inverse_time_ && m.kind != MoveKind::Rapid && m.start != programmed_start) {
    // LinuxCNC times it from the programmed point the compensation left, not from the tool.
    Move programmed = m;
    programmed.start = programmed_start;
    m.compensated_rate_mm_per_min = inverse_time_rate(programmed);
    m.feed = inverse_time_feed(m);
  }
  if (!end_known || (m.kind != MoveKind::Rapid && !start_known)) {
    if (m.kind != MoveKind::Rapid) {
      std::string missing;
      for (int i = 0; i < kAxes; ++i)
        if ((needed >> i & 1u) && !((m.known_start & known_) >> i & 1u)) missing += kAxisLetters[i];
      refuse(line, w.first_motion_offset(),
             "cannot correct a cutting move from an unknown position (" + missing +
                 " not set yet): begin the program with a G0 or G53 move to every axis, or give the start position "
                 "(volcomp predistort --start)");
    }
    effect.moved_as_written = true;  // a rapid to a partly known position: written as it is, uncorrected
    return;
  }
  effect.moves.push_back(m);
  motion_words(w, m, effect);
}

void Interpreter::require_known_offsets(int line, int offset) const {
  if (!offsets_known_ && !(offsets_set_ >> coordinate_system_ & 1u))
    refuse(line, offset,
           "work offset " +
               g_name(std::array{540, 550, 560, 570, 580, 590, 591, 592,
                                 593}[static_cast<std::size_t>(coordinate_system_ - 1)]) +
               " is not known: pass --var FILE (LinuxCNC's parameter file) or set it with G10 L2");
}

void Interpreter::motion_words(const Words& w, const Move& m, Effect& effect) const {
  effect.translate = true;
  for (char c : {'X', 'Y', 'Z', 'A', 'B', 'C', 'I', 'J', 'K', 'R', '@', '^'})
    if (w.has(c) && w[c].index >= 0) effect.motion_words.push_back(w[c].index);  // (< 0: a cycle's own move)
  if (m.kind == MoveKind::Arc && w.has('P')) effect.motion_words.push_back(w['P'].index);
}

}  // namespace vc::interpreter
