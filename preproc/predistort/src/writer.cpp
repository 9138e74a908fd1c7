#include "vc/predistort/writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace vc::predistort {
namespace {

using interpreter::kAxes;
using interpreter::kAxisLetters;
using interpreter::MoveKind;

constexpr double kInch = 25.4;
// Decimals written: 1 nm in mm, 2.5 nm in inches, 1e-6 deg (9 nm at 500 mm).
int decimals(int axis, bool inches) { return interpreter::is_linear(axis) ? (inches ? 7 : 6) : 6; }

int code_of(MoveKind kind, bool clockwise) {
  return kind == MoveKind::Rapid  ? interpreter::G_0
         : kind == MoveKind::Line ? interpreter::G_1
         : clockwise              ? interpreter::G_2
                                  : interpreter::G_3;
}

constexpr double kScale[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8};

// Integer in units of 10^-decimals: exact decimal output, and G91 increments that add up.
std::int64_t units(double value, int decimals) { return std::llround(value * kScale[decimals]); }

// Text inside a G-code comment: LinuxCNC refuses a '(' there (nested comment), and a ')'
// would end it early.
std::string commented(std::string text) {
  for (char& c : text) {
    if (c == '(') c = '[';
    if (c == ')') c = ']';
  }
  return text;
}

}  // namespace

Writer::Writer(std::ostream& out, unsigned axes, double tolerance_mm)
    : out_(out), axes_(axes), tolerance_mm_(tolerance_mm) {
  pending_.reserve(kPendingBytes + 4096);
}

Writer::~Writer() {
  try {
    flush();
  } catch (...) {  // a stream set to throw: the caller sees its state
  }
}

void Writer::emit(std::string_view text) {
  lines_ += std::count(text.begin(), text.end(), '\n');
  pending_ += text;
  if (pending_.size() >= kPendingBytes) flush();
}

void Writer::flush() {
  out_.write(pending_.data(), static_cast<std::streamsize>(pending_.size()));
  pending_.clear();
}

void Writer::header(const Provenance& p) {
  std::ostringstream h;
  if (p.title.empty())
    h << "(volcomp predistort: this program is pre-distorted for an UNCOMPENSATED machine: run it with the "
         "volkins correction disabled)\n";
  else
    h << '(' << commented(p.title) << ")\n";
  h << '(' << commented("machine: " + p.machine + ", " + p.machine_name) << ")\n";
  for (const std::string& t : p.tables) h << '(' << commented("table: " + t) << ")\n";
  std::ostringstream files;
  files << "tolerance: " << p.tolerance_mm << " mm; world: " << p.world
        << "; parameters: " << (p.parameters.empty() ? "none" : p.parameters)
        << "; tool table: " << (p.tool_table.empty() ? "none" : p.tool_table)
        << "; cutting process: " << (p.process.empty() ? "none" : p.process) << "; compensation types: " << p.types;
  h << '(' << commented(files.str()) << ")\n";
  emit(h.str());
  line_.clear();
  line_ += "G21 G64";
  append_number(line_, 'P', tolerance_mm_, 6);
  line_ += " Q0 (millimetres as assumed; blending within the tolerance, no segment merging)\n";
  emit(line_);
}

void Writer::append_number(std::string& line, char letter, double value, int decimals) const {
  append_units(line, letter, units(value, decimals), decimals);
}

void Writer::append_units(std::string& line, char letter, std::int64_t u, int decimals) const {
  // Built backwards in a buffer, then appended at once: " L-123.456" without trailing zeros.
  // The fraction is split off first so that its digits come from 32-bit arithmetic.
  char text[32];
  char* end = text + sizeof(text);
  char* p = end;
  const bool negative = u < 0;
  const std::uint64_t magnitude = negative ? 0 - static_cast<std::uint64_t>(u) : static_cast<std::uint64_t>(u);
  const auto scale = static_cast<std::uint64_t>(kScale[decimals]);
  std::uint64_t whole = magnitude / scale;
  auto fraction = static_cast<std::uint32_t>(magnitude % scale);
  if (fraction != 0) {
    int digits = decimals;
    for (; fraction % 10 == 0; fraction /= 10) --digits;  // trailing zeros dropped
    for (; digits > 0; --digits, fraction /= 10) *--p = static_cast<char>('0' + fraction % 10);
    *--p = '.';
  }
  do {
    *--p = static_cast<char>('0' + whole % 10);
    whole /= 10;
  } while (whole > 0);
  if (negative) *--p = '-';
  *--p = letter;
  *--p = ' ';
  line.append(p, static_cast<std::size_t>(end - p));
}

