// The pre-distorter end to end: reads a part program line by line, interprets it, corrects
// its moves and writes the pre-distorted program. Streaming: memory does not grow with the
// program (one line, its block and its pieces at a time).
#pragma once

#include <functional>
#include <istream>
#include <ostream>

#include "vc/interpreter/interpreter.hpp"
#include "vc/predistort/path_corrector.hpp"
#include "vc/predistort/tool_lengths.hpp"
#include "vc/predistort/writer.hpp"

namespace vc::predistort {

struct Job {
  const machine::Model* model = nullptr;
  const machine::Conditions* conditions = nullptr;  // the temperatures the program is made for (null: the file's)
  interpreter::Setup setup;                         // file, axes, tool table, parameters, world convention
  CorrectorOptions corrector;
  const Deflection* deflection = nullptr;
  Provenance provenance;  // for the header comment
  // Threads correcting moves, each taking every other batch of lines; 0: as the machine
  // needs (two with rotary axes on two cores or more, else one).
  int correcting_threads = 0;
  // If set: one row per written line, "output_line,input_file,input_line" (the header's lines
  // and lines the pre-distorter adds to the program have the input line they come from, or 0).
  std::ostream* line_map = nullptr;
};

struct Summary {
  long lines = 0, translated_lines = 0, written_as_is_moves = 0;
  CorrectorStats corrector;
  ToolLengthLog tool_lengths;  // the L of each corrected move, and where it came from
};

// `progress(bytes_read)` is called every few thousand lines. Throws vc::LoadError
// (file:line:column) on anything the program cannot be translated with.
Summary predistort(std::istream& in, std::ostream& out, const Job& job,
                   const std::function<void(long bytes_read)>& progress = {});

// The program axes (bit i of XYZABC) a machine has.
unsigned program_axes(const machine::Model& model);

// What a correcting command says about the corrections beyond its figures, one line each (no
// line ends): the tool lengths L the moves were corrected for and where each came from, the
// warning for moves without G43 whose likely tool keeps errors beyond the tolerance, and one
// warning per axis whose corrected points left an error table's grid.
std::vector<std::string> correction_notes(const Summary& summary, const Job& job);

}  // namespace vc::predistort
