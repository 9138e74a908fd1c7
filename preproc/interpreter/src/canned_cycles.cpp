// Canned cycles (G73, G74, G81-G86, G88, G89) as LinuxCNC 2.9 makes them (interp_cycles.cc:
// convert_cycle, convert_cycle_xy/zx/yz, CYCLE_MACRO in interp_internal.hh, and the cycle
// functions): the moves written out, so each point can be corrected, with the dwells, spindle
// reversals, override switches and stops the cycles make between them.
//
// The hole axis is the plane's normal: Z in G17 (holes at X Y), Y in G18 (at Z X), X in G19
// (at Y Z); "height" below is along it. Per block: R (sticky), the hole axis word (the bottom,
// sticky), P (dwell, sticky), Q (peck, sticky), L repeats. The height the cycles started from
// (cycle_il) is kept until a motion that is not a cycle. In G91, the position words are
// increments applied on each repeat, R is relative to that start height and the bottom
// relative to R. Below R, the first move is straight up to R. Each hole: rapid across at the
// current height (the first) or the clear height, down to R if above it, then the cycle, then
// up to the clear height: R (G99) or the start height (G98, if above R).
#include <cmath>
#include <string>

#include "words.hpp"
#include "vc/interpreter/line_text.hpp"

namespace vc::interpreter {
namespace {

constexpr double kPeckClearance_inch = 0.010;  // G83_RAPID_DELTA (interp_internal.hh), in program units
// The most moves one cycle block may make (its pecks times its repeats): every move is written
// out, and no real hole needs more (500 mm in pecks of 0.01 mm are 150,000 moves). Beyond it
// the block is refused, not expanded until memory runs out.
constexpr double kMostCycleMoves = 1e6;

}  // namespace

void Interpreter::cycle(const Words& w, int previous_motion, bool code_on_line, int line, Effect& effect) {
  unsigned named = 0;
  for (int i = 0; i < kAxes; ++i)
    if (w.has(kAxisLetters[i])) named |= 1u << i;
  if (w.polar()) named |= 0b11u;
  if (!named && !code_on_line) return;  // no motion on this line
  const int code = motion_;
  const auto* word = w.find_g({code});
  const int at = word ? word->offset : w.first_motion_offset();
  auto fail = [&](const std::string& why) { refuse(line, at, g_name(code) + ": " + why); };
  // The plane's axes (a, b: the hole's position) and the hole axis n, with their letters.
  const int a = plane_ == G_17 ? 0 : plane_ == G_18 ? 2 : 1;
  const int b = plane_ == G_17 ? 1 : plane_ == G_18 ? 0 : 2;
  const int n = 3 - a - b;
  const char la = kAxisLetters[a], lb = kAxisLetters[b], ln = kAxisLetters[n];
  if (w.polar() && plane_ != G_17)
    fail("polar coordinates in a canned cycle are translated in the XY plane (G17) only");
  if (inverse_time_) fail("LinuxCNC refuses inverse time feed (G93) with canned cycles");
  if (feed_ == 0.0) fail("LinuxCNC refuses a canned cycle with zero feed rate");
  for (char c : {'A', 'B', 'C'})
    if (w.has(c)) refuse(line, w[c].offset, "the rotary axes may not move in a canned cycle");
  if ((known_ & 0b111u) != 0b111u)  // (the three linear axes, in any plane)
    fail("a canned cycle from an unknown position: begin the program with a G0 to every axis, or --start");
  const double scale = inches_ ? kInch : 1.0;
  // The words that stay: a cycle block without R, Z, P or Q takes them from the last block in
  // the same mode (LinuxCNC: an error if the mode was not already this cycle).
  const bool same_mode = previous_motion == code;
  auto sticky = [&](char letter, double& value, const char* what) {
    if (w.has(letter)) {
      value = w.get(letter) * (letter == 'P' ? 1.0 : scale);
    } else if (!same_mode) {
      fail(std::string(what) + " is missing (the first block of a canned cycle needs it)");
    }
  };
  sticky('R', cycle_r_, "R (the retract plane)");
  sticky(ln, cycle_z_, ln == 'Z' ? "Z (the bottom)" : ln == 'Y' ? "Y (the bottom)" : "X (the bottom)");
  if (code == G_82 || code == G_89 || code == G_86 || code == G_88) sticky('P', cycle_p_, "P (the dwell)");
  if ((code == G_74 || code == G_84) && w.has('P')) cycle_p_ = w.get('P');  // optional, sticky
  if (code == G_74 || code == G_84) {                                       // LinuxCNC's check_g74_g84_spindle
    if (!spindle_on_) fail("LinuxCNC refuses a tapping cycle with the spindle not turning");
    if (spindle_clockwise_ != (code == G_84))
      fail(code == G_84 ? "spindle turning counterclockwise in G84" : "spindle turning clockwise in G74");
  }
  if ((code == G_86 || code == G_88) && !spindle_on_) fail("LinuxCNC refuses this cycle with the spindle not turning");
  if (code == G_73 || code == G_83) {
    sticky('Q', cycle_q_, "Q (the peck)");
    if (cycle_q_ <= 0) refuse(line, w.has('Q') ? w['Q'].offset : at, "LinuxCNC refuses a Q that is not positive");
  }
  int repeats = 1;
  if (w.has('L')) {
    repeats = w.whole('L');
    if (repeats < 1) refuse(line, w['L'].offset, "L (repeats) must be a whole number >= 1");
  }
  if (!offsets_known_ && !(offsets_set_ >> coordinate_system_ & 1u))
    fail("the work offset is not known: pass --var FILE (LinuxCNC's parameter file) or set it with G10 L2");

  if (!cycle_start_z_known_) {
    cycle_start_z_ = position_[n];
    cycle_start_z_known_ = true;
  }
  double old_z = cycle_start_z_, current_z = position_[n];
  double x = position_[a], y = position_[b], dx = 0, dy = 0, dr = 0, dt = 0, r, bottom;
  if (w.polar() && (w.has('X') || w.has('Y'))) fail("X or Y words with polar coordinates");
  if (incremental_) {
    if (w.has(la)) dx = w.get(la) * scale;
    if (w.has(lb)) dy = w.get(lb) * scale;
    if (w.has('@')) dr = w.get('@') * scale;  // polar increments, about the origin, per repeat
    if (w.has('^')) dt = w.get('^') * M_PI / 180.0;
    r = cycle_r_ + old_z;
    bottom = r + cycle_z_;
  } else {
    r = cycle_r_;
    bottom = cycle_z_;
    if (w.has(la)) x = w.get(la) * scale;
    if (w.has(lb)) y = w.get(lb) * scale;
    if (w.polar()) polar_end_point(w, line, x, y);
  }
  if (r < bottom) fail("LinuxCNC refuses R below Z");

  const Frame f = frame();
  Position tool = take_move_start(f, position_);  // where the tool is
  // A move to (to_x, to_y) in the plane, at height to_z; `swapped`: to where LinuxCNC 2.9's
  // G74/G84 sends it outside G17 (convert_cycle_g74_g84 passes the plane's coordinates to
  // cycle_feed in another order), while LinuxCNC's own position stays the intended one.
  auto add = [&](MoveKind kind, double to_x, double to_y, double to_z, bool swapped = false) {
    Move m = new_move(line, f);
    m.kind = kind;
    m.start = tool;
    m.end = position_;
    m.end[a] = to_x;
    m.end[b] = to_y;
    m.end[n] = to_z;
    position_ = m.end;
    if (swapped && plane_ == G_18) {
      m.end[0] = to_z;
      m.end[1] = to_x;
      m.end[2] = to_y;
    } else if (swapped && plane_ == G_19) {
      m.end[0] = to_y;
      m.end[1] = to_z;
      m.end[2] = to_x;
    }
    effect.moves.push_back(m);
    tool = m.end;
  };
  // What the cycle does between two moves, as G-code written after the last move.
  auto then = [&](std::string codes) { effect.after_moves.push_back({effect.moves.size() - 1, std::move(codes)}); };
  auto dwell = [&](double seconds) { then("G4 P" + gcode_number_text(seconds) + "\n"); };
  const char* spindle_on = spindle_clockwise_ ? "M3\n" : "M4\n";
  const char* spindle_reversed = spindle_clockwise_ ? "M4\n" : "M3\n";

  if (old_z < r) {  // below the R plane: straight up to it first
    add(MoveKind::Rapid, position_[a], position_[b], r);
    old_z = r;
    current_z = r;
  }
  const double clear = retract_to_r_ ? r : old_z;
  const double peck_clearance = kPeckClearance_inch * kInch;  // the same in G20 and G21
  const bool pecking = code == G_73 || code == G_83;
  const double moves = repeats * (4.0 + (pecking ? 3.0 * std::ceil((r - bottom) / cycle_q_) : 0.0));
  if (!(moves <= kMostCycleMoves))
    fail("this block would make " + gcode_number_text(moves) + " moves (" +
         (pecking ? "(R - bottom) / Q pecks of 3 moves" : std::string("4 moves")) + " x L " + std::to_string(repeats) +
         "); more than " + gcode_number_text(kMostCycleMoves) + " are refused");
  for (int k = repeats; k > 0; --k) {
    x += dx;
    y += dy;
    if ((dr != 0 || dt != 0) && x == 0 && y == 0) fail("LinuxCNC refuses G91 polar coordinates at the origin");
    if (dr != 0 || dt != 0) {
      const double radius = std::hypot(x, y) + dr, angle = std::atan2(y, x) + dt;
      x = radius * std::cos(angle);
      y = radius * std::sin(angle);
    }
    if (k == repeats && current_z > r) {
      add(MoveKind::Rapid, x, y, current_z);
      add(MoveKind::Rapid, x, y, r);
    } else {
      add(MoveKind::Rapid, x, y, clear);
      if (clear > r) add(MoveKind::Rapid, x, y, r);
    }
    switch (code) {
      case G_81:
        add(MoveKind::Line, x, y, bottom);
        add(MoveKind::Rapid, x, y, clear);
        break;
      case G_82:
        add(MoveKind::Line, x, y, bottom);
        dwell(cycle_p_);
        add(MoveKind::Rapid, x, y, clear);
        break;
      case G_73:
      case G_83:
        for (double depth = r - cycle_q_; depth > bottom; depth -= cycle_q_) {
          if (depth - cycle_q_ == depth) fail("Q is below the resolution of the heights it pecks between");
          add(MoveKind::Line, x, y, depth);
          if (code == G_83) add(MoveKind::Rapid, x, y, r);
          add(MoveKind::Rapid, x, y, depth + peck_clearance);
        }
        add(MoveKind::Line, x, y, bottom);
        add(MoveKind::Rapid, x, y, clear);
        break;
      case G_85:
        add(MoveKind::Line, x, y, bottom);
        add(MoveKind::Line, x, y, r);
        add(MoveKind::Rapid, x, y, clear);
        break;
      case G_89:
        add(MoveKind::Line, x, y, bottom);
        dwell(cycle_p_);
        add(MoveKind::Line, x, y, clear);
        break;
      case G_74:
      case G_84:  // tapping: overrides off, in, reverse, dwell, out, forward, overrides back
        then("M50 P0\nM51 P0\n");
        add(MoveKind::Line, x, y, bottom, true);
        then(std::string("M5\n") + spindle_reversed);
        dwell(cycle_p_);
        add(MoveKind::Line, x, y, clear, true);
        then(std::string("M5\n") + spindle_on + (feed_override_ ? "M50 P1\n" : "") +
             (spindle_override_ ? "M51 P1\n" : ""));
        break;
      case G_86:  // boring: in, dwell, spindle stop, rapid out, spindle on
        add(MoveKind::Line, x, y, bottom);
        dwell(cycle_p_);
        then("M5\n");
        add(MoveKind::Rapid, x, y, clear);
        then(spindle_on);
        break;
      case G_88:  // boring, manual retract: in, dwell, spindle stop, program stop, spindle on
        add(MoveKind::Line, x, y, bottom);
        dwell(cycle_p_);
        then(std::string("M5\nM0\n") + spindle_on);
        break;
    }
  }
  known_ |= 1u << a | 1u << b | 1u << n;
  if (tool != position_) tool_elsewhere_ = f.world(tool);

  // Written as plain moves in exact path mode, then the mode the program was in.
  effect.translate = true;
  effect.exact_path = path_mode_ != G_61;
  effect.restore_path_mode = path_mode_;
  effect.restore_path_p_mm = path_p_;
  for (char c : {'X', 'Y', 'Z', 'R', 'P', 'Q', 'L', '@', '^'})
    if (w.has(c)) effect.motion_words.push_back(w[c].index);
  if (word) effect.motion_code_word = word->index;
}

}  // namespace vc::interpreter
