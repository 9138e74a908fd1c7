// Splines (G5 cubic, G5.1 quadratic) and NURBS (G5.2 control points, G5.3 end), turned into
// the arcs and lines LinuxCNC 2.9 moves along, so that each can be corrected.
//
// LinuxCNC's interpreter only collects control points (interp_convert.cc: convert_spline for
// G5 and G5.1, convert_nurbs for G5.2 and G5.3; the word rules of interp_check.cc) and hands
// them to the canon's NURBS_FEED. The task's canon (emccanon.cc: NURBS_FEED, biarc, arc, with
// nurbs_additional_functions.cc: knot_vector_creator, Nmix, Rden, nurbs_point, nurbs_tangent)
// makes the motion: it samples the curve at 4 points per control point (equal steps of the
// curve's parameter) with the curve's direction there (a central difference), and joins each
// pair of samples by a biarc, two arcs meeting with a common tangent; an arc too flat to
// compute (|2 chord x tangent| <= 1e-6 program units) is a straight line. The same arithmetic
// is done here, in program units and in LinuxCNC's order of operations, so that the moves are
// LinuxCNC's to rounding; the current X Y they start from are LinuxCNC's own numbers in program
// units where the interpreter has them (program_xy), as the biarcs can magnify a last-bit
// difference. One departure: an arc of radius under 0.0013 mm, which a G2/G3 cannot have
// (LinuxCNC refuses a radius under 0.00127 mm), is written as chords on it. (The standalone
// rs274 prints only "NURBS_FEED(n, ...)": its canon does not move; tests/acceptance/README.md
// says how the corpus compares these.)
//
// What LinuxCNC 2.9 does that is easy to miss, and is done here too:
// - G5 and G5.1 leave the motion mode as it was (after "G1 ... G5.1 ...", axis words alone
//   are G1 again); G5.2 is a mode; after G5.3 there is no motion mode at all.
// - G5's first control point is the start plus I J, or without I J the mirror of the last G5's
//   second one (start - last P Q, as the numbers were written, whatever the units since).
// - G5.2 points are taken as written (in G91 relative to the curve's start, not to the last
//   point); Z, A, B, C on a G5.2 line are ignored; a missing P on the first point is weight -1.
// - The curve is drawn at G5.3 from the first point, the position when the first G5.2 came.
#include <algorithm>
#include <cmath>

#include "words.hpp"

namespace vc::interpreter {
namespace {

struct PlanePoint {
  double x, y;
};

// A piece that is an arc of radius under this is written as chords (see curve_moves).
constexpr double kSmallestArc_mm = 0.0013;
constexpr double kChordAngle_rad = 0.15;
constexpr int kLargestOrder = 64;  // G5.2 L

// LinuxCNC's unit(): the vector scaled to length 1 (a zero vector stays zero).
PlanePoint unit(PlanePoint p) {
  const double h = std::hypot(p.x, p.y);
  if (h != 0) {
    p.x /= h;
    p.y /= h;
  }
  return p;
}

// A rational B-spline (NURBS) of `order` (degree + 1) through n + 1 weighted control points,
// on LinuxCNC's knot vector: `order` zeros, then 1, 2, ... n - order + 1, then n - order + 2
// `order` times. The parameter u runs from 0 to u_max() = n - order + 2.
class Nurbs {
 public:
  Nurbs(const std::vector<ControlPoint>& points, unsigned order) : points_(points), order_(order) {
    const unsigned n = static_cast<unsigned>(points.size()) - 1;
    for (unsigned i = 0; i <= n + order; ++i)
      knots_.push_back(i < order ? 0.0
                       : i <= n  ? static_cast<double>(i - order + 1)
                                 : static_cast<double>(n - order + 2));
    u_max_ = static_cast<double>(n - order + 2);
    basis_.resize(knots_.size());
  }
  double u_max() const { return u_max_; }

