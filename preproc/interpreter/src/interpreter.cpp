#include "vc/interpreter/interpreter.hpp"

#include <algorithm>
#include <cmath>

#include "vc/gcode/evaluate.hpp"
#include "vc/gcode/parser.hpp"
#include "vc/interpreter/line_text.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::interpreter {
namespace {

constexpr double kInch = 25.4;
constexpr double kTwoPi = 2.0 * M_PI;

// LinuxCNC 2.9's arc checks (interp_internal.hh, interp_arc.cc), in program units: an R arc
// may fall short of the end point by RADIUS_TOLERANCE; an IJK arc's start and end radius
// (a spiral) may differ by CENTER_ARC_RADIUS_TOLERANCE if that is more than 0.1 % of the
// radius, and never by 100 times it; a radius below RADIUS_TOLERANCE is a zero-radius arc.
constexpr double kRadiusTolerance_inch = 0.00005;
constexpr double kCenterArcRadiusTolerance_inch = 2 * 0.001 * M_SQRT2;
constexpr double kCenterArcRadiusTolerance_mm = 2 * 0.01 * M_SQRT2;
constexpr double kSpiralRelativeTolerance = 0.001;

// Parameter numbers of a LinuxCNC .var file.
constexpr int kG28Home = 5161, kG30Home = 5181;
constexpr int kCoordinateSystem = 5220;         // active system 1..9
constexpr int kG92Applied = 5210, kG92 = 5211;  // G92 offsets on (1) and their values X..C
int offset_parameter(int system, int axis) { return 5201 + 20 * system + axis; }  // 5221 = G54 X
int rotation_parameter(int system) { return 5210 + 20 * system; }                  // 5230 = G54 R

std::string g_name(int code) {
  const int whole = code / 10, tenth = code % 10;
  return "G" + std::to_string(whole) + (tenth ? "." + std::to_string(tenth) : "");
}

}  // namespace

void Effect::clear() {
  moves.clear();
  translate = false;
  motion_words.clear();
  stop_words.clear();
  g64_word = g64_p_word = g64_q_word = f_word = motion_code_word = -1;
  moved_as_written = false;
  after_tool_change_words.clear();
  modal_motion = 800;
  inches = incremental = arc_absolute = program_end = false;
}

// The words of a block with their values (evaluated with the parameters from before the
// line), sorted into letters and G/M codes.
struct Interpreter::Words {
  struct Value {
    bool has = false;
    double value = 0.0;
    int index = -1;   // into block.words
    int offset = 0;
  };
  struct Code {
    int code;   // x10: G59.1 = 591
    int index;
    int offset;
  };
  std::array<Value, 26> letters{};
  std::vector<Code> g, m;

  const Value& operator[](char c) const { return letters[static_cast<std::size_t>(c - 'A')]; }
  // A word that must hold a whole number (tool, turns, L, P): its value, or -1 if it does not.
  int whole(char c) const {
    const double v = get(c);
    return v == std::floor(v) && v >= 0 && v <= 1e6 ? static_cast<int>(v) : -1;
  }
  bool has(char c) const { return (*this)[c].has; }
  // Where the first axis or arc word is written (for messages about the motion).
  int first_motion_offset() const {
    int first = -1;
    for (char c : {'X', 'Y', 'Z', 'A', 'B', 'C', 'I', 'J', 'K', 'R'})
      if (has(c) && (first < 0 || (*this)[c].offset < first)) first = (*this)[c].offset;
    return std::max(first, 0);
  }
  double get(char c) const { return (*this)[c].value; }
  const Code* find_g(std::initializer_list<int> codes) const {
    for (const Code& c : g)
      if (std::find(codes.begin(), codes.end(), c.code) != codes.end()) return &c;
    return nullptr;
  }
  const Code* find_m(std::initializer_list<int> codes) const {
    for (const Code& c : m)
      if (std::find(codes.begin(), codes.end(), c.code) != codes.end()) return &c;
    return nullptr;
  }
};

