// Lathe cycles G70 (finishing), G71 (turning) and G72 (facing), with .1 (no pockets) and .2
// (pockets only), as LinuxCNC runs them (interp_g7x.cc, convert_g7x; the version: lathe_passes.cpp):
// 1. the cycle's line: a rapid to its X Z (absolute, the current point for a missing one);
// 2. the subroutine Q is read, not run: its lines' G0/G1/G2/G3 with X Z (or U W increments),
//    I K or R, and A (fillet) or C (chamfer) at the corner after a move draw the profile; their
//    parameter assignments and control flow take effect, nothing else does (F, S, M, other G
//    codes are ignored, as LinuxCNC ignores them); #<_x> #<_z> read the profile's point;
// 3. the passes (lathe_passes.cpp) written as G0/G1/G2/G3 moves of the cycle's line, each
//    corrected like any other move; the motion mode is the last move's after it.
// D: allowance (G70: of the first pass, E of the last, P passes), I: depth of cut, R: retract,
// U W: a shift of the roughing profile; all in program units.
#include <cmath>

#include "lathe_cycle.hpp"
#include "words.hpp"

namespace vc::interpreter {

using lathe::Point;
using lathe::Segment;

namespace {

constexpr long kMoveLimit = 200'000;  // a cycle's moves (a fine real one makes a few thousand)

class MovesOfTheCycle final : public lathe::PassWriter {
 public:
  explicit MovesOfTheCycle(std::function<void(int, Point, Point)> add) : add_(std::move(add)) {}
  void rapid(Point end) override { add(0, end, {}); }
  void line(Point end) override { add(10, end, {}); }
  void arc(bool ccw, Point center, Point end) override { add(ccw ? G_3 : G_2, end, center); }

