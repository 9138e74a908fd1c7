#include "vc/predistort/predistort.hpp"

#include <deque>
#include <string>
#include <thread>

#include "batch_queue.hpp"
#include "vc/interpreter/program_reader.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::predistort {
namespace {

// A pipeline of threads: the reader reads, parses and interprets lines (it owns the
// interpreter and the input stream), the correctors correct their moves (each owns a
// PathCorrector and takes every other batch where there are two), and the caller's thread
// writes them (it owns the writer and the output, and calls `progress`). Lines travel in
// order in batches through a bounded ring, so the output, the error reported (the first
// failing line in file order) and the memory bound are those of reading one line at a time.
struct Line {
  int number = 0;
  const std::string* file = nullptr;  // the program, or the subroutine file the line is in
  long bytes = 0;                     // read up to the end of this line
  std::string raw;
  gcode::Block block;
  interpreter::Effect effect;
  interpreter::Position position{};  // where the line leaves the program, if it moved as written
  interpreter::Frame frame;
  std::vector<std::vector<Piece>> pieces;  // effect.translate: per move, its corrected pieces
};
// Where the machine is when a batch starts, for a corrector that did not correct the batch
// before: at the end of the corrected move `move`, or at an uncorrected position.
struct Resume {
  bool after_move = false;
  interpreter::Move move;
};
using LineQueue = BatchQueue<Line, Resume>;

// A line's data lies in buffers of its own (text, words, moves, pieces), last touched by
// another thread, often on the other core: each stage asks for the buffers of the line
// kAhead lines on while it works on this one, instead of waiting for each in turn.
constexpr std::size_t kAhead = 4;
template <typename T>
void prefetch(const T* data, std::size_t count, bool for_writing = false) {
  const char* begin = reinterpret_cast<const char*>(data);
  for (std::size_t b = 0; b < count * sizeof(T); b += 64)
    for_writing ? __builtin_prefetch(begin + b, 1) : __builtin_prefetch(begin + b);
}
void prefetch_for_reader(const Line& line) {  // the buffers it fills again
  prefetch(line.raw.data(), line.raw.capacity(), true);
  prefetch(line.block.words.data(), line.block.words.capacity(), true);
}
void prefetch_for_corrector(const Line& line) { prefetch(line.effect.moves.data(), line.effect.moves.size()); }
void prefetch_for_writer(const Line& line) {
  prefetch(line.raw.data(), line.raw.size());
  prefetch(line.block.words.data(), line.block.words.size());
  prefetch(line.effect.motion_words.data(), line.effect.motion_words.size());
  for (const std::vector<Piece>& pieces : line.pieces) prefetch(pieces.data(), pieces.size());
}
enum Stage { kRead, kCorrect, kWrite };

// A file name as a CSV field (quoted if it holds a comma or a quote).
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}
constexpr std::size_t kBatches = 8, kBatchLines = 512;  // at most 4096 lines in flight

// Where the machine is after `batch` (unchanged if no line of it moves the machine): after
// its last corrected move, or lost after a move written as it is.
void leaves(const LineQueue::Batch& batch, Resume& resume) {
  for (std::size_t i = batch.count; i-- > 0;) {
    const interpreter::Effect& effect = batch.items[i].effect;
    if (effect.translate && !effect.moves.empty()) {
      resume = {true, effect.moves.back()};
      return;
    }
    if (effect.moved_as_written) {
      resume.after_move = false;
      return;
    }
  }
}

// The interpreter and the reader of the program's lines (whose file names the lines point
// to until the writer is done with them).
struct Source {
  interpreter::Interpreter interpreter;
  interpreter::ProgramReader reader;
  Source(std::istream& in, const interpreter::Setup& setup)
      : interpreter(setup), reader(in, setup.file, interpreter, setup.subroutine_path) {}
};

void read_lines(Source& source, LineQueue& queue) {
  interpreter::Interpreter& interpreter = source.interpreter;
  interpreter::ProgramReader& reader = source.reader;
  interpreter::Origin origin;
  Resume resume;
  for (bool last = false; !last;) {
    LineQueue::Batch* batch = queue.begin(kRead);
    if (!batch) return;  // a later stage failed
    batch->header = resume;
    try {
      while (batch->count < batch->items.size()) {
        if (batch->count + kAhead < batch->items.size()) prefetch_for_reader(batch->items[batch->count + kAhead]);
        Line& line = batch->items[batch->count];
        if (!reader.next(line.raw, origin, line.block, line.effect)) {
          batch->last = true;
          break;
        }
        line.number = origin.line;
        line.file = &reader.files()[static_cast<std::size_t>(origin.file)];
        line.bytes = reader.program_bytes();
        if (line.effect.moved_as_written) {
          line.position = interpreter.position();
          line.frame = interpreter.frame();
        }
        ++batch->count;
      }
    } catch (...) {
      batch->error = std::current_exception();
      batch->last = true;
    }
    leaves(*batch, resume);
    last = batch->last;
    queue.end(kRead);
  }
}

// Lane `lane` of `lanes` correctors: batches lane, lane + lanes, ...
void correct_lines(PathCorrector& corrector, LineQueue& queue, int lane, int lanes) {
  for (bool last = false; !last;) {
    LineQueue::Batch* batch = queue.begin(kCorrect, lane);
    if (!batch) return;
    std::size_t i = 0;
    try {
      if (lanes > 1) {  // another lane corrected the batch before
        if (batch->header.after_move)
          corrector.resume_after(batch->header.move);
        else
          corrector.lost_position();
      }
      for (; i < batch->count; ++i) {
        if (i + kAhead < batch->count) prefetch_for_corrector(batch->items[i + kAhead]);
        Line& line = batch->items[i];
        const interpreter::Effect& effect = line.effect;
        if (effect.translate) {
          line.pieces.resize(effect.moves.size());
          try {
            for (std::size_t m = 0; m < effect.moves.size(); ++m) corrector.correct(effect.moves[m], line.pieces[m]);
          } catch (const std::runtime_error& e) {
            throw LoadError({*line.file, line.number, 1}, e.what());
          }
        } else if (effect.moved_as_written) {
          corrector.lost_position();
        }
      }
    } catch (...) {  // this line is the first that fails: the writer stops before it
      batch->count = i;
      batch->error = std::current_exception();
      batch->last = true;
    }
    last = batch->last;
    queue.end(kCorrect, lane);
  }
}

