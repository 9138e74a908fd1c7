// G70-G72 passes (see lathe_passes.hpp). The algorithm is LinuxCNC's (interp_g7x.cc), step for
// step, because its output is the reference, as of the LinuxCNC that Debian 12 packages
// (2.9.0~pre1, git f1270d6ed7, February 2023: the rs274 the tests compare with). Later 2.9
// releases (2023-10 to 2026) add a leadout back to the cycle's X (G71) or Z (G72) where the
// profile ends short of it, step past a segment whose end the cut has reached, and switch
// compensation off for G70's approach: a program that relies on those cuts differently
// there (preproc/predistort/README.md). The profile is reflected and turned until Z
// and X decrease along it; corners get their fillets and chamfers; the profile is offset by the
// allowance in steps no larger than half its shortest segment, arcs joining the pieces that
// part; then the roughing cuts dive to each depth step, cut across to the profile, escape
// diagonally by R and come back, climbing along the profile where it rises and recursing into
// the pockets it leaves. Where LinuxCNC would loop forever (tests/interp g71-endless-loop)
// the cycle is refused after a bounded number of steps.
#include "lathe_passes.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "vc/tables/number_text.hpp"

namespace vc::interpreter::lathe {
namespace {

constexpr double kTolerance = 1e-6;     // interp_g7x.cc's tolerance
constexpr long kStepLimit = 2'000'000;  // cuts and offset steps: beyond, LinuxCNC's endless loop
const Point kI{0.0, 1.0};

double cross(Point a, Point b) { return std::imag(std::conj(a) * b); }

// "(x,z)", as an ostream writes a std::complex.
std::string text(Point p) { return "(" + significant_text(p.real(), 6) + "," + significant_text(p.imag(), 6) + ")"; }

// --- one segment ---------------------------------------------------------------------------

double radius(const Segment& s) {
  return s.round() ? std::min(std::abs(s.start - s.end), std::abs(s.start - s.center)) : std::abs(s.start - s.end);
}

// Z decreases along it (and an arc stays on one side of its centre): the cuts can follow it.
bool monotonic(const Segment& s) {
  if (!s.round()) return std::real(s.end - s.start) <= 1e-3;
  if (s.corner != 0.0) return true;  // a fillet not made yet
  const double entry = std::imag(s.start - s.center), exit = std::imag(s.end - s.center);
  const double dz = std::real(s.end - s.start);
  return s.ccw ? entry >= -1e-3 && exit >= -1e-3 && dz <= -1e-3 : entry <= 1e-3 && exit <= 1e-3 && dz <= -1e-3;
}

void offset(Segment& s, double distance) {
  if (s.round()) {
    const double r = std::abs(s.start - s.center);
    const double factor = (r + (s.ccw ? 1.0 : -1.0) * distance) / r;
    s.start = factor * (s.start - s.center) + s.center;
    s.end = factor * (s.end - s.center) + s.center;
  } else {
    const Point d = kI * distance * (s.start - s.end) / std::abs(s.start - s.end);
    s.start += d;
    s.end += d;
  }
}

bool on_arc(const Segment& s, Point p) {
  const double from_start = cross(s.start - s.center, p - s.center), to_end = cross(s.end - s.center, p - s.center);
  return s.ccw ? from_start >= -kTolerance && to_end <= kTolerance : from_start <= kTolerance && to_end >= -kTolerance;
}

// The Z values where the segment crosses height x, in LinuxCNC's order.
std::vector<double> crossings(const Segment& s, double x) {
  std::vector<double> z;
  if (s.round()) {
    const double r = std::abs(s.start - s.center);
    double q = -(x - r - s.center.imag()) * (x + r - s.center.imag());
    if (q < -kTolerance) return z;
    q = std::sqrt(std::max(q, 0.0));
    if (const Point p(s.center.real() + q, x); on_arc(s, p)) z.push_back(p.real());
    if (const Point p(s.center.real() - q, x); on_arc(s, p)) z.push_back(p.real());
    return z;
  }
  if (std::min(s.start.imag(), s.end.imag()) > x + kTolerance ||
      std::max(s.start.imag(), s.end.imag()) < x - kTolerance)
    return z;
  if (std::abs(std::imag(s.start - s.end)) < kTolerance) {
    z.push_back(s.start.real());
    z.push_back(s.end.real());
  } else {
    z.push_back((x - s.start.imag()) / (s.end.imag() - s.start.imag()) * (s.end.real() - s.start.real()) +
                s.start.real());
  }
  return z;
}

// The highest point of an arc turning over its top (ccw, ending past the centre).
Point over_the_top(const Segment& s) {
  if (s.end.real() >= s.center.real()) return s.end;
  return {s.center.real(), s.center.imag() + std::abs(s.start - s.center)};
}

// Moves the end of `p` and the start of `n` (the next) onto their intersection.
void intersect(Segment& p, Segment& n) {
  if (!n.round() && !p.round()) {
    const Point rot = std::conj(n.start - n.end) / std::abs(n.start - n.end);
    const Point ps = (p.start - n.end) * rot, pe = (p.end - n.end) * rot;
    if (std::imag(ps - pe) == 0) throw CycleError("Cannot intersect parallel lines");
    const double f = std::imag(ps) / std::imag(ps - pe);
    n.start = p.end = (ps + f * (pe - ps)) / rot + n.end;
  } else if (!p.round() || !n.round()) {
    // A line and an arc: the line's foot of the arc's centre, +- along the line, nearest n's start.
    if (std::abs(n.start - p.end) < kTolerance) return;
    const Segment& straight = n.round() ? p : n;
    const Segment& arc = n.round() ? n : p;
    const Point rot = std::conj(straight.start - straight.end) / std::abs(straight.start - straight.end);
    const Point pe = (arc.end - straight.end) * rot, pc = (arc.center - straight.end) * rot;
    double b = std::norm(pc - pe) - std::imag(pc) * std::imag(pc);
    b = b < 0 ? 0 : std::sqrt(b);
    const Point s1 = (std::real(pc) + b) / rot + straight.end, s2 = (std::real(pc) - b) / rot + straight.end;
    n.start = p.end = std::abs(n.start - s1) < std::abs(n.start - s2) ? s1 : s2;
  } else {
    const double a = std::abs(n.start - n.center), b = std::abs(p.start - p.center), c = std::abs(n.center - p.center);
    const double cos_b = (c * c + a * a - b * b) / 2.0 / a / c;
    const double cos_b2 = std::min(cos_b * cos_b, 1.0);
    const Point rot(cos_b, std::sqrt(1 - cos_b2));
    p.end = n.start = rot * (p.center - n.center) / c * a + n.center;
  }
}

// A fillet or chamfer between `prev` and `next`: where the two, offset by its size, meet.
Point make_corner(Segment& corner, Segment& prev, Segment& next) {
  auto offset_pair = [&](Segment& p, Segment& n) {
    p = prev;
    n = next;
    offset(p, corner.corner);
    offset(n, corner.corner);
  };
  Segment p, n;
  offset_pair(p, n);
  if (std::real(p.end - n.start) > 1e-2) {
    corner.corner = -corner.corner;
    offset_pair(p, n);
  }
  if (std::real(p.end - n.start) > 1e-2) throw CycleError("Corner finish failed at " + text(prev.end));
  intersect(p, n);
  const Point center = (p.end + n.start) / 2.0;
  offset(p, -corner.corner);
  offset(n, -corner.corner);
  corner.start = prev.end = p.end;
  corner.end = next.start = n.start;
  return center;
}

// --- the profile's orientation ----------------------------------------------------------------
// Bit 0: Z reflected, bit 1: X reflected, bit 2: turned by -90 degrees (turned first).

void reflect_x(Segment& s) {
  s.start = std::conj(s.start);
  s.end = std::conj(s.end);
  s.center = std::conj(s.center);
  if (s.round()) s.ccw = !s.ccw;
}

void reflect_z(Segment& s) {
  s.start = -std::conj(s.start);
  s.end = -std::conj(s.end);
  s.center = -std::conj(s.center);
  if (s.round()) s.ccw = !s.ccw;
}

void turn(Segment& s) {
  s.start *= -kI;
  s.end *= -kI;
  s.center *= -kI;
}

// The passes of the folded profile, written in the program's orientation.
class Oriented {
 public:
  Oriented(PassWriter& out, int orientation) : out_(out), o_(orientation) {}
  void rapid(Point p) { out_.rapid(unfold(p)); }
  void line(Point p) { out_.line(unfold(p)); }
  void arc(bool ccw, Point center, Point end) {
    const bool mirrored = o_ == 1 || o_ == 2 || o_ == 5 || o_ == 6;
    out_.arc(mirrored ? !ccw : ccw, unfold(center), unfold(end));
  }
  void draw(const Segment& s) {
    if (s.round())
      arc(s.ccw, s.center, s.end);
    else
      line(s.end);
  }

