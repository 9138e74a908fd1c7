// Which tool length L a program's moves were corrected for, and where each L came from (the
// tool-length rule, machines/README.md: L = tool_length_reference_mm + LinuxCNC's tool length
// offset), for the line every correcting command prints:
//     tool lengths: L = 100 mm (reference 0 mm + G43 offset of tool 1 from mc300.tbl) for lines 5-120;
//     L = 0 mm (no G43: the spindle gauge point) for lines 1-4
// A program without G43 is corrected for the gauge point (reference 0): the user must be able
// to see that from the output.
#pragma once

#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "vc/interpreter/interpreter.hpp"
#include "vc/machine/model.hpp"

namespace vc::predistort {

class ToolLengthLog {
 public:
  // A corrected move, in program order; `file`: the file its line is in (the program, or a
  // subroutine's file).
  void add(const interpreter::Move& move, const std::string& file);

  // The line above (without a line end), or empty if no move was corrected. `program`: the
  // program's file (lines in other files are named with theirs); `tool_table`: the tool table's
  // file as given (named by its file name).
  std::string describe(const machine::Model& model, const std::string& program, const std::string& tool_table) const;

  // Where a move was first corrected without a tool length offset in force (no G43 yet, or
  // G49), if one was.
  struct Where {
    std::string file;
    int line = 0;
    int tool = -1;  // the tool in the spindle then (-1: none loaded)
  };
  std::optional<Where> first_without_offset() const { return first_without_offset_; }

 private:
  // What decides L: the offset and where it came from.
  struct Source {
    double offset_mm = 0.0;
    interpreter::ToolOffsetFrom from = interpreter::ToolOffsetFrom::None;
    int tool = -1;  // G43's tool (from the tool table)
    bool operator==(const Source& o) const { return offset_mm == o.offset_mm && from == o.from && tool == o.tool; }
  };
  // Consecutive moves of one source in one file: lines first..last.
  struct Stretch {
    std::size_t source = 0;  // index into sources_
    std::string file;
    int first = 0, last = 0;
  };
  std::vector<Source> sources_;  // in the order first met
  std::vector<Stretch> stretches_;
  std::optional<Where> first_without_offset_;
};

// The log of a program read without correcting it (the interpreter alone: what `simulate` and
// `selftune` run). Throws vc::LoadError as the pre-distorter does.
ToolLengthLog read_tool_lengths(std::istream& program, const interpreter::Setup& setup);

}  // namespace vc::predistort