Interpreter::Interpreter(Setup setup) : setup_(std::move(setup)) {
  if (setup_.var_file) {
    parameters_ = *setup_.var_file;
    const double system = parameters_[kCoordinateSystem];
    if (system >= 1 && system <= 9) coordinate_system_ = static_cast<int>(system);
    offsets_known_ = true;
    // LinuxCNC restores the G92 offsets at start if they were on (rs274ngc_pre.cc, init).
    if (parameters_[kG92Applied] != 0.0)
      for (int i = 0; i < kAxes; ++i) g92_[i] = parameters_[kG92 + i];
  }
  if (setup_.start_world) {
    set_world_position(*setup_.start_world);
    known_ = kAllAxes;
  }
}

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

Frame Interpreter::frame() const {
  Frame f;
  for (int i = 0; i < kAxes; ++i) f.offset[i] = parameters_[offset_parameter(coordinate_system_, i)];
  f.rotation_deg = parameters_[rotation_parameter(coordinate_system_)];
  // G92/G52 offsets are added to program coordinates before the rotation (LinuxCNC's canon:
  // world = rotate(program + G92) + G5x + tool length).
  const Position g92 = Frame{{}, f.rotation_deg}.world(g92_);
  for (int i = 0; i < kAxes; ++i) f.offset[i] += g92[i];
  if (setup_.tool_length_in_world) f.offset[2] += tool_length_;
  return f;
}

Position Interpreter::world_position() const { return frame().world(position_); }

void Interpreter::set_world_position(const Position& world) { position_ = frame().program(world); }