// The reader and corrector threads, joined on every way out of predistort() (stopped first
// if they still run).
class Workers {
 public:
  Workers(Source& source, std::deque<PathCorrector>& correctors, LineQueue& queue) : queue_(queue) {
    threads_.emplace_back([&source, &queue] { read_lines(source, queue); });
    const int lanes = static_cast<int>(correctors.size());
    for (int lane = 0; lane < lanes; ++lane)
      threads_.emplace_back([&correctors, &queue, lane, lanes] {
        correct_lines(correctors[static_cast<std::size_t>(lane)], queue, lane, lanes);
      });
  }
  ~Workers() { join(); }
  void join() {
    if (threads_.empty()) return;
    queue_.cancel();
    for (std::thread& t : threads_) t.join();
    threads_.clear();
  }

 private:
  LineQueue& queue_;
  std::vector<std::thread> threads_;
};

// Correcting a point with rotary joints costs several times reading and writing its line:
// there it gets two threads (if the machine has two cores).
int corrector_lanes(const Job& job) {
  if (job.correcting_threads > 0) return job.correcting_threads;
  return job.model->rotary_count() > 0 && std::thread::hardware_concurrency() > 1 ? 2 : 1;
}

}  // namespace

unsigned program_axes(const machine::Model& model) { return JointAxes(model).mask(); }

Summary predistort(std::istream& in, std::ostream& out, const Job& job, const std::function<void(long)>& progress) {
  // One corrector per lane (not copied: the threads hold them); lanes that start together
  // share the sampling of the bounds at a tool length.
  CorrectionBounds::Shared shared_bounds;
  std::deque<PathCorrector> correctors;
  const int lanes = corrector_lanes(job);
  CorrectorOptions options = job.corrector;
  if (!options.tools) options.tools = job.setup.tools;
  for (int lane = 0; lane < lanes; ++lane)
    correctors.emplace_back(*job.model, job.conditions ? *job.conditions : job.model->reference_conditions(), options,
                            job.deflection, lanes > 1 ? &shared_bounds : nullptr);
  Writer writer(out, job.setup.machine_axes, job.corrector.tolerance_mm);
  Summary summary;
  long bytes = 0;
  bool header_written = false;
  LineQueue queue({1, lanes, 1}, kBatches, kBatchLines);
  Source source(in, job.setup);
  Workers workers(source, correctors, queue);
  for (bool last = false; !last;) {
    LineQueue::Batch& batch = *queue.begin(kWrite);  // only the writer cancels
    for (std::size_t i = 0; i < batch.count; ++i) {
      if (i + kAhead < batch.count) prefetch_for_writer(batch.items[i + kAhead]);
      const Line& line = batch.items[i];
      const interpreter::Effect& effect = line.effect;
      bytes = line.bytes;
      // The header goes first, after a leading '%' (which must stay the first line).
      if (!header_written && !line.block.percent) {
        const long before = writer.lines();
        writer.header(job.provenance);
        header_written = true;
        if (job.line_map)
          for (long n = before + 1; n <= writer.lines(); ++n) *job.line_map << n << ",,0\n";
      }
      const long written_before = writer.lines();
      if (effect.translate) {
        writer.translated(line.raw, line.block, effect, line.pieces);
        ++summary.translated_lines;
        for (const interpreter::Move& m : effect.moves) summary.tool_lengths.add(m, *line.file);
      } else {
        writer.verbatim(line.raw, line.block, effect, line.position, line.frame);
        if (effect.moved_as_written) ++summary.written_as_is_moves;
      }
      if (job.line_map)
        for (long n = written_before + 1; n <= writer.lines(); ++n)
          *job.line_map << n << ',' << csv_field(*line.file) << ',' << line.number << '\n';
      ++summary.lines;
      if (progress && (line.number & 4095) == 0) progress(bytes);
    }
    if (batch.error) std::rethrow_exception(batch.error);
    last = batch.last;
    queue.end(kWrite);
  }
  workers.join();  // the corrector's statistics are final
  if (!header_written) {
    const long before = writer.lines();
    writer.header(job.provenance);
    if (job.line_map)
      for (long n = before + 1; n <= writer.lines(); ++n) *job.line_map << n << ",,0\n";
  }
  writer.flush();
  if (progress) progress(bytes);
  for (const PathCorrector& corrector : correctors) summary.corrector.add(corrector.stats());
  return summary;
}

std::vector<std::string> correction_notes(const Summary& summary, const Job& job) {
  std::vector<std::string> notes;
  const std::string& program = job.setup.file;
  const std::string& tool_table = job.provenance.tool_table;
  if (std::string lengths = summary.tool_lengths.describe(*job.model, program, tool_table); !lengths.empty())
    notes.push_back(std::move(lengths));
  if (std::string missing = missing_offset_warning(summary.corrector.missing_offset, summary.tool_lengths, *job.model,
                                                   program, tool_table, job.corrector.tolerance_mm);
      !missing.empty())
    notes.push_back(std::move(missing));
  for (std::string& grid : summary.corrector.grids.warnings(*job.model)) notes.push_back(std::move(grid));
  return notes;
}

}  // namespace vc::predistort
