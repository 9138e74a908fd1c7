// RS274/NGC as LinuxCNC interprets it, for what a pre-distorter can translate faithfully:
// modal state (units, distance modes, plane, work offsets, tool length, feed mode), and for
// each block the moves it makes. What it cannot translate is refused with file:line:column
// and a reason (vc::LoadError), never mistranslated. O-word control flow is ProgramReader's.
//
// Cutter compensation (G41/G42) holds a line's moves back until the next move shows the
// corner, as LinuxCNC does: such a line's effect has translate set and its moves arrive later,
// in released_moves() after a later line (ProgramReader puts them back where they belong).
#pragma once

#include <array>
#include <complex>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "vc/gcode/block.hpp"
#include "vc/gcode/parameters.hpp"
#include "vc/interpreter/codes.hpp"
#include "vc/interpreter/cutter_compensation.hpp"
#include "vc/interpreter/linuxcnc_files.hpp"
#include "vc/interpreter/move.hpp"

namespace vc::interpreter {

struct Setup {
  std::string file;                             // program path, for messages
  unsigned machine_axes = 0;                    // bit i: the machine has program axis i (XYZABC)
  const ToolTable* tools = nullptr;             // null: no tool table given
  const gcode::Parameters* var_file = nullptr;  // null: no parameter file given
  // World convention of the kinematics the program runs on: with TCP kinematics LinuxCNC
  // still adds the tool length to world Z and the kinematics takes it off again, so the
  // tool length is not part of the frame (model.md, kins/README.md).
  bool tool_length_in_world = true;
  // Folders searched for NAME.ngc when a subroutine or M98 subprogram is not defined in the
  // program (LinuxCNC's [RS274NGC]SUBROUTINE_PATH, [DISPLAY]PROGRAM_PREFIX); see ProgramReader.
  std::vector<std::string> subroutine_path;
  // Where the machine is when the program starts (world coordinates, mm and deg), if known:
  // the INI's home or a position the user gives. Unknown (the default): a cutting move before
  // every axis is set is refused.
  std::optional<Position> start_world;
  // The length of the machine's unit in mm: 1, or 25.4 for a LinuxCNC set up in inches
  // ([TRAJ]LINEAR_UNITS). The tool table (read already in mm) and the parameter file hold
  // lengths in it, and so do the parameters a program reads (#5161.., #5211.., #5221..,
  // #5401..), as in LinuxCNC.
  double machine_unit_mm = 1.0;
};

// A NURBS control point (G5.2, and the points LinuxCNC makes for G5 and G5.1): program units,
// as the program gave it, and its weight.
struct ControlPoint {
  double x = 0.0, y = 0.0, weight = 1.0;
};

// What one block does, for a writer that copies the block and replaces its motion.
struct Effect {
  std::vector<Move> moves;                              // in the order LinuxCNC makes them
  bool translate = false;                               // moves must be replaced by corrected ones
  std::vector<int> motion_words;                        // words (indices into block.words) the corrected moves replace
  std::vector<int> stop_words;                          // M0 M1 M2 M30 M60: LinuxCNC runs them after the motion
  int g64_word = -1, g64_p_word = -1, g64_q_word = -1;  // path blending words, if any
  int f_word = -1;                                      // F word, if any
  int motion_code_word = -1;                            // G0/G1/G2/G3 word, if any (replaced with the moves)
  int modal_motion = G_80;                              // motion mode after the block, G code x10 (-1: none after G5.3)
  // Modal state the moves are written in.
  bool inches = false;
  bool incremental = false;   // G91
  bool arc_absolute = false;  // G90.1
  bool program_end = false;   // M2 / M30
  // A canned cycle: its moves run in exact path mode (LinuxCNC's cycles switch to it and back):
  // the writer states G61 before them and the program's mode after (G61.1, or G64 with this P
  // in mm, < 0: none).
  bool exact_path = false;
  int restore_path_mode = G_64;
  double restore_path_p_mm = -1.0;
  bool moved_as_written = false;  // the block moves the machine but is written as it is (G28/G30, a
                                  // rapid to a partly known position)
  // A tool change (M6, M61) and a tool length code (G43, G43.1, G49) on a line without motion:
  // the tool length words and the stop codes, to be written on a line of their own after it.
  // LinuxCNC keeps the machine still there, but the standalone interpreter (rs274, previews)
  // re-reads its position after the tool change without the new length: on two lines both agree.
  std::vector<int> after_tool_change_words;
  // Words the flat program leaves out: G41/G42 (.1) and their D and L words (the moves are
  // written offset, with compensation off), M70-M73 (what they do is written out).
  std::vector<int> dropped_words;
  // A canned cycle's dwells, spindle reversals, override switches and stops: G-code lines
  // (each ending in a newline) that LinuxCNC runs after moves[move].
  struct AfterMove {
    std::size_t move;
    std::string codes;
  };
  std::vector<AfterMove> after_moves;
  // A lathe cycle (G70-G72): the subroutine (O number) whose lines draw the profile. They are
  // read, not run: ProgramReader passes them to Interpreter::profile_block, then the cycle's
  // passes are added to this line's moves by Interpreter::finish_lathe_cycle.
  std::string profile_subroutine;
  void clear();
};

class Interpreter {
 public:
  explicit Interpreter(Setup setup);
  ~Interpreter();
  Interpreter(const Interpreter&) = delete;  // its parameters point back at it
  Interpreter& operator=(const Interpreter&) = delete;

