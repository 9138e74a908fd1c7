// What a part program makes the machine do, as the interpreter works it out: moves in
// program coordinates (mm, deg), and the frame that maps them to the machine.
#pragma once

#include <array>
#include <cmath>

namespace vc::interpreter {

// Program axes in word order: X Y Z A B C (U V W are not supported; LinuxCNC's rs274 has
// none either).
inline constexpr int kAxes = 6;
inline constexpr char kAxisLetters[kAxes + 1] = "XYZABC";
using Position = std::array<double, kAxes>;  // mm for X Y Z, deg for A B C
inline constexpr unsigned kAllAxes = (1u << kAxes) - 1;

inline bool is_linear(int axis) { return axis < 3; }

// Program coordinates -> LinuxCNC world coordinates, as LinuxCNC's canon maps them:
//     world = rotate_z(program) + offset
// offset = the work offset (G54..G59.3) plus the tool length on Z (G43), or zero for G53
// moves. Rotation (G10 L2 R) turns X and Y about the program origin.
struct Frame {
  Position offset{};
  double rotation_deg = 0.0;

  Position world(const Position& p) const {
    Position w = p;
    if (rotation_deg != 0.0) {
      const double a = rotation_deg * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
      w[0] = c * p[0] - s * p[1];
      w[1] = s * p[0] + c * p[1];
    }
    for (int i = 0; i < kAxes; ++i) w[i] += offset[i];
    return w;
  }
  Position program(const Position& w) const {
    Position p = w;
    for (int i = 0; i < kAxes; ++i) p[i] -= offset[i];
    if (rotation_deg != 0.0) {
      const double a = rotation_deg * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
      const double x = p[0], y = p[1];
      p[0] = c * x + s * y;
      p[1] = -s * x + c * y;
    }
    return p;
  }
};

enum class MoveKind { Rapid, Line, Arc };

// Where a move's tool length offset comes from: no G43 in force (none yet, or G49), G43 (H or
// the tool in the spindle: the tool table's Z of that tool), or G43.1 Z (the program's own).
enum class ToolOffsetFrom : unsigned char { None, G43, G43_1 };

// A circular or helical arc (G2/G3) in the plane of two program axes. `first`, `second`
// and `normal` are axis indices with normal = first x second (G17: X Y Z, G18: Z X Y,
// G19: Y Z X), so counter-clockwise is a positive angle. The other axes move linearly.
struct Arc {
  int first = 0, second = 1, normal = 2;
  double center_first = 0, center_second = 0;  // program coordinates, mm
  double sweep_rad = 0;                        // signed: > 0 counter-clockwise (G3); full turns included
  int turns = 1;                               // P word (>= 1)
  bool clockwise = false;
};

struct Move {
  MoveKind kind = MoveKind::Line;
  Position start{}, end{};           // program coordinates, mm and deg
  unsigned known_start = 0;          // bit i: start[i] is known (the program has set that axis)
  Frame frame;                       // program -> world for this move (identity offset for G53)
  bool machine_coordinates = false;  // G53
  // LinuxCNC's active tool length offset (G43, G43.1; 0 without G43 or after G49), not the
  // physical tool length L: the correction is for L = Model::correction_length(tool_offset_mm)
  // (the tool-length rule, machines/README.md).
  double tool_offset_mm = 0.0;
  ToolOffsetFrom tool_offset_from = ToolOffsetFrom::None;  // where tool_offset_mm comes from
  int tool_offset_tool = -1;  // the tool whose table entry G43 applied (ToolOffsetFrom::G43)
  int tool = 0;               // tool in the spindle
  Arc arc;                    // kind == Arc
  // Feed: units/min in program units (G94), or 1/min (G93 inverse time).
  bool inverse_time = false;
  double feed = 0.0;
  // G93 under cutter compensation: LinuxCNC runs the compensated moves (and the corner arc
  // before them), and the move after G40, at the programmed move's length x F, in mm/min;
  // `feed` is made from it for each move once its geometry is final (Interpreter::
  // take_released), and the writer gives each such move an F of its own. 0: not such a move.
  double compensated_rate_mm_per_min = 0.0;
  bool spindle_on = false;
  double spindle_rpm = 0.0;
  int line = 0;  // 1-based line in the source file
};

// Point at fraction s in [0, 1] of a move's nominal path in program coordinates: straight
// for lines and rapids (LinuxCNC interpolates world coordinates linearly), a circle with
// radius changing linearly from start to end for arcs (LinuxCNC's spiral for a small radius
// mismatch) with the other axes linear in s.
Position point_at(const Move& move, double s);

// The length LinuxCNC divides by for feed (interp_inverse.cc find_straight_length,
// find_arc_length): X Y Z if they move, else the rotary axes; an arc's radius at its start.
double feed_length(const Move& move);

// A move timed at compensated_rate_mm_per_min, as its own inverse-time feed (1/min).
double inverse_time_feed(const Move& move);

}  // namespace vc::interpreter