void Interpreter::execute(const gcode::Block& block, int line, Effect& effect) {
  effect.clear();
  if (block.percent) return;
  if (block.o_word >= 0)
    refuse(line, block.o_word,
           "O-word control flow (subroutines, loops, conditions) is not translated: expand it in the "
           "post-processor");

  // Words, evaluated before this line's assignments take effect.
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
    Words::Value& v = w.letters[static_cast<std::size_t>(word.letter - 'A')];
    if (v.has) refuse(line, word.begin, std::string("word ") + word.letter + " appears twice on the line");
    v = {true, value, i, word.begin};
  }
  try {
    gcode::apply_assignments(block, parameters_);
  } catch (const gcode::SyntaxError& e) {
    refuse(line, e.offset, e.what());
  }
  effect.f_word = w['F'].index;

  // Codes this tool refuses, with the reason.
  for (const Words::Code& c : w.g) {
    const int g = c.code;
    const char* reason = nullptr;
    if (g == 410 || g == 411 || g == 420 || g == 421)
      reason = "cutter radius compensation (G41/G42) is not translated: the corrected path would be "
               "offset again by the controller; let the CAM system compute the tool path";
    else if ((g >= 810 && g <= 890 && g % 10 == 0) || g == 730 || g == 760)
      reason = "canned cycles are not translated: expand them into G0/G1 moves in the post-processor";
    else if (g == 330 || g == 331 || (g >= 382 && g <= 385) || g == 50 || g == 51 || g == 52 || g == 70 ||
             g == 80 || g == 432 || g == 171 || g == 181 || g == 191)
      reason = "not supported by the pre-distorter (threading, probing, splines, lathe modes, G43.2, "
               "G17.1-G19.1)";
    if (reason) refuse(line, c.offset, g_name(g) + ": " + reason);
    static constexpr int kKnown[] = {0,   10,  20,  30,  40,  100, 170, 180, 190, 200, 210, 280,
                                     281, 300, 301, 400, 430, 431, 490, 530, 540, 550, 560, 570,
                                     580, 590, 591, 592, 593, 610, 611, 640, 800, 900, 901, 910,
                                     911, 920, 921, 922, 923, 520, 930, 940, 950, 960, 970, 980, 990};
    if (std::find(std::begin(kKnown), std::end(kKnown), g) == std::end(kKnown))
      refuse(line, c.offset, "unknown G code " + g_name(g));
  }
  for (const Words::Code& c : w.m) {
    const int m = c.code / 10;
    if (c.code % 10 != 0) refuse(line, c.offset, "unknown M code");
    if (m == 98 || m == 99)
      refuse(line, c.offset, "M98/M99 subprograms are not translated: expand them in the post-processor");
    if (m >= 70 && m <= 73)
      refuse(line, c.offset, "M70-M73 (save/restore modal state) are not supported");
    const bool known = m <= 9 || m == 30 || (m >= 48 && m <= 53) || (m >= 60 && m <= 68) || (m >= 100 && m <= 199);
    if (!known) refuse(line, c.offset, "unknown M code M" + std::to_string(m));
  }
  for (char c : {'U', 'V', 'W'})
    if (w.has(c)) refuse(line, w[c].offset, std::string("the ") + c + " axis is not supported (machines have X Y Z A B C)");
  if (block.block_delete) {
    // Whether LinuxCNC runs this line depends on the block-delete switch: the path after it
    // would be unknown if the line moved or changed the modal state.
    for (char c : {'X', 'Y', 'Z', 'A', 'B', 'C', 'I', 'J', 'K', 'R'})
      if (w.has(c)) refuse(line, 0, "a block-delete ('/') line may not move the machine");
    if (!w.g.empty()) refuse(line, 0, "a block-delete ('/') line may not change G modes");
  }

  // LinuxCNC's order of execution (RS274/NGC 3.8, LinuxCNC docs "Order of Execution").
  if (w.find_g({930})) inverse_time_ = true;
  if (w.find_g({940, 950})) inverse_time_ = false;
  if (w.find_g({950})) refuse(line, w.find_g({950})->offset, "G95 (feed per revolution) is not supported");
  if (w.has('F')) feed_ = w.get('F');
  if (w.has('S')) spindle_rpm_ = w.get('S');
  if (w.has('T')) {
    selected_tool_ = w.whole('T');
    if (selected_tool_ < 0) refuse(line, w['T'].offset, "T must be a whole number >= 0");
  }
  if (w.find_m({60})) tool_in_spindle_ = selected_tool_;
  if (const auto* m61 = w.find_m({610})) {
    if (!w.has('Q')) refuse(line, m61->offset, "M61 needs a Q word (tool number)");
    tool_in_spindle_ = w.whole('Q');
    if (tool_in_spindle_ < 0) refuse(line, w['Q'].offset, "M61 Q must be a whole number >= 0");
  }
  if (w.find_m({30, 40})) spindle_on_ = true;
  if (w.find_m({50})) spindle_on_ = false;
  if (w.find_g({170})) plane_ = 170;
  if (w.find_g({180})) plane_ = 180;
  if (w.find_g({190})) plane_ = 190;
  if (w.find_g({200})) inches_ = true;
  if (w.find_g({210})) inches_ = false;
  if (w.find_g({430, 431, 490})) set_tool_length(w, line);
  if (const auto* c = w.find_g({540, 550, 560, 570, 580, 590, 591, 592, 593})) {
    static constexpr int kSystems[] = {540, 550, 560, 570, 580, 590, 591, 592, 593};
    const int index = static_cast<int>(std::find(std::begin(kSystems), std::end(kSystems), c->code) -
                                       std::begin(kSystems)) + 1;
    set_coordinate_system(index);
  }
  if (const auto* g64 = w.find_g({640})) {
    effect.g64_word = g64->index;
    effect.g64_p_word = w['P'].index;
    effect.g64_q_word = w['Q'].index;
  }
  if (w.find_g({900})) incremental_ = false;
  if (w.find_g({910})) incremental_ = true;
  if (w.find_g({901})) arc_absolute_ = true;
  if (w.find_g({911})) arc_absolute_ = false;
  if (w.find_g({100})) set_offsets(w, line);
  if (const auto* g92 = w.find_g({520, 920, 921, 922, 923})) set_axis_offsets(w, g92->code, line);
  if (const auto* home = w.find_g({280, 300})) go_home(w, home->code, line, effect);
  if (const auto* store = w.find_g({281, 301})) {
    const Position world = world_position();
    const int base = store->code == 281 ? kG28Home : kG30Home;
    for (int i = 0; i < kAxes; ++i) parameters_[base + i] = world[i];
  }
  if (const auto* motion = w.find_g({0, 10, 20, 30, 800})) motion_ = motion->code;
  if (!w.find_g({280, 300, 100, 431, 520, 920})) move(w, line, effect);  // their axis words are not motion
  for (const Words::Code& c : w.m)
    if (c.code == 0 || c.code == 10 || c.code == 20 || c.code == 300 || c.code == 600) {
      effect.stop_words.push_back(c.index);
      if (c.code == 20 || c.code == 300) effect.program_end = true;
    }
  if (const auto* motion = w.find_g({0, 10, 20, 30})) effect.motion_code_word = motion->index;
  const auto* length_code = w.find_g({430, 431, 490});
  if (length_code && w.find_m({60, 610}) && effect.moves.empty() && !effect.moved_as_written) {
    std::vector<int>& words = effect.after_tool_change_words;
    words.push_back(length_code->index);
    if (w.has('H')) words.push_back(w['H'].index);
    if (length_code->code == 431)
      for (int i = 0; i < kAxes; ++i)
        if (w.has(kAxisLetters[i])) words.push_back(w[kAxisLetters[i]].index);
    words.insert(words.end(), effect.stop_words.begin(), effect.stop_words.end());
  }
  effect.modal_motion = motion_;
  effect.inches = inches_;
  effect.incremental = incremental_;
  effect.arc_absolute = arc_absolute_;
}

