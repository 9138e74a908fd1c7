// Cutter radius compensation (G41/G42, G41.1/G42.1) as LinuxCNC 2.9 computes it
// (interp_convert.cc: convert_straight_comp1/2, convert_arc_comp1/2,
// convert_cutter_compensation_on/off; interp_queue.cc: the queue of held moves).
//
// LinuxCNC offsets the programmed path by the tool radius to the left or right and joins the
// offset segments: a convex corner gets an arc about the programmed corner, a concave corner
// moves the end of the move before it (which is why each move is held until the next one is
// known). The moves come out in the order LinuxCNC issues them, each tagged with the
// interpreter's sequence number of the line that made it, so that the line can be written
// with its own moves once they are final.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "vc/interpreter/move.hpp"

namespace vc::interpreter {

// A move the compensation has made final: `sequence` of the line it belongs to.
struct ReleasedMove {
  long sequence;
  Move move;
};

// What LinuxCNC refuses (gouging corners, entry moves shorter than the radius, ...).
struct CompensationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class CutterCompensation {
 public:
  enum Side { kOff = 0, kLeft = 1, kRight = 2 };

  // G41/G42: `radius` in mm (a negative one switches the side, as LinuxCNC does); `plane` G17 or
  // G18 (x10); `orientation` the lathe tool's (0 and 9: none); `inches`: the program's units,
  // for LinuxCNC's tolerances given in them.
  void start(Side side, double radius_mm, int plane, int orientation, bool inches);
  // G40 and the stops (M0 M1 M2 M30 M60): the held moves end where the tool is now and are
  // released. G40 also turns compensation off.
  void stop(std::vector<ReleasedMove>& out);
  void flush(std::vector<ReleasedMove>& out);

  Side side() const { return side_; }
  bool on() const { return side_ != kOff; }
  bool offsets() const { return side_ != kOff && radius_ > 0.0; }  // moves are offset (radius > 0)
  bool first_move() const { return first_; }
  bool holding() const { return !queue_.empty(); }
  // Where the tool is, as issued so far (program coordinates, mm and deg).
  const Position& tool() const { return tool_; }

  // A G0/G1 (move.kind Rapid or Line) from the programmed point `from` to `move.end`, both
  // programmed (uncompensated). `move` carries the line's state (frame, feed, tool, line).
  // `tool_at`: where the tool is before the first move of a compensated run.
  void straight(const Move& move, const Position& from, const Position& tool_at, long sequence,
                std::vector<ReleasedMove>& out);
  // A G2/G3 whose programmed centre (move.arc.center_*, turns, clockwise) LinuxCNC computes
  // from the programmed start `from` (arc_data_comp_*).
  void arc(const Move& move, const Position& from, const Position& tool_at, long sequence,
           std::vector<ReleasedMove>& out);

 private:
  struct Queued {
    long sequence;
    Move move;                 // uncompensated for the lathe tool's origin (applied when issued)
    double d1 = 0, d2 = 0;     // straight: direction of the original motion (the gouge check)
    double original_turn = 0;  // arc: its sweep when queued (0: not checked)
    int turn = 0;              // arc: LinuxCNC's turn (+ counter-clockwise, - clockwise; |turn| = P)
  };
  double get1(const Position& p) const { return p[a_]; }
  double get2(const Position& p) const { return p[b_]; }
  bool tool_inside_arc(int turn) const { return (side_ == kLeft && turn > 0) || (side_ == kRight && turn < 0); }
  void enqueue_straight(const Move& line, long sequence, double d1, double d2, double x, double y,
                        const Position& rest);
  void enqueue_arc(const Move& arc, long sequence, double original_turn, double x, double y, double cx, double cy,
                   int turn, const Position& rest);
  void move_endpoint_and_flush(double x, double y, std::vector<ReleasedMove>& out);
  void dequeue(std::vector<ReleasedMove>& out);
  void set_endpoint(double x, double y) {
    endpoint_[0] = x;
    endpoint_[1] = y;
    endpoint_valid_ = true;
  }
  // The first held move, or the one LinuxCNC's cleared queue still holds in its memory.
  const Queued* front() const {
    return queue_.empty() ? (stale_front_.sequence >= 0 ? &stale_front_ : nullptr) : &queue_.front();
  }
  void lathe_origin(Position& p) const;  // the lathe tool's origin point from its radius centre

  Side side_ = kOff;
  double radius_ = 0.0;
  int orientation_ = 0;
  int a_ = 0, b_ = 1, n_ = 2;  // plane axes: G17 X Y (Z), G18 Z X (Y)
  bool xz_ = false;
  double unit_ = 1.0;  // mm per program unit (LinuxCNC's tolerances are in program units)
  bool first_ = true;
  Position current_{};  // compensated point (LinuxCNC's current_x...), before the lathe origin
  Position tool_{};     // where the issued moves leave the tool
  std::vector<Queued> queue_;
  Queued stale_front_{-1, {}};
  double endpoint_[2] = {0, 0};
  bool endpoint_valid_ = false;
};

}  // namespace vc::interpreter