 private:
  void add(int code, Point end, Point center) {
    if (++count_ > kMoveLimit)
      throw lathe::CycleError(
          "more than " + std::to_string(kMoveLimit) +
          " moves: the depth of cut (I) is too small for the profile, or LinuxCNC loops forever on it");
    add_(code, end, center);
  }
  std::function<void(int, Point, Point)> add_;
  long count_ = 0;
};

}  // namespace

void Interpreter::lathe_cycle(const Words& w, int line, Effect& effect) {
  const Words::Code* word = w.find_g({G_70, G_71, G_71_1, G_71_2, G_72, G_72_1, G_72_2});
  const int code = motion_;
  const int at = word ? word->offset : w.first_motion_offset();
  auto fail = [&](const std::string& why) { refuse(line, at, g_name(code) + ": " + why); };
  if (!word) fail("a lathe cycle runs on the line that names it (G70-G72 are not modal)");
  if (!w.has('Q')) fail("G7x.x requires a Q word (the subroutine that draws the profile)");
  if (compensation_.on())
    fail(code == G_70 ? "G70 with cutter compensation on is not translated: this LinuxCNC (Debian 12's 2.9.0~pre1) "
                        "compensates the approach rapids too and makes a stray rapid move (fixed in LinuxCNC 2.9.3); "
                        "cut the finishing pass with G40, or write it out with G41/G42"
                      : "LinuxCNC refuses this cycle with cutter compensation on");
  if (plane_ != G_18) fail("LinuxCNC runs the lathe cycles in the XZ plane (G18) only");
  if (incremental_)
    fail(
        "in incremental mode (G91) LinuxCNC's rapid to the cycle's start reads X Z as absolute: not translated; "
        "program the cycle in G90");
  for (char c : {'Y', 'A', 'B', 'C', 'J', 'K', 'L', '@', '^'})
    if (w.has(c)) refuse(line, w[c].offset, std::string("the lathe cycles take no ") + c + " word here");
  if ((known_ & setup_.machine_axes) != setup_.machine_axes)
    fail("a lathe cycle from an unknown position: begin the program with a G0 to every axis, or --start");
  if (!offsets_known_ && !(offsets_set_ >> coordinate_system_ & 1u))
    fail("the work offset is not known: pass --var FILE (LinuxCNC's parameter file) or set it with G10 L2");
  const double q = w.get('Q');
  if (q != std::floor(q) || q < 0 || q > 1e9) refuse(line, w['Q'].offset, "Q must be the O number of a subroutine");

  const double scale = inches_ ? kInch : 1.0;
  auto c = std::make_unique<LatheCycle>();
  c->code = code;
  c->line = line;
  c->offset = at;
  const double x = w.has('X') ? w.get('X') : position_[0] / scale;
  const double z = w.has('Z') ? w.get('Z') : position_[2] / scale;
  c->from = Point(z, x);
  for (auto [letter, value] :
       {std::pair{'D', &c->d}, {'E', &c->e}, {'I', &c->i}, {'P', &c->p}, {'R', &c->r}, {'U', &c->u}, {'W', &c->w}})
    if (w.has(letter)) *value = w.get(letter);
  if (c->i <= 0) refuse(line, w['I'].offset, "G7X error: I must be greater than zero");
  if (code == G_70 && (c->p < 1 || c->p > 1000)) refuse(line, w['P'].offset, "G70: P (passes) must be 1..1000");

  lathe_ = std::move(c);
  lathe_move(0, lathe_->from, {}, line, at, effect);  // the rapid to X Z
  lathe_->at = lathe_->from;
  lathe_->start = position_;
  for (char letter : {'X', 'Z', 'D', 'E', 'I', 'P', 'Q', 'R', 'U', 'W'})
    if (w.has(letter)) effect.motion_words.push_back(w[letter].index);
  effect.motion_code_word = word->index;
  effect.profile_subroutine = std::to_string(static_cast<long>(q));
}

void Interpreter::profile_block(const gcode::Block& block, int line) {
  LatheCycle& c = *lathe_;
  const Words w = evaluate(block, line);
  assign(block, line);
  auto fail = [&](char letter, const std::string& why) {
    refuse(line, w.has(letter) ? w[letter].offset : 0, "G7X error: " + why);
  };
  if (const auto* g = w.find_g({G_0,   G_1,   G_2,  G_3,  G_33, G_33_1, G_38_2, G_38_3, G_38_4, G_38_5, G_5,
                                G_5_1, G_5_2, G_73, G_74, G_76, G_80,   G_81,   G_82,   G_83,   G_84,   G_85,
                                G_86,  G_87,  G_88, G_89, G_70, G_71,   G_71_1, G_71_2, G_72,   G_72_1, G_72_2}))
    motion_ = g->code;
  Point end = c.at;
  if (w.has('U')) {
    if (w.has('X')) fail('U', "Cannot use U and X in the same block");
    end.imag(end.imag() + w.get('U'));
  } else if (w.has('X')) {
    end.imag(w.get('X'));
  }
  if (w.has('W')) {
    if (w.has('Z')) fail('W', "Cannot use W and Z in the same block");
    end.real(end.real() + w.get('W'));
  } else if (w.has('Z')) {
    end.real(w.get('Z'));
  }
  if (end == c.at) return;  // no move: nothing else on the line counts
  const bool straight = motion_ == G_0 || motion_ == G_1, round = motion_ == G_2 || motion_ == G_3;
  if (straight) {
    c.profile.push_back(Segment::line(c.at, end));
  } else if (round) {
    Point center(w.has('K') ? w.get('K') : 0.0, w.has('I') ? w.get('I') : 0.0);
    if (w.has('R')) {
      if (w.has('I') || w.has('K')) fail('R', "both R and I or K flag used for arc");
      const double r = w.get('R'), chord2 = std::norm(end - c.at);
      if (r * r < chord2 / 4) fail('R', "the radius R is shorter than half the chord");
      const Point d = Point(0, 1) * std::sqrt((r * r - chord2 / 4) / chord2) * (end - c.at);
      center = (c.at + end) / 2.0 + (motion_ == G_3 ? d : -d);
    } else {
      if (!w.has('I') && !w.has('K')) fail('X', "either I or K must be present for arc");
      if (!arc_absolute_) center += c.at;
    }
    c.profile.push_back(Segment::arc(motion_ == G_3, c.at, center, end));
  }
  if (straight || round) {
    if (w.has('A') && w.has('C')) fail('A', "Both A and C parameters on a corner");
    for (char letter : {'A', 'C'})
      if (w.has(letter)) {
        Segment corner{
            letter == 'A' ? Segment::Kind::Fillet : Segment::Kind::Chamfer, end, end, end, false, w.get(letter)};
        c.profile.push_back(corner);
      }
  }
  c.at = end;
  const double scale = inches_ ? kInch : 1.0;
  position_[0] = end.imag() * scale;  // #<_x> and #<_z> read the profile's point, as in LinuxCNC
  position_[2] = end.real() * scale;
}

void Interpreter::finish_lathe_cycle(Effect& effect) {
  const LatheCycle& c = *lathe_;
  position_ = c.start;
  const int line = c.line;
  auto fail = [&](const std::string& why) { refuse(line, c.offset, g_name(c.code) + ": " + why); };
  if (c.profile.size() <= 1)
    fail("the profile (subroutine " + effect.profile_subroutine +
         ") has fewer than two segments: LinuxCNC then cuts nothing and loses track of where the tool is");
  MovesOfTheCycle out([&](int code, Point to, Point center) { lathe_move(code, to, center, line, c.offset, effect); });
  try {
    if (c.code == G_70)
      lathe::finishing_passes(c.profile, c.from, c.d, c.e, c.p, out);
    else
      lathe::roughing_passes(c.profile, c.code / 10 == 72, c.code % 10, c.from, Point(c.w, c.u), c.d, c.i, c.r, out);
  } catch (const lathe::CycleError& e) {
    fail(std::string("G7X error: ") + e.what());
  }
  lathe_.reset();
}

void Interpreter::lathe_move(int code, Point end, Point center, int line, int offset, Effect& effect) {
  const double scale = inches_ ? kInch : 1.0;
  // LinuxCNC leaves out an arc that ends where it starts (within its TOLERANCE_EQUAL).
  if ((code == G_2 || code == G_3) && std::abs(position_[0] / scale - end.imag()) < 1e-6 &&
      std::abs(position_[2] / scale - end.real()) < 1e-6)
    return;
  Words w;
  auto set = [&](char letter, double value) { w.letters[Words::slot(letter)] = {true, value, -1, offset}; };
  set('X', end.imag());
  set('Z', end.real());
  if (code == G_2 || code == G_3) {
    set('I', center.imag());
    set('K', center.real());
  }
  // The cycle's moves are absolute, their centres too (LinuxCNC's switch_settings).
  const bool incremental = incremental_, arc_absolute = arc_absolute_;
  incremental_ = false;
  arc_absolute_ = true;
  motion_ = code;
  move(w, line, effect);
  incremental_ = incremental;
  arc_absolute_ = arc_absolute;
}

}  // namespace vc::interpreter