 private:
  Point unfold(Point p) const {
    switch (o_) {
      case 1:
        return -std::conj(p);
      case 2:
        return std::conj(p);
      case 3:
        return -p;
      case 4:
        return kI * p;
      case 5:
        return std::conj(kI * p);
      case 6:
        return -std::conj(kI * p);
      case 7:
        return -kI * p;
      default:
        return p;
    }
  }
  PassWriter& out_;
  int o_;
};

// --- cutting along the profile ---------------------------------------------------------------

// Follows a rising segment from `at`; true if it does not rise (the climb ends here).
bool climb(const Segment& s, Point& at, Oriented& out) {
  if (!s.round()) {
    if (s.end.imag() + kTolerance < s.start.imag()) return true;
    if (std::abs(at - s.start) > kTolerance) throw CycleError("How did we get here?");
    out.line(s.end);
    at = s.end;
    return false;
  }
  if (!s.ccw) {
    if (at.real() > s.center.real()) return true;
    if (std::abs(at - s.end) > 1e-3) out.arc(s.ccw, s.center, s.end);
    at = s.end;
    return false;
  }
  if (at.real() < s.center.real()) return true;
  const Point top = over_the_top(s);
  if (std::abs(at - top) > 1e-3) out.arc(s.ccw, s.center, top);
  at = top;
  return true;
}

// After the first roughing pass of G7x.1: up the rising parts of the profile only.
void climb_only(const Segment& s, Point& at, Oriented& out) {
  if (!s.round() && s.end.imag() < s.start.imag()) return;
  const std::vector<double> z = crossings(s, at.imag());
  if (z.empty()) return;
  if (!s.round()) {
    at.real(z.front());
    out.line(at);
    out.line(s.end);
    at = s.end;
    return;
  }
  if (!s.ccw) {
    if (z.back() > s.center.real()) return;
    at.real(z.back());
    out.line(at);
    if (std::abs(at - s.end) > 1e-3) out.arc(s.ccw, s.center, s.end);
    at = s.end;
    return;
  }
  if (z.front() < s.center.real()) return;
  at.real(z.front());
  out.line(at);
  const Point top = over_the_top(s);
  if (std::abs(at - top) > 1e-3) out.arc(s.ccw, s.center, top);
  at = top;
}

// Follows a falling segment down to height x (rapid if `fast`); true if it does not fall.
bool dive(const Segment& s, Point& at, double x, Oriented& out, bool fast) {
  if (!s.round()) {
    if (s.start.imag() <= s.end.imag() + kTolerance) return true;
    Point to = s.end;
    if (x >= s.end.imag()) {
      const std::vector<double> z = crossings(s, x);
      if (z.empty()) throw CycleError("x too large in straight dive");
      to = Point(z.front(), x);
    }
    if (fast)
      out.rapid(to);
    else
      out.line(to);
    at = to;
    return false;
  }
  if (std::abs(at - s.end) < kTolerance || std::real(at - s.end) <= kTolerance) {
    at = s.end;
    return false;
  }
  std::vector<double> z = crossings(s, x);
  if (z.empty()) z = crossings(s, x - kTolerance);
  if (s.ccw) {
    if (at.real() - kTolerance > s.center.real()) return true;
    const Point to = z.empty() || z.back() > s.center.real() ? s.end : Point(z.back(), x);
    out.arc(s.ccw, s.center, to);
    at = to;
    return false;
  }
  if (at.real() <= s.center.real()) return true;                // climbing already
  if (!z.empty() && z.front() < s.center.real()) return false;  // hit on the far side only: the next depth
  const Point to = z.empty() ? s.end : Point(z.front(), x);
  out.arc(s.ccw, s.center, to);
  at = to;
  return false;
}

// --- the profile -----------------------------------------------------------------------------

class Profile {
 public:
  explicit Profile(std::vector<Segment> s) : s_(std::move(s)) {}

