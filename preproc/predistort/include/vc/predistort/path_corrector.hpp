// Corrects the moves of a part program: every point of a move is mapped to the machine and
// corrected with the core correction (the same as the kinematics module applies), and the
// move is split where needed so that the path LinuxCNC interpolates between the corrected
// points stays within a tolerance of the exact correction everywhere along the move.
//
// Error measured (the quantity the tolerance bounds): at a point of a piece, the tool tip of
// the real machine at the joints LinuxCNC interpolates there, plus the cutting-force
// deflection, against the ideal machine's tool tip at the corresponding nominal point.
// Checked at 1/4, 1/2 and 3/4 of each piece against 0.7 x tolerance (a single kink of the
// correction inside a piece is then caught); straight pieces short enough that a sampled
// bound on the correction's slope, or (world = joints, no kink inside) on its curvature,
// keeps them inside a quarter of the tolerance are accepted unchecked (correction_bounds.hpp).
// On machines with rotary axes the tool direction is bounded the same way (tolerance_rad): at
// the check points, the real machine's direction at the interpolated joints against the
// direction the exact correction gives there (the ideal direction plus the exact correction's
// own direction error, which the pole fade leaves: computed at the check point itself where
// the fade acts, at the piece's ends or at the point, since the fade is not linear along a
// piece); such pieces are not accepted by the position bounds alone.
#pragma once

#include <utility>
#include <vector>

#include "vc/interpreter/move.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/predistort/correction_bounds.hpp"
#include "vc/predistort/deflection.hpp"
#include "vc/predistort/grid_excursions.hpp"
#include "vc/predistort/joint_axes.hpp"
#include "vc/predistort/missing_tool_offset.hpp"
#include "vc/predistort/one_step_correction.hpp"

namespace vc::predistort {

using interpreter::Move;
using interpreter::MoveKind;
using interpreter::Position;

struct CorrectorOptions {
  double tolerance_mm = 0.0005;
  double tolerance_rad = 2e-5;  // tool direction, machines with rotary axes (0: not bounded)
  machine::WorldConvention world = machine::WorldConvention::Axes;
  int max_depth = 24;  // halvings of one move (2^24 pieces) before giving up on the tolerance
  // The tool table the program runs with (none: not given): the likely length of a tool that
  // moves without G43 (missing_tool_offset.hpp).
  const interpreter::ToolTable* tools = nullptr;
};

// One output piece of a move: go from the previous piece's end to `end` (program
// coordinates, corrected), straight or along an arc about `center` (same plane and
// direction as the move's arc, radius equal at both ends).
struct Piece {
  MoveKind kind = MoveKind::Line;
  Position end{};
  double center_first = 0, center_second = 0;
  int turns = 1;
  double fraction = 1.0;  // share of the move (for G93 inverse-time feeds)
};

struct CorrectorStats {
  long moves = 0, pieces = 0, corrections = 0, checks = 0;
  long tolerance_misses = 0;           // moves where max_depth was reached
  GridExcursions grids;                // corrected points outside a table's grid
  MissingOffsetError missing_offset;   // moves without G43: the error left at the likely tool
  double max_checked_error_mm = 0.0;   // largest error at an accepted piece's check points
  double max_checked_error_rad = 0.0;  // largest tool direction error there
  double max_deflection_mm = 0.0;

  void add(const CorrectorStats& other);  // of another corrector (a lane of the same program)
};

class PathCorrector {
 public:
  // `shared`: the sampling of the correction bounds shared with correctors on other threads.
  PathCorrector(const machine::Model& model, const machine::Conditions& conditions, CorrectorOptions options,
                const Deflection* deflection, CorrectionBounds::Shared* shared = nullptr);

  // Appends the pieces of `move` to `pieces` (cleared first). The first piece starts where
  // the previous corrected move ended; if the machine is elsewhere (the previous move was
  // written uncorrected), a short piece first goes to the corrected start.
  void correct(const Move& move, std::vector<Piece>& pieces);
  // The machine is now at an uncorrected, or unknown, position (a move written as it is).
  void lost_position() { have_last_ = false; }
  // The machine is now where the correction of `move` left it (another corrector corrected
  // the move: this one takes over after it).
  void resume_after(const Move& move);

  const CorrectorStats& stats() const { return stats_; }

  // A point of a move: where the nominal path is, and where its correction sends the machine.
  struct Node {
    double s = 0.0;
    machine::Joints input;      // world coordinates of the nominal point (what the program says)
    machine::Joints nominal;    // q_n at the nominal point (ideal machine)
    machine::Joints target;     // q_n shifted against the deflection
    machine::Joints corrected;  // q_c
    machine::Joints world;      // corrected world coordinates (what LinuxCNC interpolates)
    Position program{};         // corrected point in program coordinates
    Eigen::Vector3d deflection_mm = Eigen::Vector3d::Zero();  // part frame
  };

 private:
  Node node_at(const Move& move, double s);
  machine::Joints joints_of(const Position& world) const;
  Position program_of(const Move& move, const machine::Joints& joints, const Position& like) const;
  struct PieceError {
    double mm = 0.0, rad = 0.0;
  };
  // The real minus the ideal tool direction of the exact correction at a node.
  Eigen::Vector3d direction_error(const Move& move, const Node& n) const;
  using DirectionErrors = std::pair<Eigen::Vector3d, Eigen::Vector3d>;  // at a piece's two ends
  // Position error at t of a piece, and, if `exact_direction_errors` (at the piece's ends) are
  // given, the direction error against the exact correction's own there: zero outside the
  // pole fade band, else the exact correction's at the point.
  PieceError error_between(const Move& move, const Node& a, const Node& b, const Piece& piece, double t,
                           const DirectionErrors* exact_direction_errors);
  // Worst error of a piece at its check points; true if within the tolerances' accept share.
  bool piece_within_tolerance(const Move& move, const Node& a, const Node& b, const Piece& piece);
  Position commanded_at(const Move& move, const Node& a, const Piece& piece, double t) const;
  Eigen::Vector3d force_at(const Move& move, double s);
  void refine(const Move& move, const Node& a, const Node& b, int depth, std::vector<Piece>& pieces);
  Piece piece_between(const Move& move, const Node& a, const Node& b) const;
  bool within_bounds(const Move& move, const Node& a, const Node& b);
  void ended(const Move& move, const Node& end);
  machine::Joints seed_for(const machine::Joints& target, double tool_length_mm) const;
  void solved(const machine::Joints& target, const machine::Joints& corrected, double tool_length_mm);

  const machine::Model& model_;
  machine::Conditions conditions_;  // the machine's temperatures and pole fade
  CorrectorOptions options_;
  const Deflection* deflection_;
  bool checks_direction_;  // rotary axes and a direction tolerance
  JointAxes axes_;
  CorrectorStats stats_;
  bool have_last_ = false;
  Node last_;  // end of the previous corrected move
  double last_tool_length_ = 0.0;
  bool last_loaded_ = false;  // a cutting force acted at last_
  // The last two corrections (any move, in the order made): the seed of the next one is
  // extrapolated from them. Only the Newton iterations depend on it, never the answer.
  struct Solved {
    machine::Joints target, offset;  // offset = corrected - target
    double tool_length_mm = 0.0;
  };
  Solved recent_[2];  // [1] the latest
  int recent_count_ = 0;
  CorrectionBounds bounds_;
  OneStepCorrection one_step_;
  MissingOffsetCheck missing_offset_;
};

}  // namespace vc::predistort