  // Interprets one block (line `line` of the file). Throws vc::LoadError on anything it
  // cannot translate faithfully.
  void execute(const gcode::Block& block, int line, Effect& effect);
  // Reads line `line` of the file as LinuxCNC does (a DOS line end dropped from `raw`) into
  // `block`, then interprets it. A line that reads #<_line> is rewritten in `raw` to say the
  // same on another line (pin_line_number). Throws vc::LoadError with file:line:column for what it
  // cannot read or translate.
  void read(std::string& raw, int line, gcode::Block& block, Effect& effect);

  // Each execute() numbers its line: moves released later name the line by this number.
  long sequence() const { return sequence_; }
  // Cutter compensation holds moves back (lines executed since then are not final yet).
  bool holding_moves() const { return compensation_.holding(); }
  // Moves of earlier lines (by sequence()) that the last execute() made final, in order.
  std::vector<ReleasedMove>& released_moves() { return released_; }
  // Subroutine calls (ProgramReader): M70-M73 keep a saved state per call level, and M73's is
  // restored on return. The restoring G-code lines LinuxCNC would run (after an M72 line, a
  // return) are to be run as the next lines of the flat program: take_restore_lines().
  // A lathe cycle's profile (see Effect::profile_subroutine): each line of the subroutine that
  // is not control flow, then the end of the subroutine (the cycle's passes into `effect`).
  void profile_block(const gcode::Block& block, int line);
  void finish_lathe_cycle(Effect& effect);
  void enter_call_level();
  void leave_call_level();
  std::string take_restore_lines();

  const gcode::Parameters& parameters() const { return parameters_; }
  gcode::Parameters& parameters() { return parameters_; }
  // The file the next blocks come from, for messages (a subroutine's file).
  void set_file(const std::string& file) {
    if (file != setup_.file) setup_.file = file;
  }
  // Where the program is (program coordinates of the active frame) and that frame.
  const Position& position() const { return position_; }
  Frame frame() const;