  void finishing(Point from, double first, double last, double passes, PassWriter& writer);
  void roughing(bool facing, int variant, Point from, Point shift, double allowance, double depth, double retract,
                PassWriter& writer);

 private:
  void turn_all() {
    for (Segment& s : s_) turn(s);
    orientation_ ^= 4;
  }
  // Reflects the profile so that from the first segment's end to the last one's Z decreases
  // and X increases, recording the reflections for the output.
  void fold() {
    const Point d = s_.front().end - s_.back().end;
    if (d.imag() > 0) {
      for (Segment& s : s_) reflect_x(s);
      orientation_ ^= 2;
    }
    if (d.real() < 0) {
      for (Segment& s : s_) reflect_z(s);
      orientation_ ^= 1;
    }
  }
  void require_monotonic() {
    Segment& first = s_.front();
    if (std::real(first.end - first.start) > 0) first.start.real(first.end.real());
    for (const Segment& s : s_)
      if (!monotonic(s)) throw CycleError("Not monotonic");
  }
  void make_corners() {
    for (std::size_t h = 1; h + 1 < s_.size(); ++h) {
      Segment& c = s_[h];
      if (c.kind == Segment::Kind::Fillet) {
        c.center = make_corner(c, s_[h - 1], s_[h + 1]);
        c.ccw = std::imag(c.start - c.center) > 0 || std::imag(c.end - c.center) > 0;
        c.corner = 0.0;
      } else if (c.kind == Segment::Kind::Chamfer) {
        make_corner(c, s_[h - 1], s_[h + 1]);
      }
    }
    s_.erase(std::remove_if(s_.begin(), s_.end(), [](const Segment& s) { return radius(s) < 1e-3; }), s_.end());
    if (s_.empty()) throw CycleError("the profile has no segment longer than 0.001");
  }
  void add_allowance(double distance);
  void pocket(int variant, Point at, std::size_t p, Oriented& out);
  void count_step() {
    if (++steps_ > kStepLimit) throw CycleError("the cycle does not end (LinuxCNC loops forever on this profile)");
  }