void Interpreter::set_tool_length(const Words& w, int line) {
  const Position world = world_position();
  const auto* g = w.find_g({430, 431, 490});
  if (g->code == 490) {
    tool_length_ = 0.0;
  } else if (g->code == 431) {
    if (!w.has('Z')) refuse(line, g->offset, "G43.1 needs a Z word (tool length)");
    tool_length_ = w.get('Z') * (inches_ ? kInch : 1.0);
  } else {
    int tool = tool_in_spindle_;
    if (w.has('H')) tool = w.whole('H');
    if (w.has('H') && tool < 0) refuse(line, w['H'].offset, "H must be a whole number >= 0");
    else if (tool < 0)
      refuse(line, g->offset, "G43 without H and no tool in the spindle yet (use G43 Hn, or M6 Tn first)");
    if (!setup_.tools)
      refuse(line, g->offset, "G43 needs the tool table: pass --tool-table FILE (LinuxCNC's .tbl)");
    const auto it = setup_.tools->find(tool);
    if (it == setup_.tools->end())
      refuse(line, w.has('H') ? w['H'].offset : g->offset,
             "tool " + std::to_string(tool) + " is not in the tool table");
    tool_length_ = it->second.z_offset;  // machine units: mm
  }
  set_world_position(world);  // LinuxCNC keeps the machine still; the program position changes
}

void Interpreter::set_coordinate_system(int index) {
  const Position world = world_position();
  coordinate_system_ = index;
  set_world_position(world);
}

void Interpreter::set_offsets(const Words& w, int line) {
  const auto* g10 = w.find_g({100});
  if (!w.has('L')) refuse(line, g10->offset, "G10 needs an L word");
  const int l = w.whole('L');
  if (l != 2 && l != 20)
    refuse(line, w['L'].offset, "G10 L" + std::to_string(l) + " is not supported (G10 L2 and L20 are)");
  if (!w.has('P')) refuse(line, g10->offset, "G10 L" + std::to_string(l) + " needs a P word (1..9, or 0)");
  int system = w.whole('P');
  if (system < 0 || system > 9) refuse(line, w['P'].offset, "G10 P must be 0..9");
  if (system == 0) system = coordinate_system_;
  const Position world = world_position();
  const double scale = inches_ ? kInch : 1.0;
  for (int i = 0; i < kAxes; ++i) {
    const char letter = kAxisLetters[i];
    if (!w.has(letter)) continue;
    const double value = w.get(letter) * (is_linear(i) ? scale : 1.0);
    double& offset = parameters_[offset_parameter(system, i)];
    if (l == 2) {
      offset = value;
    } else {
      // L20: the current position becomes `value` in that system.
      if (!(known_ >> i & 1u))
        refuse(line, w[letter].offset, std::string("G10 L20: the current ") + letter + " is not known yet");
      double tool = (i == 2 && setup_.tool_length_in_world) ? tool_length_ : 0.0;
      if (parameters_[rotation_parameter(system)] != 0.0 && i < 2)
        refuse(line, w[letter].offset, "G10 L20 on a rotated coordinate system is not supported");
      if (g92_[i] != 0.0) refuse(line, w[letter].offset, "G10 L20 while G92 offsets are on is not supported");
      offset = world[i] - tool - value;
    }
  }
  if (w.has('R')) {
    if (l != 2) refuse(line, w['R'].offset, "R (rotation) only with G10 L2");
    parameters_[rotation_parameter(system)] = w.get('R');
  }
  offsets_set_ |= 1u << system;
  if (system == coordinate_system_) set_world_position(world);
}