 private:
  struct Words;  // the block's evaluated words
  Words evaluate(const gcode::Block& block, int line) const;
  void assign(const gcode::Block& block, int line);  // the block's parameter assignments
  // The modal state as the program reads it: #<_x>, #<_metric>, #5420... (state_parameters.cpp).
  struct StateView final : gcode::StateParameters {
    explicit StateView(const Interpreter& i) : interpreter(i) {}
    std::optional<double> numbered(int n) const override;
    std::optional<double> named(const std::string& name) const override;
    const Interpreter& interpreter;
  };
  void refuse(int line, int offset, const std::string& message) const;
  void set_tool_length(const Words& w, int line);
  void set_coordinate_system(int index);
  void set_offsets(const Words& w, int line);                 // G10 L2 / L20
  void set_tool_entry(const Words& w, int l, int line);       // G10 L1, L10, L11
  void set_axis_offsets(const Words& w, int code, int line);  // G92, G92.1-G92.3, G52
  void go_home(const Words& w, int code, int line, Effect& effect);
  void move(const Words& w, int line, Effect& effect);
  // A move of line `line` in frame `in` from the current point, with the modal state it runs in.
  Move new_move(int line, const Frame& in) const;
  void motion_words(const Words& w, const Move& m, Effect& effect) const;  // replaced by the corrected moves
  // Cutter compensation (cutter_compensation_modes.cpp): G40/G41/G42 and what LinuxCNC refuses
  // while it is on; a compensated move; the moves it releases, sorted into this line's and others.
  void compensation_rules(const gcode::Block& block, const Words& w, int line) const;
  void set_compensation(const Words& w, int line, Effect& effect);
  void compensated_move(const Words& w, Move& m, int line, Effect& effect);
  void take_released(std::vector<ReleasedMove>& out, Effect& effect);
  // Runs a step of the compensation; what it refuses is refused with this line and column.
  void compensating(int line, int offset, Effect& effect, const std::function<void()>& step);
  // M70-M73 (modal_state.cpp): the state LinuxCNC saves, as its active G and M codes.
  struct ModalState {
    bool inches = false;
    std::array<int, 11> g{};  // plane, cutter comp, distance, feed mode, system, tool offset, retract,
                              // spindle mode, arc centres, lathe mode, G92 applied (-1: not restored)
    int path_mode = G_64;
    double path_p = -1.0;  // program units
    double feed = 0.0, speed = 0.0;
    std::array<int, 6> m{};  // spindle, mist, flood, overrides, adaptive feed, feed hold
  };
  struct Context {
    std::optional<ModalState> saved;
    bool restore_on_return = false;  // M73
  };
  ModalState modal_state() const;
  void state_codes(const Words& w, int line, Effect& effect);
  std::string restore_text(const ModalState& saved) const;
  // Where the next move starts, in `in`: `otherwise` (the current point), or where the tool was
  // left (tool_elsewhere_, which this clears).
  Position take_move_start(const Frame& in, const Position& otherwise);
  static bool is_cycle(int motion) { return motion == G_73 || motion == G_74 || (motion >= G_81 && motion <= G_89); }
  // A canned cycle block (canned_cycles.cpp); `code_on_line`: the cycle's G code is written here.
  void cycle(const Words& w, int previous_motion, bool code_on_line, int line, Effect& effect);
  // Lathe cycles G70-G72 (lathe_cycles.cpp): the rapid to X Z, then the profile is read.
  struct LatheCycle;
  static bool is_lathe_cycle(int motion) { return motion >= G_70 && motion <= G_72_2; }
  void lathe_cycle(const Words& w, int line, Effect& effect);
  // One move of a lathe cycle (G0, G1, G2, G3 as code x10) in the XZ plane, in program units.
  void lathe_move(int code, std::complex<double> end, std::complex<double> center, int line, int offset,
                  Effect& effect);
  // Splines and NURBS (splines.cpp): G5, G5.1, G5.2 (the line's motion code, or the mode with
  // axis words) and G5.3, as LinuxCNC runs them; the rules of the words on such a line.
  static bool is_spline(int motion) { return motion == G_5 || motion == G_5_1 || motion == G_5_2; }
  void spline_rules(const Words& w, int line) const;
  void spline(const Words& w, int previous_motion, int line, Effect& effect);
  void cubic_or_quadratic_spline(const Words& w, int code, int line, Effect& effect);  // G5, G5.1
  void nurbs_point(const Words& w, int mode_before, int line);                         // G5.2
  void end_nurbs(const Words& w, int previous_motion, int line, Effect& effect);       // G5.3
  // The curve's moves (LinuxCNC's NURBS_FEED in the task's canon), from the current point.
  void curve_moves(const std::vector<ControlPoint>& points, unsigned order, int line, int offset, Effect& effect);
  void spline_start_rules(int line, int offset, const std::string& what, bool nurbs) const;  // what a curve needs
  void require_known_offsets(int line, int offset) const;
  bool no_motion_mode() const { return motion_ == G_80 || motion_ == -1; }
  Position world_position() const;
  // frame() in coordinate system 1..9; without G92/G52 or the tool length offset on request.
  Frame frame_for(int system, bool with_g92 = true, bool with_tool_length = true) const;
  // The mm (or deg) of one unit of a parameter that holds a length of this axis (#5161..,
  // #5211.., #5221.., #5401..: the machine's units, as in LinuxCNC).
  std::optional<double> spindle_tool_parameter(int n) const;  // #5401..#5413
  // G93: the feed rate LinuxCNC gives a move from its programmed start and end, mm/min.
  double inverse_time_rate(const Move& programmed) const;
  double machine_unit(int axis) const { return is_linear(axis) ? setup_.machine_unit_mm : 1.0; }
  void set_world_position(const Position& world);  // after a frame change, as LinuxCNC does
  Position end_point(const Words& w, int line) const;
  std::array<double, 2> program_xy() const;  // the current X Y in program units (program_xy_)
  void note_program_xy(double x, double y);  // position_ is at these X Y (program units)
  void polar_end_point(const Words& w, int line, double& x, double& y) const;  // '@' '^'
  void arc_geometry(const Words& w, const Position& end, int line, Move& move) const;

