// The passes of LinuxCNC's lathe cycles G70 (finishing), G71 (turning) and G72 (facing)
// from the profile a subroutine draws, as LinuxCNC's interp_g7x.cc makes them: corners with
// fillets and chamfers, the profile offset by the finishing allowance, roughing cuts at depth
// steps with their escape moves, pockets, and the eight orientations of a profile folded onto
// one. The same cuts, in the same order, within floating-point rounding: the pre-distorted
// program is compared with rs274's expansion of the original. Pure geometry, in the program's
// units; private to preproc/interpreter/src.
#pragma once

#include <complex>
#include <stdexcept>
#include <vector>

namespace vc::interpreter::lathe {

// A point of the XZ plane: real part Z, imaginary part X (LinuxCNC's convention).
using Point = std::complex<double>;

struct Segment {
  enum class Kind { Line, Arc, Fillet, Chamfer };  // a fillet is an arc, a chamfer a line, once made
  Kind kind = Kind::Line;
  Point start, end, center;
  bool ccw = false;     // arcs: G3
  double corner = 0.0;  // fillet radius (A) or chamfer size (C) still to be made at a corner

  static Segment line(Point from, Point to) { return {Kind::Line, from, to, {}, false, 0.0}; }
  static Segment arc(bool ccw, Point from, Point center, Point to) { return {Kind::Arc, from, to, center, ccw, 0.0}; }
  bool round() const { return kind == Kind::Arc || kind == Kind::Fillet; }
};

// Where the passes go, in the program's orientation.
class PassWriter {
 public:
  virtual ~PassWriter() = default;
  virtual void rapid(Point end) = 0;
  virtual void line(Point end) = 0;
  virtual void arc(bool ccw, Point center, Point end) = 0;
};

// What LinuxCNC reports as "G7X error: ..." (a profile it cannot cut).
struct CycleError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// G70: `passes` finishing passes from `allowance_first` to `allowance_last` (D, E) along
// `profile` (its first segment runs from where the cycle starts, `from` = X Z of the block).
void finishing_passes(std::vector<Segment> profile, Point from, double allowance_first, double allowance_last,
                      double passes, PassWriter& out);

// G71 (turning) or G72 (`facing`: the profile turned by 90 degrees first); `variant` is the
// subcode: 0 all, 1 no pockets (G7x.1), 2 the pockets only (G7x.2). `shift` = (W, U),
// `allowance` D, `depth` I (> 0), `retract` R.
void roughing_passes(std::vector<Segment> profile, bool facing, int variant, Point from, Point shift, double allowance,
                     double depth, double retract, PassWriter& out);

}  // namespace vc::interpreter::lathe