void Interpreter::set_axis_offsets(const Words& w, int code, int line) {
  // LinuxCNC's convert_axis_offsets (interp_convert.cc): the machine stays where it is. G92:
  // the current point gets the given coordinates; G52: the offset is the given values; G92.1
  // and G92.2 take the offsets off (G92.1 also zeroes #5211..), G92.3 puts #5211.. back on.
  const Position world = world_position();
  const double scale = inches_ ? kInch : 1.0;
  if (code == 920 || code == 520) {
    bool any = false;
    for (int i = 0; i < kAxes; ++i) {
      const char letter = kAxisLetters[i];
      if (!w.has(letter)) continue;
      any = true;
      if (!(setup_.machine_axes >> i & 1u))
        refuse(line, w[letter].offset, std::string("this machine has no ") + letter + " axis");
      if (code == 920 && !(known_ >> i & 1u))
        refuse(line, w[letter].offset, std::string("G92: the current ") + letter + " is not known yet");
      const double value = w.get(letter) * (is_linear(i) ? scale : 1.0);
      g92_[i] = code == 920 ? position_[i] + g92_[i] - value : value;
    }
    if (!any) refuse(line, w.find_g({code})->offset, g_name(code) + " needs at least one axis word");
    parameters_[kG92Applied] = 1.0;
    for (int i = 0; i < kAxes; ++i) parameters_[kG92 + i] = g92_[i];
  } else if (code == 921 || code == 922) {
    g92_ = {};
    parameters_[kG92Applied] = 0.0;
    if (code == 921)
      for (int i = 0; i < kAxes; ++i) parameters_[kG92 + i] = 0.0;
  } else {  // G92.3
    parameters_[kG92Applied] = 1.0;
    for (int i = 0; i < kAxes; ++i) g92_[i] = parameters_[kG92 + i];
  }
  set_world_position(world);
}

void Interpreter::go_home(const Words& w, int code, int line, Effect& effect) {
  // G28/G30: rapid to the intermediate point (axis words), then to the stored home
  // (machine coordinates) on those axes, or on all axes if none is given. The pre-distorter
  // writes these lines as they are: rapids away from the part, to a position stored in the
  // controller.
  const int base = code == 280 ? kG28Home : kG30Home;
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
    if (named >> i & 1u) world[i] = parameters_[base + i];
  set_world_position(world);
  known_ |= named;
  effect.moved_as_written = true;
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
  return end;
}