void Writer::blending_edits(const gcode::Block& block, const interpreter::Effect& effect) {
  // G64 in the program: Q0 (no naive-cam merging of the fine pieces) and, without P, the
  // tolerance as blending limit. An explicit P is kept: it is the programmer's choice.
  if (effect.g64_word < 0) return;
  if (effect.g64_q_word >= 0) {
    const gcode::Word& q = block.words[static_cast<std::size_t>(effect.g64_q_word)];
    add_edit(q.begin, q.end, "Q0");
    return;
  }
  const gcode::Word& g64 = block.words[static_cast<std::size_t>(effect.g64_word)];
  const std::size_t start = edit_text_.size();
  if (effect.g64_p_word < 0)  // the tolerance in the program's units (G20: inches)
    append_number(edit_text_, 'P', effect.inches ? tolerance_mm_ / kInch : tolerance_mm_, effect.inches ? 7 : 6);
  edit_text_ += " Q0";
  edits_.push_back({g64.end, g64.end, start + 1, edit_text_.size()});  // without the leading space
}

void Writer::add_edit(int begin, int end, std::string_view text) {
  const std::size_t start = edit_text_.size();
  edit_text_ += text;
  edits_.push_back({begin, end, start, edit_text_.size()});
}

void Writer::write_edited(std::string_view raw) {
  const auto by_begin = [](const Edit& a, const Edit& b) { return a.begin < b.begin; };
  if (!std::is_sorted(edits_.begin(), edits_.end(), by_begin)) std::sort(edits_.begin(), edits_.end(), by_begin);
  line_.clear();
  std::size_t from = 0;
  for (const Edit& e : edits_) {
    line_.append(raw.substr(from, static_cast<std::size_t>(e.begin) - from));
    const std::size_t next = static_cast<std::size_t>(e.end);
    const bool space_after = next >= raw.size() || raw[next] == ' ' || raw[next] == '\t';
    if (e.text_end > e.text_begin) {
      // One space between the text and the words on either side of it.
      if (!line_.empty() && line_.back() != ' ' && line_.back() != '\t') line_ += ' ';
      line_.append(edit_text_, e.text_begin, e.text_end - e.text_begin);
      if (!space_after) line_ += ' ';
    } else if (!line_.empty() && line_.back() == ' ' && space_after) {
      line_.pop_back();  // a removed word takes the space before it along
    }
    from = next;
  }
  line_.append(raw.substr(std::min(from, raw.size())));
  line_ += '\n';
  emit(line_);
}

void Writer::verbatim(std::string_view raw, const gcode::Block& block, const interpreter::Effect& effect,
                      const interpreter::Position& position, const interpreter::Frame& frame) {
  edits_.clear();
  edit_text_.clear();
  blending_edits(block, effect);
  remove_words(block, effect.after_tool_change_words);
  remove_words(block, effect.dropped_words);
  write_edited(raw);
  if (!effect.after_tool_change_words.empty()) write_words(raw, block, effect.after_tool_change_words);
  motion_ = effect.modal_motion;
  if (effect.moved_as_written) {
    at_ = position;
    frame_ = frame;
  }
}

void Writer::append_piece(std::string& line, const interpreter::Move& move, const Piece& piece,
                          const interpreter::Effect& effect, bool with_code, bool with_feed) {
  const bool inches = effect.inches;
  const int code = code_of(piece.kind, move.arc.clockwise);
  if (with_code || code != motion_) {
    line += " G";
    line += std::to_string(code / 10);
    motion_ = code;
  }
  // Re-express where the machine is if the frame changed (work offset, tool length, G53).
  const bool same_frame = frame_.offset == move.frame.offset && frame_.rotation_deg == move.frame.rotation_deg;
  if (!same_frame) {
    at_ = move.frame.program(frame_.world(at_));
    frame_ = move.frame;
  }
  const interpreter::Position start = at_;
  for (int i = 0; i < kAxes; ++i) {
    if (!(axes_ >> i & 1u)) continue;
    const double scale = interpreter::is_linear(i) && inches ? 1.0 / kInch : 1.0;
    const int d = decimals(i, inches);
    const std::int64_t written = units(piece.end[i] * scale, d);
    // Incremental: the increment between the written (rounded) positions, so that increments add up.
    const bool incremental = effect.incremental && !move.machine_coordinates;
    append_units(line, kAxisLetters[i], incremental ? written - units(at_[i] * scale, d) : written, d);
    at_[i] = static_cast<double>(written) / kScale[d] / scale;  // as written
  }
  if (piece.kind == MoveKind::Arc) {
    const interpreter::Arc& arc = move.arc;
    const char letters[3] = {'I', 'J', 'K'};  // center words of X, Y, Z
    const double scale = inches ? 1.0 / kInch : 1.0;
    const int d = inches ? 7 : 6;
    const double cf = effect.arc_absolute ? piece.center_first : piece.center_first - start[arc.first];
    const double cg = effect.arc_absolute ? piece.center_second : piece.center_second - start[arc.second];
    // Written in I J K order.
    if (arc.first < arc.second) {
      append_number(line, letters[arc.first], cf * scale, d);
      append_number(line, letters[arc.second], cg * scale, d);
    } else {
      append_number(line, letters[arc.second], cg * scale, d);
      append_number(line, letters[arc.first], cf * scale, d);
    }
    if (piece.turns > 1) line += " P" + std::to_string(piece.turns);
  }
  if (with_feed) append_number(line, 'F', move.feed / std::max(piece.fraction, 1e-9), 6);
}

