// Writes the pre-distorted program: every line as it was, except that the motion of a
// translated line is replaced by its corrected pieces (the first on the line itself, the
// others on lines of their own after it), and path blending is stated so that LinuxCNC
// cannot merge the fine corrections away.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "vc/gcode/block.hpp"
#include "vc/interpreter/interpreter.hpp"
#include "vc/predistort/path_corrector.hpp"

namespace vc::predistort {

// What the header comment names.
struct Provenance {
  std::string title;  // first line of the header; empty: the pre-distorter's own
  std::string machine, machine_name;
  std::vector<std::string> tables;
  std::string parameters, tool_table, process, world;
  double tolerance_mm = 0.0;
  std::string types = "all";  // the compensation types pre-distorted for (TypeSelection::to_string)
};

class Writer {
 public:
  // `axes`: bit i set for each program axis (XYZABC) the machine has; all are written.
  Writer(std::ostream& out, unsigned axes, double tolerance_mm);
  ~Writer();  // flushes
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  void header(const Provenance& provenance);
  // A line that does not move the machine in a way to correct: as it is, with G64 stated.
  // `position` and `frame`: where the interpreter is after the line (used if it moved).
  void verbatim(std::string_view raw, const gcode::Block& block, const interpreter::Effect& effect,
                const interpreter::Position& position, const interpreter::Frame& frame);
  // A line whose moves are replaced by `pieces` (one list per move of effect.moves).
  void translated(std::string_view raw, const gcode::Block& block, const interpreter::Effect& effect,
                  const std::vector<std::vector<Piece>>& pieces);
  // Hands what is written so far to the stream (lines are collected in blocks of about
  // kPendingBytes: one stream write per block, not per line).
  void flush();
  // Lines written so far (the header included).
  long lines() const { return lines_; }

 private:
  // A change to the raw line: [begin, end) replaced by edit_text_[text_begin, text_end).
  struct Edit {
    int begin, end;
    std::size_t text_begin, text_end;
  };
  static constexpr std::size_t kPendingBytes = 64 * 1024;
  void emit(std::string_view text);
  void add_edit(int begin, int end, std::string_view text);
  void blending_edits(const gcode::Block& block, const interpreter::Effect& effect);
  void write_edited(std::string_view raw);
  void remove_words(const gcode::Block& block, const std::vector<int>& words);
  // The words `words` (indices into block.words) of the line, as written, on a line of their own.
  void write_words(std::string_view raw, const gcode::Block& block, const std::vector<int>& words);
  void append_piece(std::string& line, const interpreter::Move& move, const Piece& piece,
                    const interpreter::Effect& effect, bool with_code, bool with_feed);
  void append_number(std::string& line, char letter, double value, int decimals) const;
  // The number u / 10^decimals.
  void append_units(std::string& line, char letter, std::int64_t u, int decimals) const;

  std::ostream& out_;
  unsigned axes_;
  double tolerance_mm_;
  int motion_ = -1;             // motion mode LinuxCNC is in (G code x10), -1 unknown
  interpreter::Position at_{};  // where the written program leaves the machine, program coordinates
  interpreter::Frame frame_;    // the frame `at_` is in
  std::string pending_;         // written, not yet handed to out_
  long lines_ = 0;
  std::string line_;  // reused buffers
  std::vector<Edit> edits_;
  std::string edit_text_;     // the texts of edits_
  std::vector<int> removed_;  // words a translated line loses
};

}  // namespace vc::predistort