  // The point at u: sum of point * basis * weight / (sum of basis * weight), term by term as
  // LinuxCNC adds them. Not finite where the weights cancel.
  PlanePoint point(double u) const {
    std::size_t first = 0, last = 0;
    basis(u, first, last);
    double denominator = 0.0;
    for (std::size_t i = first; i < last; ++i) denominator = denominator + basis_[i] * points_[i].weight;
    if (denominator == 0.0) return {NAN, NAN};  // (LinuxCNC: 0/0 in every term)
    PlanePoint p{0.0, 0.0};
    for (std::size_t i = first; i < last; ++i) {
      p.x = p.x + points_[i].x * basis_[i] * points_[i].weight / denominator;
      p.y = p.y + points_[i].y * basis_[i] * points_[i].weight / denominator;
    }
    return p;
  }

  // The direction at u: a central difference over +-1e-5 of u (one-sided at the ends), length 1.
  PlanePoint tangent(double u) const {
    constexpr double kStep = 1e-5;
    const double low = std::max(0.0, u - kStep), high = std::min(u_max_, u + kStep);
    const PlanePoint a = point(low), b = point(high);
    return unit({(b.x - a.x) / (high - low), (b.y - a.y) / (high - low)});
  }

 private:
  // basis_[i] = N(i, order) at u for i in [first, last), the functions that are not zero
  // there (the others are, and add nothing), by the Cox-de Boor recursion as LinuxCNC's Nmix
  // evaluates it: the first-order function of a knot span is 1 on it ends included (at a knot
  // two spans hold u), and a term over a span of zero length is left out.
  void basis(double u, std::size_t& first, std::size_t& last) const {
    const std::size_t spans = knots_.size() - 1;
    // First order: the spans [t_i, t_i+1] holding u (consecutive, as the knots never decrease).
    std::size_t low =
        static_cast<std::size_t>(std::lower_bound(knots_.begin() + 1, knots_.end(), u) - knots_.begin()) - 1;
    std::size_t high = static_cast<std::size_t>(std::upper_bound(knots_.begin(), knots_.end() - 1, u) - knots_.begin());
    if (high <= low) {  // u outside [0, u_max]: no function is not zero (LinuxCNC: 0/0)
      first = last = 0;
      return;
    }
    high = std::min(high, spans);
    // Order j's function i depends on order j - 1's i and i + 1: not zero for i in
    // [low - j + 1, high).
    const std::size_t start = low >= order_ - 1 ? low - (order_ - 1) : 0;
    for (std::size_t i = start; i < high; ++i) basis_[i] = i >= low ? 1.0 : 0.0;
    basis_[high] = 0.0;
    for (unsigned j = 2; j <= order_; ++j) {
      const std::size_t count = knots_.size() - j;  // functions of order j
      const std::size_t from = low >= j - 1 ? low - (j - 1) : 0;
      for (std::size_t i = std::max(from, start); i < std::min(high, count); ++i) {
        const double left = knots_[i + j - 1] - knots_[i], right = knots_[i + j] - knots_[i + 1];
        const double down = basis_[i], up = i + 1 < high ? basis_[i + 1] : 0.0;
        double value = 0.0;
        if (left == 0 && right != 0)
          value = ((knots_[i + j] - u) * up) / right;
        else if (right == 0 && left != 0)
          value = ((u - knots_[i]) * down) / left;
        else if (left != 0 && right != 0)
          value = ((u - knots_[i]) * down) / left + ((knots_[i + j] - u) * up) / right;
        basis_[i] = value;
      }
    }
    first = start;
    last = std::min(high, points_.size());
  }