void Interpreter::move(const Words& w, int line, Effect& effect) {
  unsigned named = 0;
  for (int i = 0; i < kAxes; ++i)
    if (w.has(kAxisLetters[i])) named |= 1u << i;
  const auto* g53 = w.find_g({530});
  const bool arc_words = w.has('I') || w.has('J') || w.has('K') || w.has('R');
  if (!named && !arc_words) {
    if (g53) refuse(line, g53->offset, "G53 without axis words");
    return;
  }
  if (motion_ == 800)
    refuse(line, w.first_motion_offset(),
           "axis words without a motion mode (G0, G1, G2 or G3)");
  if (!offsets_known_ && !(offsets_set_ >> coordinate_system_ & 1u) && !g53)
    refuse(line, w.first_motion_offset(),
           "work offset " + g_name(std::array{540, 550, 560, 570, 580, 590, 591, 592, 593}
                                       [static_cast<std::size_t>(coordinate_system_ - 1)]) +
               " is not known: pass --var FILE (LinuxCNC's parameter file) or set it with G10 L2");

  Move m;
  m.line = line;
  m.start = position_;
  m.known_start = known_;
  m.frame = frame();
  m.tool_length_mm = tool_length_;
  m.tool = tool_in_spindle_;
  m.inverse_time = inverse_time_;
  m.feed = feed_;
  m.spindle_on = spindle_on_;
  m.spindle_rpm = spindle_rpm_;
  m.kind = motion_ == 0 ? MoveKind::Rapid : motion_ == 10 ? MoveKind::Line : MoveKind::Arc;

  if (g53) {
    if (m.kind == MoveKind::Arc) refuse(line, g53->offset, "G53 is only allowed with G0 or G1");
    if (incremental_) refuse(line, g53->offset, "G53 is only allowed in absolute mode (G90)");
    if (m.frame.rotation_deg != 0.0) refuse(line, g53->offset, "G53 on a rotated coordinate system is not supported");
    // Machine coordinates: the given axes are world positions; the others stay where they are.
    Frame machine;
    if (!setup_.tool_length_in_world) machine.offset[2] = -tool_length_;
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
    m.end = end_point(w, line);
    if (m.kind == MoveKind::Arc) arc_geometry(w, m.end, line, m);
    else if (arc_words)
      refuse(line, w[w.has('I') ? 'I' : w.has('J') ? 'J' : w.has('K') ? 'K' : 'R'].offset,
             "I, J, K or R words without G2/G3");
    position_ = m.end;
  }
  known_ |= named;

  const unsigned needed = setup_.machine_axes;
  const bool start_known = (m.known_start & needed) == needed;
  const bool end_known = (known_ & needed) == needed;
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
  effect.translate = true;
  effect.moves.push_back(m);
  for (char c : {'X', 'Y', 'Z', 'A', 'B', 'C', 'I', 'J', 'K', 'R'})
    if (w.has(c)) effect.motion_words.push_back(w[c].index);
  if (m.kind == MoveKind::Arc && w.has('P')) effect.motion_words.push_back(w['P'].index);
}

