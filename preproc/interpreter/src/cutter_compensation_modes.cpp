// Cutter compensation in the interpreter: G40, G41/G42 (radius from the tool table's diameter)
// and G41.1/G42.1 (diameter in D), LinuxCNC's convert_cutter_compensation_on/off; what LinuxCNC
// refuses while compensation is on; and the compensated moves, whose geometry is
// CutterCompensation's (cutter_compensation.cpp).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>

#include "words.hpp"

namespace vc::interpreter {
namespace {

// (MSG,...), (DEBUG,...), (PRINT,...): LinuxCNC shows them at once, not in its move queue.
bool is_message(const std::string& text) {
  std::string head;
  for (char c : text) {
    if (head.empty() && std::isspace(static_cast<unsigned char>(c))) continue;
    head += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (head.size() == 6) break;
  }
  return head.rfind("msg,", 0) == 0 || head.rfind("debug,", 0) == 0 || head.rfind("print,", 0) == 0;
}

}  // namespace

void Interpreter::compensation_rules(const gcode::Block& block, const Words& w, int line) const {
  const auto is_frame_or_cycle = [](int g) {
    return g == G_10 || g == G_28 || g == G_30 || g == G_28_1 || g == G_30_1 || g == G_52 ||
           (g >= G_92 && g <= G_92_3) || (g >= G_54 && g <= G_59_3) || g == G_43 || g == G_43_1 || g == G_49 ||
           g == G_53 || is_cycle(g);
  };
  if (!compensation_.on()) return;
  for (const Words::Code& c : w.g) {
    const int g = c.code;
    std::string what;
    if (g == G_41 || g == G_41_1 || g == G_42 || g == G_42_1)
      what = "turn cutter radius compensation on when it is on";
    else if (is_frame_or_cycle(g))
      what = "use " + g_name(g);
    else if ((g == G_17 || g == G_18 || g == G_19) && g != plane_)
      what = "change the plane";
    else if ((g == G_20 && !inches_) || (g == G_21 && inches_))
      what = "change units";
    if (!what.empty())
      refuse(line, c.offset, "cannot " + what + " with cutter radius compensation on (turn it off with G40)");
  }
  if (const auto* m = w.find_m({M_6, M_61}))
    refuse(line, m->offset, "cannot change tools with cutter radius compensation on (turn it off with G40)");
  if (const auto* m = w.find_m({M_70, M_71, M_72, M_73}))
    refuse(line, m->offset, "M70-M73 with cutter radius compensation on are not translated (turn it off with G40)");
  if (!compensation_.holding()) return;
  // LinuxCNC runs a T word and shows a message before the move it holds back: written after
  // that move, they would come later.
  if (w.has('T'))
    refuse(line, w['T'].offset,
           "a T word while cutter compensation holds a move back: LinuxCNC selects the tool "
           "before that move; select it before G41/G42 or after G40");
  for (const gcode::Comment& c : block.comments)
    if (is_message(c.text))
      refuse(line, c.begin,
             "a message while cutter compensation holds a move back: LinuxCNC shows it before that "
             "move; show it before G41/G42 or after G40");
}

Position Interpreter::take_move_start(const Frame& in, const Position& otherwise) {
  if (!tool_elsewhere_) return otherwise;
  const Position start = in.program(*tool_elsewhere_);
  tool_elsewhere_.reset();
  return start;
}

void Interpreter::take_released(std::vector<ReleasedMove>& out, Effect& effect) {
  for (ReleasedMove& r : out) {
    if (r.move.compensated_rate_mm_per_min > 0.0)  // G93: the move's own inverse time
      r.move.feed = inverse_time_feed(r.move);
    if (r.sequence == sequence_)
      effect.moves.push_back(r.move);
    else
      released_.push_back(r);
  }
  out.clear();
}

void Interpreter::set_compensation(const Words& w, int line, Effect& effect) {
  const Words::Code* c = w.find_g({G_40, G_41, G_41_1, G_42, G_42_1});
  if (!c) {
    if (w.has('D') && !w.find_g({G_70, G_71, G_71_1, G_71_2, G_72, G_72_1, G_72_2}))  // (a lathe cycle's allowance)
      refuse(line, w['D'].offset, "D word without G41, G42, G41.1, G42.1 or G70-G72");
    return;
  }
  for (char letter : {'D', 'L'})
    if (w.has(letter)) effect.dropped_words.push_back(w[letter].index);
  if (c->code != G_40) effect.dropped_words.push_back(c->index);  // the output is offset already
  if (c->code == G_40) {
    const bool moved = compensation_.offsets() && !compensation_.first_move();
    compensating(line, c->offset, effect, [&] { compensation_.stop(own_); });
    if (moved) {
      // LinuxCNC takes the programmed point as its position again; the tool stays at the offset one.
      tool_elsewhere_ = frame().world(compensation_.tool());
      arc_not_allowed_ = true;
    }
    return;
  }
  if (plane_ != G_17 && plane_ != G_18)
    refuse(line, c->offset, "cutter radius compensation is only possible in the XY (G17) or XZ (G18) plane");
  const auto side = c->code == G_41 || c->code == G_41_1 ? CutterCompensation::kLeft : CutterCompensation::kRight;
  double radius = 0.0;
  int orientation = 0;
  if (c->code == G_41_1 || c->code == G_42_1) {  // the diameter in D, in program units
    if (!w.has('D')) refuse(line, c->offset, g_name(c->code) + " needs D (the tool diameter)");
    radius = w.get('D') * (inches_ ? kInch : 1.0) / 2;
    if (w.has('L')) {
      if (plane_ != G_18) refuse(line, w['L'].offset, g_name(c->code) + " with L (lathe tool orientation) needs G18");
      orientation = w.whole('L');
      if (orientation < 0 || orientation > 9) refuse(line, w['L'].offset, "L (tool orientation) must be 0..9");
    }
  } else {  // the radius from the tool table: tool D, or the tool in the spindle
    int tool = tool_in_spindle_;
    if (w.has('D')) {
      const double d = w.get('D');
      const double nearest = std::floor(d + 0.5);  // LinuxCNC's is_near_int, without its int overflow
      if (std::abs(nearest - d) >= 0.0001)
        refuse(line, w['D'].offset, g_name(c->code) + " requires D word to be a whole number");
      if (nearest < 0) refuse(line, w['D'].offset, "negative D word (tool) with " + g_name(c->code));
      if (nearest > 1e6) refuse(line, w['D'].offset, "D word (tool number) with " + g_name(c->code) + " out of range");
      tool = static_cast<int>(nearest);
    } else if (tool < 0) {
      refuse(line, c->offset,
             g_name(c->code) +
                 " without D takes the radius of the tool in the spindle, and the program "
                 "has not loaded one (M6 or M61): give D (the tool number)");
    }
    if (tool > 0) {
      if (!tools_)
        refuse(line, c->offset,
               g_name(c->code) + " takes the tool's diameter from the tool table: pass --tool-table FILE");
      const auto entry = tools_->find(tool);
      if (entry == tools_->end())
        refuse(line, w.has('D') ? w['D'].offset : c->offset,
               "tool " + std::to_string(tool) + " is not in the tool table");
      radius = entry->second.diameter / 2;  // machine units: mm
    }
  }
  compensation_.start(side, radius, plane_, orientation, inches_);
}

double Interpreter::inverse_time_rate(const Move& programmed) const {
  // interp_inverse.cc inverse_time_rate_straight/_arc: length x F in program units, at least 0.1.
  const double unit = inches_ ? kInch : 1.0;
  return std::max(0.1, feed_length(programmed) / unit * programmed.feed) * unit;
}

void Interpreter::compensated_move(const Words& w, Move& m, int line, Effect& effect) {
  // The compensation works from the programmed start; the tool may be elsewhere (after G40).
  const Position tool_at = take_move_start(m.frame, m.start);
  if (inverse_time_ && m.kind != MoveKind::Rapid) {
    // LinuxCNC (interp_inverse.cc): the feed rate is the programmed move's length x F (the
    // first move's from where the tool is), whatever length the compensated path has.
    const bool from_tool = compensation_.first_move() || !compensation_.offsets();
    if (from_tool && compensation_.offsets() && m.kind == MoveKind::Arc)
      refuse(line, w.first_motion_offset(),
             "an arc as the first move under cutter compensation in inverse time (G93) is not translated");
    Move programmed = m;
    if (from_tool) programmed.start = tool_at;
    m.compensated_rate_mm_per_min = inverse_time_rate(programmed);
  }
  compensating(line, w.first_motion_offset(), effect, [&] {
    if (m.kind == MoveKind::Arc)
      compensation_.arc(m, m.start, tool_at, sequence_, own_);
    else
      compensation_.straight(m, m.start, tool_at, sequence_, own_);
  });
}

void Interpreter::compensating(int line, int offset, Effect& effect, const std::function<void()>& step) {
  try {
    step();
  } catch (const CompensationError& e) {  // a gouge found when a held move is made final
    own_.clear();
    refuse(line, offset, std::string(e.what()) + " (LinuxCNC refuses it too)");
  }
  take_released(own_, effect);
}

}  // namespace vc::interpreter