  const std::vector<ControlPoint>& points_;
  unsigned order_;
  std::vector<double> knots_;
  double u_max_ = 0.0;
  mutable std::vector<double> basis_;
};

// One move of the curve: a straight line, or an arc about `center` (counterclockwise or not),
// to `end`; program units, in the XY plane.
struct CurvePiece {
  bool arc = false;
  bool counterclockwise = false;
  PlanePoint end{}, center{};
};

// LinuxCNC's arc(): from p0 with direction d to p1, the arc that leaves p0 along d, or a line
// where that arc is too flat (the test is in program units).
void arc_or_line(PlanePoint p0, PlanePoint p1, PlanePoint d, std::vector<CurvePiece>& out) {
  constexpr double kFlat = 0.000001;
  const double x = p1.x - p0.x, y = p1.y - p0.y;
  const double den = 2 * (y * d.x - x * d.y);
  CurvePiece piece;
  piece.end = p1;
  if (std::fabs(den) > kFlat) {
    const double r = -(x * x + y * y) / den;  // signed radius: < 0 turns counterclockwise
    const double i = d.y * r, j = -d.x * r;
    piece.arc = true;
    piece.center = {p0.x + i, p0.y + j};
    piece.counterclockwise = r < 0;
  }
  out.push_back(piece);
}

// LinuxCNC's biarc() (with its r = 1: both arcs' tangent lengths alike): from p0 leaving along
// ts to p4 arriving along te, through the point p2 where the two arcs meet. No move where the
// quadratic for the tangent length has no usable root (LinuxCNC makes none either).
void biarc(PlanePoint p0, PlanePoint ts, PlanePoint p4, PlanePoint te, std::vector<CurvePiece>& out) {
  ts = unit(ts);
  te = unit(te);
  const double vx = p0.x - p4.x, vy = p0.y - p4.y;
  const double c = vx * vx + vy * vy;
  const double b = 2 * (vx * (ts.x + te.x) + vy * (ts.y + te.y));
  const double a = 2 * (ts.x * te.x + ts.y * te.y - 1);
  const double discriminant = b * b - 4 * a * c;
  if (discriminant < 0) return;
  const double root = std::sqrt(discriminant);
  const double beta1 = (-b - root) / 2 / a, beta2 = (-b + root) / 2 / a;
  if (beta1 > 0 && beta2 > 0) return;
  const double beta = beta1 < beta2 ? beta2 : beta1;  // (LinuxCNC's max: NaN unless the second is greater)
  const double alpha = beta, sum = alpha + beta;
  const PlanePoint p1{p0.x + alpha * ts.x, p0.y + alpha * ts.y};
  const PlanePoint p3{p4.x - beta * te.x, p4.y - beta * te.y};
  const PlanePoint p2{(p1.x * beta + p3.x * alpha) / sum, (p1.y * beta + p3.y * alpha) / sum};
  const PlanePoint tm = unit({p3.x - p2.x, p3.y - p2.y});
  arc_or_line(p0, p2, ts, out);
  arc_or_line(p2, p4, tm, out);
}

// LinuxCNC's NURBS_FEED: the curve sampled at 4 points per control point, biarcs between.
std::vector<CurvePiece> nurbs_feed(const std::vector<ControlPoint>& points, unsigned order) {
  const Nurbs curve(points, order);
  const unsigned steps = static_cast<unsigned>(points.size()) * 4;
  std::vector<CurvePiece> pieces;
  PlanePoint p0 = curve.point(0), t0 = curve.tangent(0);
  for (unsigned i = 1; i <= steps; ++i) {
    const double u = curve.u_max() * i / steps;
    const PlanePoint p1 = curve.point(u), t1 = curve.tangent(u);
    biarc(p0, t0, p1, t1, pieces);
    p0 = p1;
    t0 = t1;
  }
  return pieces;
}

bool finite(const CurvePiece& p) {
  return std::isfinite(p.end.x) && std::isfinite(p.end.y) &&
         (!p.arc || (std::isfinite(p.center.x) && std::isfinite(p.center.y)));
}

}  // namespace

void Interpreter::spline_rules(const Words& w, int line) const {
  const Words::Code* code = w.motion_code();
  const Words::Code* nurbs_end = w.find_g({G_5_3});
  unsigned named = 0;
  for (int i = 0; i < kAxes; ++i)
    if (w.has(kAxisLetters[i])) named |= 1u << i;
  const bool modal_nurbs = !code && motion_ == G_5_2 && (named || w.polar()) &&
                           !w.find_g({G_10, G_28, G_30, G_52, G_92});  // (their axis words are theirs)
  const bool spline_code = code && is_spline(code->code);
  if (!spline_code && !nurbs_end && !modal_nurbs) return;
  const int at = spline_code ? code->offset : nurbs_end ? nurbs_end->offset : w.first_motion_offset();
  const std::string name = spline_code ? g_name(code->code) : nurbs_end ? "G5.3" : "G5.2";
  // Codes that do not go with them (LinuxCNC refuses them all).
  int motion_codes = 0;
  for (const Words::Code& c : w.g)
    if (c.code == G_0 || c.code == G_1 || c.code == G_2 || c.code == G_3 || is_spline(c.code) || is_cycle(c.code) ||
        c.code == G_80)
      ++motion_codes;
  if (motion_codes > 1) refuse(line, at, name + " with another motion code on the line (the same modal group)");
  if (nurbs_end && code && code->code != G_5_2)
    refuse(line, code->offset, "between G5.2 and G5.3 only more G5.2 codes are allowed (LinuxCNC)");
  if (const auto* other =
          w.find_g({G_4, G_10, G_28, G_28_1, G_30, G_30_1, G_43_1, G_52, G_53, G_92, G_92_1, G_92_2, G_92_3}))
    refuse(line, other->offset,
           g_name(other->code) + " on a line with " + name +
               (nurbs_end && other->code != G_43_1 ? " (the same modal group, LinuxCNC refuses it)"
                                                   : ": write it on a line of its own"));
  // Words the curve's moves, written on this line, would read as theirs: a P, Q or L of
  // another code (G64, M-codes) on a line whose moves may be G2/G3, a word only arcs take.
  const bool g5 = spline_code && code->code == G_5;
  const bool g52 = (spline_code && code->code == G_5_2) || modal_nurbs || (nurbs_end && (named || w.polar()));
  const bool p_own = g5 || g52, q_own = g5, l_own = g52;
  const bool p_other = w.find_g({G_64}) || w.find_m({M_19, M_50, M_51, M_52, M_53, M_62, M_63, M_64, M_65, M_66});
  const bool q_other = w.find_g({G_64}) || w.find_m({M_19, M_61, M_66, M_67, M_68});
  const bool l_other = w.find_m({M_66}) != nullptr;
  const auto shared = [&](char letter, bool own, bool other) {
    if (!w.has(letter) || (own && !other)) return;
    const std::string word(1, letter);
    if (own)
      refuse(line, w[letter].offset,
             word + " on this line is both " + name + "'s and another code's (LinuxCNC reads one " + word +
                 " for both): write that code on a line of its own");
    if (other)
      refuse(line, w[letter].offset,
             word + " on a line with " + name + ": the curve's moves, written on this line as " +
                 "G1/G2/G3, would read it as theirs; write the code that takes " + word + " on a line of its own");
    refuse(line, w[letter].offset, word + " word on a line with " + name + " (LinuxCNC refuses it: nothing uses it)");
  };
  shared('P', p_own, p_other);
  shared('Q', q_own, q_other);
  shared('L', l_own, l_other);
  for (char c : {'K', 'R'})
    if (w.has(c))
      refuse(line, w[c].offset, std::string(1, c) + " word on a line with " + name + " (LinuxCNC refuses it)");
  if (!spline_code || code->code == G_5_2)
    for (char c : {'I', 'J'})
      if (w.has(c))
        refuse(line, w[c].offset,
               std::string(1, c) + " word on a line with " + name +
                   " (LinuxCNC refuses it: only G5 "
                   "and G5.1 take I and J)");
}

void Interpreter::spline(const Words& w, int previous_motion, int line, Effect& effect) {
  const Words::Code* code = w.motion_code();
  unsigned named = 0;
  for (int i = 0; i < kAxes; ++i)
    if (w.has(kAxisLetters[i])) named |= 1u << i;
  // LinuxCNC's order: G5.3 (modal group 0) first, then the motion: the line's code, or with
  // axis words the mode the line started in.
  int mode_before = previous_motion;
  if (w.find_g({G_5_3})) {
    end_nurbs(w, previous_motion, line, effect);
    mode_before = -1;
  }
  const int motion = code ? code->code : (named || w.polar()) ? previous_motion : -1;
  if (!is_spline(motion)) return;
  cycle_start_z_known_ = false;  // LinuxCNC's cycle_il_flag: any motion that is not a cycle
  if (code) {
    if (effect.motion_code_word < 0)
      effect.motion_code_word = code->index;
    else
      effect.motion_words.push_back(code->index);  // (G5.3 G5.2: the G5.3 takes the moves' place)
  }
  effect.translate = true;
  if (motion == G_5_2) {
    nurbs_point(w, mode_before, line);
    for (char c : {'X', 'Y', 'Z', 'A', 'B', 'C', 'P', 'L'})
      if (w.has(c)) effect.motion_words.push_back(w[c].index);
    return;
  }
  if (!named && !w.polar())
    refuse(line, code->offset, g_name(motion) + " without axis words (LinuxCNC: all axes missing with motion code)");
  cubic_or_quadratic_spline(w, motion, line, effect);
  for (char c : {'X', 'Y', 'I', 'J', 'P', 'Q', '@', '^'})
    if (w.has(c) && (motion == G_5 || (c != 'P' && c != 'Q'))) effect.motion_words.push_back(w[c].index);
  motion_ = previous_motion;  // G5 and G5.1 leave the mode as it was (LinuxCNC sets none)
}

void Interpreter::spline_start_rules(int line, int offset, const std::string& what, bool nurbs) const {
  if (compensation_.on())
    refuse(line, offset,
           what +
               (nurbs ? " with cutter radius compensation on is not translated: LinuxCNC 2.9 does not "
                        "offset it"
                      : " with cutter radius compensation on (LinuxCNC refuses it)") +
               "; turn compensation off with G40");
  if (plane_ != G_17)
    refuse(line, offset,
           what + (nurbs ? " outside the XY plane (G17) is not translated: LinuxCNC 2.9 draws its X Y "
                           "as arcs of the active plane"
                         : " outside the XY plane (LinuxCNC: splines must be in the XY plane, G17)"));
  if (inverse_time_)
    refuse(line, offset,
           what +
               " in inverse time feed (G93) is not translated: LinuxCNC 2.9 gives the curve's "
               "pieces no time of their own (they run at the last feed rate set)");
  if (feed_ == 0.0) refuse(line, offset, what + " with zero feed rate" + (nurbs ? "" : " (LinuxCNC refuses it)"));
  if (tool_elsewhere_)
    refuse(line, offset,
           what +
               " where the tool is not at the programmed point (just after G40, or a G74/G84 outside "
               "G17): LinuxCNC would start the curve off it; move with G1 first");
  const unsigned needed = setup_.machine_axes;
  if ((known_ & needed) != needed) {
    std::string missing;
    for (int i = 0; i < kAxes; ++i)
      if ((needed >> i & 1u) && !(known_ >> i & 1u)) missing += kAxisLetters[i];
    refuse(line, offset,
           "cannot correct a " + what + " from an unknown position (" + missing +
               " not set yet): begin the program with a G0 or G53 move to every axis, or give the start "
               "position (volcomp predistort --start)");
  }
  require_known_offsets(line, offset);
}

void Interpreter::cubic_or_quadratic_spline(const Words& w, int code, int line, Effect& effect) {
  const auto* word = w.find_g({code});
  const int at = word ? word->offset : w.first_motion_offset();
  const std::string name = g_name(code);
  spline_start_rules(line, at, name + " spline", false);
  for (char c : {'Z', 'A', 'B', 'C'})
    if (w.has(c)) refuse(line, w[c].offset, "splines may not have motion in Z, A, B or C (LinuxCNC)");
  const double scale = inches_ ? kInch : 1.0;
  const auto [x0, y0] = program_xy();
  // The end: X Y (G90, G91) or polar, as for a line.
  for (char c : {'X', 'Y'})
    if (w.has(c) && !(setup_.machine_axes >> (c - 'X') & 1u))
      refuse(line, w[c].offset, std::string("this machine has no ") + c + " axis");
  double x_end = x0, y_end = y0;
  if (w.polar()) {
    polar_end_point(w, line, x_end, y_end);
    x_end /= scale;
    y_end /= scale;
  } else {
    if (w.has('X')) x_end = incremental_ ? x0 + w.get('X') : w.get('X');
    if (w.has('Y')) y_end = incremental_ ? y0 + w.get('Y') : w.get('Y');
  }
  std::vector<ControlPoint> points{{x0, y0, 1.0}};
  if (code == G_5_1) {
    if (!w.has('I') || !w.has('J')) refuse(line, at, "G5.1 needs both I and J (LinuxCNC)");
    points.push_back({x0 + w.get('I'), y0 + w.get('J'), 1.0});
  } else {
    if (w.has('I') != w.has('J'))
      refuse(line, w[w.has('I') ? 'I' : 'J'].offset, "G5 needs both I and J, or neither (LinuxCNC)");
    if (w.has('I'))
      points.push_back({x0 + w.get('I'), y0 + w.get('J'), 1.0});
    else
      points.push_back({x0 + spline_i_, y0 + spline_j_, 1.0});  // the last G5's P Q, mirrored
    if (!w.has('P') || !w.has('Q')) refuse(line, at, "G5 needs both P and Q (LinuxCNC)");
    points.push_back({x_end + w.get('P'), y_end + w.get('Q'), 1.0});
  }
  points.push_back({x_end, y_end, 1.0});
  if (!nurbs_points_.empty())
    refuse(line, at, name + " after G5.2 points no G5.3 ended: LinuxCNC 2.9 would draw them into this spline");
  curve_moves(points, code == G_5_1 ? 3 : 4, line, at, effect);
  if (code == G_5) {
    spline_i_ = -w.get('P');
    spline_j_ = -w.get('Q');
  }
  position_[0] = x_end * scale;
  position_[1] = y_end * scale;
  note_program_xy(x_end, y_end);
}

void Interpreter::nurbs_point(const Words& w, int mode_before, int line) {
  const auto* word = w.find_g({G_5_2});
  const int at = word ? word->offset : w.first_motion_offset();
  const bool x = w.has('X'), y = w.has('Y');
  const double p = w.has('P') ? w.get('P') : -1.0;  // (LinuxCNC's value for no P)
  if (x != y) refuse(line, w[x ? 'X' : 'Y'].offset, "a G5.2 control point needs both X and Y (LinuxCNC)");
  if (!x && p > 0 && !nurbs_points_.empty())
    refuse(line, w['P'].offset, "P without X and Y is the weight of the first G5.2 point only (LinuxCNC)");
  if (p <= 0 && !nurbs_points_.empty())
    refuse(line, w.has('P') ? w['P'].offset : at, "every G5.2 control point needs a positive weight P (LinuxCNC)");
  if (w.polar())
    refuse(line, w[w.has('@') ? '@' : '^'].offset,
           "polar coordinates with G5.2: LinuxCNC takes control points from X and Y only");
  if (compensation_.on())
    refuse(line, at, "G5.2 with cutter radius compensation on is not translated: LinuxCNC 2.9 does not offset a NURBS");
  if (inverse_time_)
    refuse(line, at,
           "G5.2 in inverse time feed (G93) is not translated: LinuxCNC 2.9 gives the curve's pieces no time of "
           "their own (they run at the last feed rate set)");
  if (feed_ == 0.0) refuse(line, at, "a NURBS with zero feed rate (LinuxCNC refuses it)");
  int order = -1;
  if (w.has('L')) {
    const double l = w.get('L'), nearest = std::round(l);
    if (std::abs(l - nearest) > 0.0001 || nearest < 0)
      refuse(line, w['L'].offset, "L (the NURBS's order) must be a whole number >= 0 (LinuxCNC)");
    if (nearest > kLargestOrder)
      refuse(line, w['L'].offset,
             "a NURBS of order L above " + std::to_string(kLargestOrder) +
                 " is not translated (LinuxCNC's own evaluation takes a time growing as 2^L)");
    order = static_cast<int>(nearest);
  }
  for (char c : {'X', 'Y'})
    if (w.has(c) && !(setup_.machine_axes >> (c - 'X') & 1u))
      refuse(line, w[c].offset, std::string("this machine has no ") + c + " axis");
  const auto [x0, y0] = program_xy();
  if (mode_before != G_5_2) nurbs_points_.clear();
  if (nurbs_points_.empty()) {  // the first point: where the curve starts
    nurbs_points_.push_back({x0, y0, !x && p > 0 ? p : 1.0});
    nurbs_order_ = 3;
  }
  if (order > 3) nurbs_order_ = static_cast<unsigned>(order);
  if (x) {
    const double px = incremental_ ? x0 + w.get('X') : w.get('X');
    const double py = incremental_ ? y0 + w.get('Y') : w.get('Y');
    nurbs_points_.push_back({px, py, p});
  }
  motion_ = G_5_2;
}

void Interpreter::end_nurbs(const Words& w, int previous_motion, int line, Effect& effect) {
  const Words::Code& word = *w.find_g({G_5_3});
  const int at = word.offset;
  if (previous_motion != G_5_2) refuse(line, at, "G5.3 without G5.2 first (LinuxCNC refuses it)");
  if (nurbs_points_.size() < nurbs_order_)
    refuse(line, at,
           "a NURBS of order L = " + std::to_string(nurbs_order_) + " needs at least " + std::to_string(nurbs_order_) +
               " control points, the start included; this one has " + std::to_string(nurbs_points_.size()) +
               " (LinuxCNC refuses it)");
  spline_start_rules(line, at, "NURBS", true);
  // LinuxCNC draws the curve from where the machine is, through the first point: the two
  // differ if the position, the coordinate system or the units changed since the first G5.2.
  const double scale = inches_ ? kInch : 1.0;
  const ControlPoint& first = nurbs_points_.front();
  const auto [x0, y0] = program_xy();
  if (std::abs(first.x - x0) > 1e-9 || std::abs(first.y - y0) > 1e-9)
    refuse(line, at,
           "the NURBS's first point is no longer where the tool is (the position, coordinate system or "
           "units changed since the first G5.2): LinuxCNC 2.9 would draw the curve off it");
  effect.translate = true;
  effect.motion_code_word = word.index;
  curve_moves(nurbs_points_, nurbs_order_, line, at, effect);
  position_[0] = nurbs_points_.back().x * scale;
  position_[1] = nurbs_points_.back().y * scale;
  note_program_xy(nurbs_points_.back().x, nurbs_points_.back().y);
  nurbs_points_.clear();
  motion_ = -1;  // no motion mode (LinuxCNC)
}

void Interpreter::curve_moves(const std::vector<ControlPoint>& points, unsigned order, int line, int offset,
                              Effect& effect) {
  const std::vector<CurvePiece> pieces = nurbs_feed(points, order);
  for (const CurvePiece& p : pieces)
    if (!finite(p))
      refuse(line, offset,
             "LinuxCNC 2.9's arcs for this curve are not finite numbers (a piece of it is straight, of "
             "zero length, or its weights cancel): write that part with G1");
  if (pieces.empty()) refuse(line, offset, "LinuxCNC 2.9 makes no move for this curve");
  const double scale = inches_ ? kInch : 1.0;
  const Frame f = frame();
  Position at = position_;
  for (const CurvePiece& p : pieces) {
    Move m = new_move(line, f);
    m.start = at;
    m.end = at;
    m.end[0] = p.end.x * scale;
    m.end[1] = p.end.y * scale;
    if (p.arc) {
      m.kind = MoveKind::Arc;
      Arc& arc = m.arc;
      arc.first = 0;
      arc.second = 1;
      arc.normal = 2;
      arc.center_first = p.center.x * scale;
      arc.center_second = p.center.y * scale;
      arc.clockwise = !p.counterclockwise;
      arc.turns = 1;
      arc.sweep_rad =
          arc_sweep(std::atan2(m.start[1] - arc.center_second, m.start[0] - arc.center_first),
                    std::atan2(m.end[1] - arc.center_second, m.end[0] - arc.center_first), arc.clockwise, 1);
      const double radius = std::min(std::hypot(m.start[0] - arc.center_first, m.start[1] - arc.center_second),
                                     std::hypot(m.end[0] - arc.center_first, m.end[1] - arc.center_second));
      if (radius < kSmallestArc_mm) {
        // LinuxCNC's canon moves along it, but a G2/G3 so small is refused ("zero-radius arc",
        // under RADIUS_TOLERANCE, 0.00127 mm): written as chords, each over at most
        // kChordAngle_rad of it (within 0.3 % of its radius and length).
        const int chords = std::max(1, static_cast<int>(std::ceil(std::abs(arc.sweep_rad) / kChordAngle_rad)));
        for (int k = 1; k <= chords; ++k) {
          Move chord = m;
          chord.kind = MoveKind::Line;
          chord.start = at;
          chord.end = k == chords ? m.end : point_at(m, static_cast<double>(k) / chords);
          effect.moves.push_back(chord);
          at = chord.end;
        }
        continue;
      }
    } else {
      m.kind = MoveKind::Line;
    }
    effect.moves.push_back(m);
    at = m.end;
  }
}

}  // namespace vc::interpreter