void Interpreter::arc_geometry(const Words& w, const Position& end, int line, Move& m) const {
  Arc& arc = m.arc;
  arc.clockwise = motion_ == 20;
  const int offset = w.find_g({20, 30}) ? w.find_g({20, 30})->offset : w[w.has('X') ? 'X' : 'Y'].offset;
  char first_letter, second_letter;  // center words of the plane
  if (plane_ == 170) { arc.first = 0; arc.second = 1; arc.normal = 2; first_letter = 'I'; second_letter = 'J'; }
  else if (plane_ == 180) { arc.first = 2; arc.second = 0; arc.normal = 1; first_letter = 'K'; second_letter = 'I'; }
  else { arc.first = 1; arc.second = 2; arc.normal = 0; first_letter = 'J'; second_letter = 'K'; }
  if (w.has('P')) {
    const double p = w.get('P');
    if (w.whole('P') < 1 || p > 1000) refuse(line, w['P'].offset, "P (turns) of an arc must be a whole number 1..1000");
    arc.turns = w.whole('P');
  }
  const double scale = inches_ ? kInch : 1.0;
  const double radius_tolerance = kRadiusTolerance_inch * kInch;  // the same length in G20 and G21
  const double spiral_tolerance = inches_ ? kCenterArcRadiusTolerance_inch * kInch : kCenterArcRadiusTolerance_mm;
  const double a0 = m.start[arc.first], b0 = m.start[arc.second];
  const double a1 = end[arc.first], b1 = end[arc.second];
  if (w.has('R')) {
    // Radius form: the center on the perpendicular bisector; R < 0 takes the long way.
    const double r = std::abs(w.get('R') * scale);
    if (a1 == a0 && b1 == b0) refuse(line, w['R'].offset, "an R-form arc cannot end where it starts");
    double half = std::hypot(a1 - a0, b1 - b0) / 2;
    if (half - r > radius_tolerance) refuse(line, w['R'].offset, "arc radius too small to reach the end point");
    if (half / r > 1 - 1e-12) half = r;  // LinuxCNC: a half circle within the tolerance
    const double h = std::sqrt(r * r - half * half);
    // Center to the left of start->end for (CCW, short way) and (CW, long way).
    const double sign = ((w.get('R') > 0) != arc.clockwise) ? 1.0 : -1.0;
    const double chord = std::hypot(a1 - a0, b1 - b0);
    const double ua = (a1 - a0) / chord, ub = (b1 - b0) / chord;
    arc.center_first = (a0 + a1) / 2 - sign * h * ub;
    arc.center_second = (b0 + b1) / 2 + sign * h * ua;
  } else {
    if (!w.has(first_letter) && !w.has(second_letter))
      refuse(line, offset, std::string("G2/G3 in this plane needs ") + first_letter + " or " + second_letter +
                               " (center), or R");
    for (char c : {'I', 'J', 'K'})
      if (w.has(c) && c != first_letter && c != second_letter)
        refuse(line, w[c].offset, std::string(1, c) + " is not a center word in the active plane");
    const double di = w.get(first_letter) * scale, dj = w.get(second_letter) * scale;
    arc.center_first = arc_absolute_ ? di : a0 + di;
    arc.center_second = arc_absolute_ ? dj : b0 + dj;
    const double r0 = std::hypot(a0 - arc.center_first, b0 - arc.center_second);
    const double r1 = std::hypot(a1 - arc.center_first, b1 - arc.center_second);
    if (r0 < radius_tolerance || r1 < radius_tolerance) refuse(line, offset, "arc of zero radius");
    const double difference = std::abs(r1 - r0);
    if (difference > 100 * spiral_tolerance ||
        (difference / std::max(r0, r1) > kSpiralRelativeTolerance && difference > spiral_tolerance))
      refuse(line, offset, "radius to end of arc differs from radius to start by " + std::to_string(difference) +
                               " mm (LinuxCNC allows " + std::to_string(spiral_tolerance) + " mm or 0.1 %)");
  }
  const double t0 = std::atan2(b0 - arc.center_second, a0 - arc.center_first);
  const double t1 = std::atan2(b1 - arc.center_second, a1 - arc.center_first);
  double sweep = t1 - t0;
  if (arc.clockwise) {
    while (sweep >= -1e-12) sweep -= kTwoPi;  // (-2 pi, 0), a full turn if start == end
    if (sweep < -kTwoPi) sweep += kTwoPi;
  } else {
    while (sweep <= 1e-12) sweep += kTwoPi;
    if (sweep > kTwoPi) sweep -= kTwoPi;
  }
  arc.sweep_rad = sweep + (arc.clockwise ? -1.0 : 1.0) * kTwoPi * (arc.turns - 1);
}

Position point_at(const Move& m, double s) {
  Position p;
  for (int i = 0; i < kAxes; ++i) p[i] = m.start[i] + s * (m.end[i] - m.start[i]);
  if (m.kind != MoveKind::Arc) return p;
  const Arc& a = m.arc;
  const double t0 = std::atan2(m.start[a.second] - a.center_second, m.start[a.first] - a.center_first);
  const double r0 = std::hypot(m.start[a.first] - a.center_first, m.start[a.second] - a.center_second);
  const double r1 = std::hypot(m.end[a.first] - a.center_first, m.end[a.second] - a.center_second);
  const double r = r0 + s * (r1 - r0), t = t0 + s * a.sweep_rad;
  p[a.first] = a.center_first + r * std::cos(t);
  p[a.second] = a.center_second + r * std::sin(t);
  return p;
}

}  // namespace vc::interpreter
