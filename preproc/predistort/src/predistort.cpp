#include "vc/predistort/predistort.hpp"

#include <string>

#include "vc/gcode/parser.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::predistort {

unsigned program_axes(const machine::Model& model) {
  unsigned axes = 0;
  for (const machine::Axis& a : model.axes) {
    const auto i = std::string_view(interpreter::kAxisLetters).find(a.letter);
    if (i != std::string_view::npos) axes |= 1u << i;
  }
  return axes;
}

Summary predistort(std::istream& in, std::ostream& out, const Job& job,
                   const std::function<void(long)>& progress) {
  interpreter::Interpreter interpreter(job.setup);
  PathCorrector corrector(*job.model, job.corrector, job.deflection);
  Writer writer(out, job.setup.machine_axes, job.corrector.tolerance_mm);
  Summary summary;
  gcode::Block block;
  interpreter::Effect effect;
  std::vector<std::vector<Piece>> pieces;
  std::string raw;
  long bytes = 0;
  bool header_written = false;
  for (int line = 1; std::getline(in, raw); ++line) {
    bytes += static_cast<long>(raw.size()) + 1;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();  // DOS line ends
    try {
      gcode::parse_block(raw, block);
    } catch (const gcode::SyntaxError& e) {
      throw LoadError({job.setup.file, line, e.offset + 1}, e.what());
    }
    interpreter.execute(block, line, effect);
    // The header goes first, after a leading '%' (which must stay the first line).
    if (!header_written && !block.percent) {
      writer.header(job.provenance);
      header_written = true;
    }
    if (effect.translate) {
      pieces.resize(effect.moves.size());
      try {
        for (std::size_t m = 0; m < effect.moves.size(); ++m) corrector.correct(effect.moves[m], pieces[m]);
      } catch (const std::runtime_error& e) {
        throw LoadError({job.setup.file, line, 1}, e.what());
      }
      writer.translated(raw, block, effect, pieces);
      ++summary.translated_lines;
    } else {
      writer.verbatim(raw, block, effect, interpreter);
      if (effect.moved_as_written) {
        corrector.lost_position();
        ++summary.written_as_is_moves;
      }
    }
    ++summary.lines;
    if (progress && (line & 4095) == 0) progress(bytes);
  }
  if (!header_written) writer.header(job.provenance);
  if (progress) progress(bytes);
  summary.corrector = corrector.stats();
  return summary;
}

}  // namespace vc::predistort