void Writer::translated(std::string_view raw, const gcode::Block& block, const interpreter::Effect& effect,
                        const std::vector<std::vector<Piece>>& pieces) {
  std::size_t count = 0;
  for (const auto& p : pieces) count += p.size();
  const bool split = count > 1;
  // In G93 each piece gets an F for its own time: when a move is split, and for the moves of
  // cutter compensation (their F is not the programmed move's).
  const interpreter::Move* first_move = effect.moves.empty() ? nullptr : &effect.moves.front();
  const bool per_piece_feed =
      first_move && first_move->inverse_time && (split || first_move->compensated_rate_mm_per_min > 0.0);

  // Words replaced by the pieces: motion code, axes and arc words; when split, also the
  // stop codes (they go after the last piece) and an inverse-time F (one per piece).
  std::vector<int>& removed = removed_;
  removed.assign(effect.motion_words.begin(), effect.motion_words.end());
  if (effect.motion_code_word >= 0) removed.push_back(effect.motion_code_word);
  if (split) removed.insert(removed.end(), effect.stop_words.begin(), effect.stop_words.end());
  if (per_piece_feed && effect.f_word >= 0) removed.push_back(effect.f_word);
  const auto written_first = [&](int a, int b) {
    return block.words[static_cast<std::size_t>(a)].begin < block.words[static_cast<std::size_t>(b)].begin;
  };
  if (!std::is_sorted(removed.begin(), removed.end(), written_first))
    std::sort(removed.begin(), removed.end(), written_first);

  // The original line, without the removed words, with the first piece where the first
  // removed word was.
  edits_.clear();
  edit_text_.clear();
  blending_edits(block, effect);
  remove_words(block, effect.dropped_words);
  for (std::size_t i = 0; i < removed.size(); ++i) {
    const gcode::Word& w = block.words[static_cast<std::size_t>(removed[i])];
    const std::size_t start = edit_text_.size();
    if (i == 0 && count > 0) {                      // (no moves: a line whose move cutter compensation dropped)
      if (effect.exact_path) edit_text_ += " G61";  // a canned cycle's moves: LinuxCNC runs them so
      append_piece(edit_text_, effect.moves.front(), pieces.front().front(), effect, effect.motion_code_word >= 0,
                   per_piece_feed);
      edits_.push_back({w.begin, w.end, start + 1, edit_text_.size()});  // without the leading space
    } else {
      edits_.push_back({w.begin, w.end, start, start});
    }
  }
  write_edited(raw);

  // The other pieces, each on a line of its own.
  bool first = true;
  for (std::size_t m = 0; m < pieces.size(); ++m) {
    const interpreter::Move& move = effect.moves[m];
    for (const Piece& piece : pieces[m]) {
      if (first) {
        first = false;
        continue;
      }
      line_.clear();
      if (move.machine_coordinates) line_ += " G53";
      append_piece(line_, move, piece, effect, move.machine_coordinates, per_piece_feed);
      line_ += '\n';
      emit(std::string_view(line_).substr(1));
    }
    for (const interpreter::Effect::AfterMove& after : effect.after_moves)
      if (after.move == m) emit(after.codes);
  }
  if (effect.exact_path) {  // the program's path control mode again
    line_.clear();
    if (effect.restore_path_mode == interpreter::G_61_1) {
      line_ = "G61.1";
    } else if (effect.restore_path_mode == interpreter::G_64) {
      const double p = effect.restore_path_p_mm >= 0 ? effect.restore_path_p_mm : tolerance_mm_;
      line_ = "G64";
      append_number(line_, 'P', effect.inches ? p / kInch : p, effect.inches ? 7 : 6);
      line_ += " Q0";
    }
    if (!line_.empty()) emit(line_ + "\n");
  }
  if (split && !effect.stop_words.empty()) write_words(raw, block, effect.stop_words);
}

void Writer::remove_words(const gcode::Block& block, const std::vector<int>& words) {
  for (int index : words) {
    const gcode::Word& w = block.words[static_cast<std::size_t>(index)];
    edits_.push_back({w.begin, w.end, 0, 0});
  }
}

void Writer::write_words(std::string_view raw, const gcode::Block& block, const std::vector<int>& words) {
  line_.clear();
  for (int index : words) {
    const gcode::Word& w = block.words[static_cast<std::size_t>(index)];
    if (!line_.empty()) line_ += ' ';
    line_.append(raw.substr(static_cast<std::size_t>(w.begin), static_cast<std::size_t>(w.end - w.begin)));
  }
  line_ += '\n';
  emit(line_);
}

}  // namespace vc::predistort