  Setup setup_;
  StateView state_view_{*this};
  std::unique_ptr<LatheCycle> lathe_;  // a lathe cycle reading its profile
  std::optional<ToolTable> tools_;     // the tool table as G10 L1 leaves it (none: no table given)
  gcode::Parameters parameters_;
  // Modal state, LinuxCNC's defaults at program start.
  bool inches_ = false;
  bool incremental_ = false;
  bool arc_absolute_ = false;
  int plane_ = G_17;
  int motion_ = G_80;     // none yet (-1: none after G5.3, as LinuxCNC)
  int path_mode_ = G_64;  // G61, G61.1, G64, and G64's P (mm; < 0: none)
  double path_p_ = -1.0;
  // Canned cycles: retract to R (G99, rs274's start) or to the start Z (G98); the words that
  // stay from block to block (R, Z, P, Q, in mm and s) and the Z the cycles started from.
  bool retract_to_r_ = true;
  double cycle_r_ = 0.0, cycle_z_ = 0.0, cycle_p_ = 0.0, cycle_q_ = 0.0;
  double cycle_start_z_ = 0.0;
  bool cycle_start_z_known_ = false;
  // Splines: the first control point of the next G5 without I J, from the last G5's P Q
  // (LinuxCNC's cycle_i, cycle_j: program units as written); the G5.2 points not yet ended
  // by G5.3, and the NURBS's order (L).
  double spline_i_ = 0.0, spline_j_ = 0.0;
  std::vector<ControlPoint> nurbs_points_;
  unsigned nurbs_order_ = 3;
  bool inverse_time_ = false;
  double feed_ = 0.0;  // program units per minute, or 1/min in G93
  double spindle_rpm_ = 0.0;
  bool spindle_on_ = false;
  bool spindle_clockwise_ = true;                        // M3 (M4: false)
  bool mist_ = false, flood_ = false;                    // M7, M8 (M9: both off)
  bool feed_override_ = true, spindle_override_ = true;  // M48-M51: LinuxCNC starts with both on
  bool adaptive_feed_ = false, feed_hold_ = true;        // M52, M53 (rs274 starts with feed hold enabled)
  bool constant_surface_speed_ = false;                  // G96 (G97: off)
  int selected_tool_ = -1;                               // T word
  int tool_in_spindle_ = -1;                             // after M6 / M61
  // #5401-#5413 read the spindle's tool table entry: known after M6, when LinuxCNC synchronises
  // the interpreter with the tool changer; after M61 they depend on when the task does (the
  // standalone rs274 keeps the previous tool's), so they are not given then.
  bool tool_data_known_ = false;
  double tool_offset_ = 0.0;  // mm: LinuxCNC's tool length offset (G43, G43.1; 0: G49), not L
  ToolOffsetFrom tool_offset_from_ = ToolOffsetFrom::None;  // where it comes from
  int tool_offset_tool_ = -1;                               // G43's tool (its table entry), if from the tool table
  int coordinate_system_ = 1;                               // 1..9: G54..G59.3
  bool offsets_known_ = false;  // the active system's offsets came from the .var file or G10
  unsigned offsets_set_ = 0;    // bit n: system n set by G10 in this program
  Position g92_{};              // G92/G52 offsets (mm, deg), added before the rotation
  Position position_{};         // current point, program coordinates (mm, deg); with cutter
                                // compensation the programmed point, not the tool's
  // LinuxCNC's current X and Y in program units as it computes them (the words as written, G91
  // sums and unit changes in program units), where the interpreter knows them: a spline's
  // arithmetic starts from them, and converted from mm they can differ in the last bit, which
  // LinuxCNC's biarcs can magnify (splines.cpp). Valid while position_ is still at mm_x, mm_y.
  struct ProgramXY {
    double x = 0.0, y = 0.0, mm_x = 0.0, mm_y = 0.0;
    bool inches = false, known = false;
  };
  ProgramXY program_xy_;
  CutterCompensation compensation_;
  // Where the tool is (world) when LinuxCNC's position is not where it left the tool: after G40
  // (the programmed point again), after a G74/G84 outside G17 (LinuxCNC 2.9 swaps its axes).
  std::optional<Position> tool_elsewhere_;
  bool arc_not_allowed_ = false;  // LinuxCNC: the move after G40 must be straight
  long sequence_ = 0;
  int call_level_ = 0;
  std::vector<Context> contexts_;  // by call level
  std::string restore_lines_;
  std::vector<ReleasedMove> released_, own_;
  unsigned known_ = 0;  // axes whose current position is known
};

}  // namespace vc::interpreter
