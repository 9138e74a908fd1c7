// The lines of a program in the order LinuxCNC executes them: O-word subroutines (in the
// program or in NAME.ngc files on the subroutine path) with their arguments, scopes and return
// values, M98/M99 subprograms, do/while, while/endwhile, repeat, if/elseif/else,
// break/continue, with LinuxCNC 2.9's rules (interp_o_word.cc), each line then interpreted.
// A line whose moves cutter compensation holds back is handed out when they are final.
//
// The result is a flat program: O-word lines are executed, not returned, and a line executed
// inside a call is rewritten to say the same outside it (its words' expressions evaluated, its
// assignments to the call's local parameters dropped, its messages expanded: evaluated_line),
// so that the pre-distorted program needs no subroutine file and means what the original did.
#pragma once

#include <array>
#include <deque>
#include <istream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "vc/gcode/block.hpp"
#include "vc/gcode/parameters.hpp"
#include "vc/interpreter/interpreter.hpp"

namespace vc::interpreter {

// Where an executed line comes from.
struct Origin {
  int file = 0;  // index into ProgramReader::files(): 0 is the program
  int line = 0;  // 1-based line number in that file
};

class ProgramReader {
 public:
  // `program` is read from its start; named `program_name` in messages. Jumping back (loops,
  // calls of a subroutine defined before) needs a stream that can seek (a file, not a pipe).
  // `subroutine_path`: folders searched for NAME.ngc when `o<name> call` or `M98 P<n>` finds
  // no definition (LinuxCNC's [RS274NGC]SUBROUTINE_PATH and [DISPLAY]PROGRAM_PREFIX).
  ProgramReader(std::istream& program, const std::string& program_name, Interpreter& interpreter,
                std::vector<std::string> subroutine_path = {});
  ~ProgramReader();
  ProgramReader(const ProgramReader&) = delete;
  ProgramReader& operator=(const ProgramReader&) = delete;

  // The next line LinuxCNC executes, interpreted into `block` and `effect`; `raw` is its text as
  // the flat program holds it. False after the program's end (M2, M30, the end of the file).
  // Throws vc::LoadError with file:line:column.
  bool next(std::string& raw, Origin& origin, gcode::Block& block, Effect& effect);

  // The files read so far: the program, then subroutine files (names stay where they are).
  const std::deque<std::string>& files() const { return file_names_; }
  // Bytes of the program read so far (it goes back in a loop).
  long program_bytes() const;

 private:
  struct Source;  // an open file and where its reading is
  struct Label {  // where an O word was met (LinuxCNC's offset_map)
    gcode::OWord::Kind kind;
    int file;
    long offset;  // of the labelled line's start
    int line;
    long repeats_left = -1;  // repeat: iterations still to run (-1: not counting)
    long iterations = 0;     // times a loop jumped back here (to stop endless loops)
  };
  struct Frame {  // a call in progress
    int file;     // where to return: the line after the call
    long offset;
    int line;
    gcode::Parameters::Scope caller;
    bool m98 = false;  // an M98 subprogram: shares the caller's #1..#30
    std::string name;
    long repeats_left = 0;  // M98 L: calls still to make after this one
  };

  struct Held {  // a line whose moves cutter compensation still holds back
    std::string raw;
    Origin origin;
    gcode::Block block;
    Effect effect;
    long sequence;  // Interpreter::sequence() of the line
  };

  bool execute_next(std::string& raw, Origin& origin, gcode::Block& block, Effect& effect);
  // G-code lines LinuxCNC runs by itself (M72's and M73's restoring): read before the file's next.
  void inject(const std::string& lines, const Origin& origin);
  bool read_line(std::string& raw, Origin& origin);
  // A lathe cycle's profile: its subroutine's lines read into the interpreter, then the passes.
  void read_profile(Effect& effect, const Origin& cycle);
  bool trailing_percent(std::string& raw, Origin& origin, gcode::Block& block, Effect& effect);
  // Acts on an O word or M98/M99; false if the line is to be executed as G-code.
  bool control(const gcode::Block& block, const Origin& origin);
  void call(const std::string& name, const std::array<double, gcode::Parameters::kLocals>* arguments, bool m98,
            long repeats, const Origin& origin, int column);
  void leave(const Origin& origin);
  void jump_to(const Label& label, const Origin& origin);
  void jump_back(Label& label, const Origin& origin);  // a loop's next turn
  // The label of a block's closing or inner O word, which must be open with one of `kinds`.
  Label& label(const gcode::OWord& o, const std::string& name, const Origin& origin,
               std::initializer_list<gcode::OWord::Kind> kinds);
  // The label an opening O word (sub, do, while, if, repeat) sets on this line; the same name
  // on another line is refused, as LinuxCNC does.
  Label& open_label(const gcode::OWord& o, const std::string& name, const Origin& origin);
  double argument(const gcode::OWord& o, const Origin& origin) const;
  bool needs_rewriting(const std::string& raw) const;
  void apply_original_assignments(const Origin& origin);  // of a rewritten line, after it ran
  [[noreturn]] void refuse(const Origin& origin, int column, const std::string& message) const;

  Interpreter& interpreter_;
  std::vector<std::string> subroutine_path_;
  std::vector<std::unique_ptr<Source>> sources_;
  std::deque<std::string> file_names_;
  int current_ = 0;      // source being read
  long line_start_ = 0;  // byte offset of the line last read in it
  std::map<std::string, Label> labels_;
  std::vector<Frame> frames_;
  std::string skipping_to_;       // O name the lines are skipped up to (empty: none)
  bool skipping_to_sub_ = false;  // ... and it is a subroutine a call looks for
  bool defining_sub_ = false;     // between "sub" and "endsub" at the program's level
  std::string defining_name_;     // ... of this subroutine
  bool executed_if_ = false, doing_break_ = false, doing_continue_ = false;
  bool ended_ = false;
  gcode::Block original_;  // a rewritten line as it was written
  std::deque<Held> held_;
  std::deque<std::pair<std::string, Origin>> injected_;
};

}  // namespace vc::interpreter