  std::vector<Segment> s_;
  int orientation_ = 0;
  double depth_ = 0.5;
  Point escape_{0.3, 0.3};
  std::vector<Point> pocket_starts_;
  long steps_ = 0;
};

// Offsets the profile (without its first segment, the approach) by `distance` to the side
// away from the approach, in steps that no segment's offset can turn over.
void Profile::add_allowance(double distance) {
  if (s_.size() < 2) throw CycleError("the profile needs a segment after the approach");
  const Point v1 = s_.front().end - s_.front().start, v2 = s_.back().start - s_.front().start;
  if (std::imag(v1 / v2) < 0) distance = -distance;
  const Segment approach = s_.front();
  s_.erase(s_.begin());
  double done = 0.0;
  while (done != distance) {
    count_step();
    double step = 1e9;
    for (const Segment& s : s_) step = std::min(step, radius(s) / 2);
    step = std::min(step, std::abs(distance - done));
    if (distance < 0) step = -step;
    for (std::size_t p = 0; p < s_.size();) {
      offset(s_[p], step);
      if (radius(s_[p]) < 1e-3)
        s_.erase(s_.begin() + static_cast<long>(p));
      else
        ++p;
    }
    for (std::size_t p = 0; p + 1 < s_.size(); ++p) {  // segments that part: joined by an arc
      if (std::real(s_[p].end - s_[p + 1].start) <= 1e-2) continue;
      Segment a = s_[p], b = s_[p + 1];
      offset(a, -step);
      offset(b, -step);
      const Point center = (a.end + b.start) / 2.0;
      s_.insert(s_.begin() + static_cast<long>(p) + 1, Segment::arc(distance > 0, s_[p].end, center, s_[p + 1].start));
      ++p;
    }
    for (std::size_t p = 0; p + 1 < s_.size(); ++p) {
      if (!monotonic(s_[p])) {  // LinuxCNC drops the shorter of it and the one before
        if (p == 0) throw CycleError("Not monotonic after the allowance");
        s_.erase(s_.begin() + static_cast<long>(radius(s_[p]) < radius(s_[p - 1]) ? p : p - 1));
        p = 0;
      }
      if (p + 1 >= s_.size()) break;
      if (radius(s_[p]) < 1e-3) {
        s_.erase(s_.begin() + static_cast<long>(p));
        p = 0;
      } else {
        intersect(s_[p], s_[p + 1]);
      }
    }
    if (s_.empty()) throw CycleError("the allowance leaves nothing of the profile");
    done += step;
  }
  for (std::size_t p = 0; p + 1 < s_.size(); ++p) s_[p].end = s_[p + 1].start = (s_[p].end + s_[p + 1].start) / 2.0;
  s_.insert(s_.begin(), approach);
  s_.front().end = s_[1].start;
}

void Profile::finishing(Point from, double first, double last, double passes, PassWriter& writer) {
  s_.front().start = from;
  // Turned by 90 degrees if the profile without its approach does not fall monotonically otherwise.
  Profile body(std::vector<Segment>(s_.begin() + 1, s_.end()));
  body.fold();
  if (!std::all_of(body.s_.begin(), body.s_.end(), monotonic)) {
    body.turn_all();
    body.fold();
  }
  body.require_monotonic();
  if (body.orientation_ & 4) turn_all();
  fold();
  make_corners();
  require_monotonic();
  Oriented out(writer, orientation_);
  for (int pass = static_cast<int>(passes); pass > 0; --pass) {
    Profile path(*this);
    path.add_allowance((pass - 1) * (first - last) / passes + last);
    out.rapid(path.s_.front().start);
    out.rapid(path.s_.front().end);
    for (std::size_t k = 1; k < path.s_.size(); ++k) out.draw(path.s_[k]);
  }
}

void Profile::roughing(bool facing, int variant, Point from, Point shift, double allowance, double depth,
                       double retract, PassWriter& writer) {
  s_.front().start = from;
  if (facing) turn_all();
  fold();
  make_corners();
  require_monotonic();
  add_allowance(allowance);
  for (Segment& s : s_) {
    s.start += shift;
    s.end += shift;
    s.center += shift;
  }
  Oriented out(writer, orientation_);
  depth_ = std::max(depth, 2 * kTolerance);
  escape_ = retract * Point(1, 1);
  out.rapid(s_.front().start);
  if (s_.back().end.imag() < s_.front().start.imag()) {  // back up to the start height at the end
    Point up = s_.back().end;
    up.imag(s_.front().start.imag());
    s_.push_back(Segment::line(s_.back().end, up));
  }
  pocket_starts_.push_back(s_.front().start);
  pocket(variant, s_.front().start, 0, out);
}

// Cuts from `at` (on segment p) at depth steps down to the profile; a pocket (the profile
// rising, then falling again) is cut by recursion from where the climb ends.
void Profile::pocket(int variant, Point at, std::size_t p, Oriented& out) {
  double x = pocket_starts_.back().imag();
  if (variant == 2) {  // the first roughing pass skipped: down along the profile to the first pocket
    for (; p < s_.size(); ++p)
      if (dive(s_[p], at, -1e9, out, p == 0)) break;
    variant = 3;
  }
  while (p < s_.size()) {
    count_step();
    while (x - kTolerance > at.imag()) {
      x -= depth_;
      count_step();  // (a depth of cut below the coordinates' resolution would never get there)
    }
    if (dive(s_[p], at, x, out, p == 0)) {
      if (variant == 1) {  // along the finished contour, no pockets
        for (; p < s_.size(); ++p) climb_only(s_[p], at, out);
        return;
      }
      for (; p < s_.size(); ++p) {
        if (!climb(s_[p], at, out)) continue;
        if (variant == 3) {
          if (at.imag() > pocket_starts_.back().imag() && pocket_starts_.size() > 1) pocket_starts_.pop_back();
          if (pocket_starts_.size() == 1) pocket_starts_.push_back(at);
        }
        pocket(variant, at, p, out);
        return;
      }
      return;
    }
    if (std::abs(at.imag() - x) > kTolerance) {  // past this segment's height
      ++p;
      continue;
    }
    for (std::size_t ip = p; ip < s_.size(); ++ip) {  // cut across at this depth
      const std::vector<double> z = crossings(s_[ip], at.imag());
      if (z.empty()) continue;
      const double to_z = ip != p ? z.front() : z.back();  // the diving arc may be hit twice
      const double distance = std::abs(to_z - at.real());
      if (to_z - kTolerance > at.real()) continue;
      if (distance < kTolerance) {
        if (ip == p) continue;
        if (std::abs(at - s_[ip].start) < kTolerance) {
          p = ip;
        } else {
          x -= depth_;
        }
        break;
      }
      Point to = at;
      to.real(to_z);
      out.line(to);
      const double scale = std::min(1.0, distance / 2 / escape_.real());  // a short cut escapes less
      to += scale * escape_;
      out.rapid(to);
      out.rapid(at - std::conj(scale * escape_));
      if (p == 0)
        out.rapid(at);
      else
        out.line(at);
      x -= depth_;
      break;
    }
  }
}

}  // namespace

void finishing_passes(std::vector<Segment> profile, Point from, double allowance_first, double allowance_last,
                      double passes, PassWriter& out) {
  Profile(std::move(profile)).finishing(from, allowance_first, allowance_last, passes, out);
}

void roughing_passes(std::vector<Segment> profile, bool facing, int variant, Point from, Point shift, double allowance,
                     double depth, double retract, PassWriter& out) {
  Profile(std::move(profile)).roughing(facing, variant, from, shift, allowance, depth, retract, out);
}

}  // namespace vc::interpreter::lathe
