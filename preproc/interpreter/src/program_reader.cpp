#include "vc/interpreter/program_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "vc/gcode/evaluate.hpp"
#include "vc/gcode/parser.hpp"
#include "vc/interpreter/line_text.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::interpreter {
namespace {

using Kind = gcode::OWord::Kind;

constexpr int kCallLevels = 10;           // LinuxCNC's INTERP_SUB_ROUTINE_LEVELS
constexpr long kLoopLimit = 100'000'000;  // jumps back to one loop: beyond, an endless loop

const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::None:
      return "O number";
    case Kind::Sub:
      return "sub";
    case Kind::EndSub:
      return "endsub";
    case Kind::Call:
      return "call";
    case Kind::Do:
      return "do";
    case Kind::While:
      return "while";
    case Kind::EndWhile:
      return "endwhile";
    case Kind::If:
      return "if";
    case Kind::ElseIf:
      return "elseif";
    case Kind::Else:
      return "else";
    case Kind::EndIf:
      return "endif";
    case Kind::Break:
      return "break";
    case Kind::Continue:
      return "continue";
    case Kind::Return:
      return "return";
    case Kind::Repeat:
      return "repeat";
    case Kind::EndRepeat:
      return "endrepeat";
  }
  return "?";
}

// As written: "o100" or "o<name>" (a label local to a subroutine is kept as "sub#label").
std::string o_name(std::string name) {
  name = name.substr(name.find('#') + 1);
  return std::isdigit(static_cast<unsigned char>(name[0])) ? "o" + name : "o<" + name + ">";
}

// The value of a plain M word on the line, if it is M98 or M99 (-1 if none).
int subprogram_code(const gcode::Block& block, int& column) {
  for (const gcode::Word& w : block.words)
    if (w.letter == 'M')
      if (const double* v = boost::get<double>(&w.value); v && (*v == 98 || *v == 99)) {
        column = w.begin;
        return static_cast<int>(*v);
      }
  return -1;
}

}  // namespace

struct ProgramReader::Source {
  std::unique_ptr<std::ifstream> owned;
  std::istream* in = nullptr;
  long offset = 0;  // byte offset of the next line
  int line = 0;     // number of the last line read
};

ProgramReader::ProgramReader(std::istream& program, const std::string& program_name, Interpreter& interpreter,
                             std::vector<std::string> subroutine_path)
    : interpreter_(interpreter), subroutine_path_(std::move(subroutine_path)) {
  auto source = std::make_unique<Source>();
  source->in = &program;
  sources_.push_back(std::move(source));
  file_names_.push_back(program_name);
  gcode::Parameters& p = interpreter_.parameters();
  p.set("_value", 0.0);
  p.set("_value_returned", 0.0);
}

ProgramReader::~ProgramReader() = default;

long ProgramReader::program_bytes() const { return sources_.front()->offset; }

void ProgramReader::refuse(const Origin& origin, int column, const std::string& message) const {
  throw LoadError({file_names_[static_cast<std::size_t>(origin.file)], origin.line, column + 1}, message);
}

bool ProgramReader::read_line(std::string& raw, Origin& origin) {
  if (!injected_.empty()) {
    raw = std::move(injected_.front().first);
    origin = injected_.front().second;
    injected_.pop_front();
    return true;
  }
  Source& s = *sources_[static_cast<std::size_t>(current_)];
  line_start_ = s.offset;
  if (!std::getline(*s.in, raw)) return false;
  s.offset += static_cast<long>(raw.size()) + 1;
  origin = {current_, ++s.line};
  if (!raw.empty() && raw.back() == '\r') raw.pop_back();  // DOS line ends
  return true;
}

bool ProgramReader::next(std::string& raw, Origin& origin, gcode::Block& block, Effect& effect) {
  // Lines run while cutter compensation holds a move back wait here until it is final.
  while (true) {
    if (!held_.empty() && !interpreter_.holding_moves()) {
      Held& h = held_.front();
      raw = std::move(h.raw);
      origin = h.origin;
      block = std::move(h.block);
      effect = std::move(h.effect);
      held_.pop_front();
      return true;
    }
    if (!execute_next(raw, origin, block, effect)) {
      if (!held_.empty())
        refuse(held_.front().origin, 0,
               "the program ends while cutter compensation holds this line's move back (no G40, M2 or M30 after it)");
      return false;
    }
    for (ReleasedMove& r : interpreter_.released_moves()) {
      const auto h = std::find_if(held_.begin(), held_.end(), [&](const Held& x) { return x.sequence == r.sequence; });
      if (h == held_.end()) throw std::logic_error("cutter compensation released a move of a line not held");
      h->effect.moves.push_back(std::move(r.move));
    }
    interpreter_.released_moves().clear();
    if (held_.empty() && !interpreter_.holding_moves()) return true;
    held_.push_back({std::move(raw), origin, std::move(block), std::move(effect), interpreter_.sequence()});
  }
}

bool ProgramReader::execute_next(std::string& raw, Origin& origin, gcode::Block& block, Effect& effect) {
  if (ended_) return trailing_percent(raw, origin, block, effect);
  while (true) {
    if (!read_line(raw, origin)) {
      if (!skipping_to_.empty())
        refuse(origin, 0,
               skipping_to_sub_ ? "the file ends before subroutine " + o_name(skipping_to_) + " is defined (nor is " +
                                      skipping_to_ + ".ngc on the subroutine path)"
                                : "the file ends before the " + o_name(skipping_to_) + " that ends this block");
      if (!frames_.empty()) refuse(origin, 0, "the file ends inside subroutine " + o_name(frames_.back().name));
      return false;
    }
    const bool skipping = !skipping_to_.empty();
    try {
      pin_line_number(raw, origin.line, interpreter_.parameters());
      gcode::parse_block(raw, block);
    } catch (const gcode::SyntaxError& e) {
      if (skipping) continue;  // LinuxCNC does not read what it skips
      refuse(origin, e.offset, e.what());
    }
    if (control(block, origin)) continue;
    if (!frames_.empty() || needs_rewriting(raw)) {
      // Executed inside a call (or reading a call's result): written as it reads outside it.
      original_ = block;
      try {
        raw = evaluated_line(raw, block, interpreter_.parameters(), origin.line,
                             std::all_of(frames_.begin(), frames_.end(), [](const Frame& f) { return f.m98; }),
                             frames_.empty());
        gcode::parse_block(raw, block);
      } catch (const gcode::SyntaxError& e) {
        refuse(origin, e.offset, e.what());
      }
      const bool writes_assignments = !block.assignments.empty();
      block.assignments.clear();  // the parameters take the original line's assignments, once
      if (!writes_assignments && block.words.empty() && block.comments.empty() && !block.percent) {  // only local ones
        apply_original_assignments(origin);
        continue;
      }
    }
    interpreter_.set_file(file_names_[static_cast<std::size_t>(origin.file)]);
    interpreter_.execute(block, origin.line, effect);
    apply_original_assignments(origin);
    if (!effect.profile_subroutine.empty()) read_profile(effect, origin);
    inject(interpreter_.take_restore_lines(), origin);  // M72
    if (effect.program_end) ended_ = true;
    return true;
  }
}

void ProgramReader::read_profile(Effect& effect, const Origin& cycle) {
  // LinuxCNC calls the subroutine and reads its lines until it returns (interp_g7x.cc).
  const std::size_t level = frames_.size();
  const std::array<double, gcode::Parameters::kLocals> no_arguments{};
  call(effect.profile_subroutine, &no_arguments, false, 1, cycle, 0);
  std::string raw;
  Origin origin = cycle;
  gcode::Block block;
  while (frames_.size() > level) {
    if (!read_line(raw, origin)) {
      if (!skipping_to_.empty())
        refuse(cycle, 0,
               "the file ends before subroutine " + o_name(skipping_to_) +
                   " (the profile of this lathe cycle) is defined (nor is " + skipping_to_ +
                   ".ngc on the subroutine path)");
      refuse(origin, 0, "the file ends inside subroutine " + o_name(frames_.back().name));
    }
    try {
      pin_line_number(raw, origin.line, interpreter_.parameters());
      gcode::parse_block(raw, block);
    } catch (const gcode::SyntaxError& e) {
      if (!skipping_to_.empty()) continue;
      refuse(origin, e.offset, e.what());
    }
    if (control(block, origin)) continue;
    interpreter_.set_file(file_names_[static_cast<std::size_t>(origin.file)]);
    interpreter_.profile_block(block, origin.line);
  }
  interpreter_.set_file(file_names_[static_cast<std::size_t>(cycle.file)]);
  interpreter_.finish_lathe_cycle(effect);
}

bool ProgramReader::trailing_percent(std::string& raw, Origin& origin, gcode::Block& block, Effect& effect) {
  // LinuxCNC reads nothing after the program's end; the flat program keeps a closing '%' (of a
  // program that opens with one) and leaves out the rest (subroutine definitions, notes).
  if (current_ != 0) return false;
  while (read_line(raw, origin)) {
    try {
      gcode::parse_block(raw, block);
    } catch (const gcode::SyntaxError&) {
      continue;
    }
    if (!block.percent) continue;
    interpreter_.execute(block, origin.line, effect);
    return true;
  }
  return false;
}

void ProgramReader::apply_original_assignments(const Origin& origin) {
  if (original_.assignments.empty()) return;
  try {
    gcode::apply_assignments(original_, interpreter_.parameters());
  } catch (const gcode::SyntaxError& e) {
    refuse(origin, e.offset, e.what());
  }
  original_.clear();
}

bool ProgramReader::needs_rewriting(const std::string& raw) const {
  // Main-program lines keep their text, except those that read what a call leaves
  // (#<_value>, #<_value_returned>), the call level (the flat program makes no call) or the
  // interpreter's state (#<_x>, #<_feed>, #5420...: the pre-distorted program's differs; its
  // position by the correction, its motion mode where canned cycles are written out).
  if (raw.find('#') == std::string::npos) return false;
  std::string lower;
  for (char c : raw)
    if (c != ' ' && c != '\t') lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower.find("#<_") != std::string::npos || lower.find("#54") != std::string::npos;
}

double ProgramReader::argument(const gcode::OWord& o, const Origin& origin) const {
  try {
    return gcode::evaluate(o.args.front(), interpreter_.parameters(), o.begin);
  } catch (const gcode::SyntaxError& e) {
    refuse(origin, e.offset, e.what());
  }
}

ProgramReader::Label& ProgramReader::open_label(const gcode::OWord& o, const std::string& name, const Origin& origin) {
  const auto [it, added] = labels_.try_emplace(name, Label{o.kind, origin.file, line_start_, origin.line});
  if (!added && (it->second.line != origin.line || it->second.file != origin.file))
    refuse(origin, o.begin,
           o_name(name) + " is already used on line " + std::to_string(it->second.line) + " of " +
               file_names_[static_cast<std::size_t>(it->second.file)]);
  return it->second;
}

ProgramReader::Label& ProgramReader::label(const gcode::OWord& o, const std::string& name, const Origin& origin,
                                           std::initializer_list<Kind> kinds) {
  const auto it = labels_.find(name);
  if (it == labels_.end())
    refuse(origin, o.begin,
           std::string(kind_name(o.kind)) + " without its " + kind_name(*kinds.begin()) + ": " + o_name(name) +
               " is not open");
  if (std::find(kinds.begin(), kinds.end(), it->second.kind) == kinds.end())
    refuse(origin, o.begin,
           std::string(kind_name(o.kind)) + " does not match " + o_name(name) + " " + kind_name(it->second.kind) +
               " on line " + std::to_string(it->second.line));
  return it->second;
}

void ProgramReader::jump_to(const Label& label, const Origin& origin) {
  Source& s = *sources_[static_cast<std::size_t>(label.file)];
  s.in->clear();
  s.in->seekg(label.offset);
  if (!*s.in)
    refuse(origin, 0,
           "loops and calls of subroutines defined before need to read the program again: give it as a file, not a "
           "pipe");
  s.offset = label.offset;
  s.line = label.line - 1;
  current_ = label.file;
}

void ProgramReader::jump_back(Label& label, const Origin& origin) {
  if (++label.iterations > kLoopLimit)
    refuse(origin, 0, "the loop ran " + std::to_string(kLoopLimit) + " times: an endless loop?");
  jump_to(label, origin);
}

void ProgramReader::call(const std::string& name, const std::array<double, gcode::Parameters::kLocals>* arguments,
                         bool m98, long repeats, const Origin& origin, int column) {
  if (static_cast<int>(frames_.size()) + 1 >= kCallLevels)
    refuse(origin, column, "subroutine calls nested deeper than LinuxCNC's " + std::to_string(kCallLevels) + " levels");
  const Source& s = *sources_[static_cast<std::size_t>(current_)];
  Frame& f = frames_.emplace_back();
  interpreter_.enter_call_level();
  f.file = current_;
  f.offset = s.offset;
  f.line = s.line;
  f.m98 = m98;
  f.name = name;
  f.repeats_left = repeats - 1;
  gcode::Parameters& p = interpreter_.parameters();
  p.enter_scope(f.caller, arguments);

  if (const auto it = labels_.find(name); it != labels_.end()) {
    if (it->second.kind != (m98 ? Kind::None : Kind::Sub))
      refuse(origin, column,
             o_name(name) + " on line " + std::to_string(it->second.line) + " is not a " +
                 (m98 ? "subprogram (O number) for M98" : "subroutine (sub)"));
    jump_to(it->second, origin);
    return;
  }
  // Not defined yet: NAME.ngc on the subroutine path, else further on in this file.
  for (const std::string& folder : subroutine_path_) {
    const std::filesystem::path path = std::filesystem::path(folder) / (name + ".ngc");
    auto file = std::make_unique<std::ifstream>(path);
    if (!*file) continue;
    auto source = std::make_unique<Source>();
    source->in = file.get();
    source->owned = std::move(file);
    sources_.push_back(std::move(source));
    file_names_.push_back(path.string());
    current_ = static_cast<int>(sources_.size()) - 1;
    break;
  }
  skipping_to_ = name;
  skipping_to_sub_ = true;
}

void ProgramReader::leave(const Origin& origin) {
  Frame& f = frames_.back();
  if (f.repeats_left > 0) {  // M98 L: call again
    --f.repeats_left;
    jump_to(labels_.at(f.name), origin);
    return;
  }
  interpreter_.parameters().leave_scope(f.caller);
  Source& s = *sources_[static_cast<std::size_t>(f.file)];
  if (current_ != f.file || s.offset != f.offset) {
    s.in->clear();
    s.in->seekg(f.offset);
    if (!*s.in) refuse(origin, 0, "cannot return from the subroutine: the program cannot be read again (a pipe?)");
    s.offset = f.offset;
  }
  s.line = f.line;
  current_ = f.file;
  frames_.pop_back();
  interpreter_.leave_call_level();
  inject(interpreter_.take_restore_lines(), origin);
}

void ProgramReader::inject(const std::string& lines, const Origin& origin) {
  for (std::size_t begin = 0; begin < lines.size();) {
    const std::size_t end = lines.find('\n', begin);
    injected_.push_back({lines.substr(begin, end - begin), origin});
    begin = end == std::string::npos ? lines.size() : end + 1;
  }
}

bool ProgramReader::control(const gcode::Block& block, const Origin& origin) {
  int m_column = 0;
  const int m = block.o_word < 0 ? subprogram_code(block, m_column) : -1;
  if (block.o_word < 0 && m < 0) return !skipping_to_.empty();  // G-code: skipped or executed
  if (m >= 0 && !skipping_to_.empty()) return true;
  const gcode::OWord& o = block.o;
  std::string o_number = o.name;
  if (o.computed_name) {  // o[expression], o#n: the integer value names it (skipped lines: unknown)
    try {
      o_number = std::to_string(
          static_cast<long>(std::lround(gcode::evaluate(o.name_expression, interpreter_.parameters(), o.begin))));
    } catch (const gcode::SyntaxError& e) {
      if (!skipping_to_.empty()) return true;
      refuse(origin, e.offset, e.what());
    }
  }
  // LinuxCNC (interp_read.cc, read_o): sub, endsub, return and call name subroutines, global;
  // the other O words name labels local to the subroutine they are in ("sub#label").
  const bool global = o.kind == Kind::Sub || o.kind == Kind::None || o.kind == Kind::EndSub || o.kind == Kind::Call ||
                      o.kind == Kind::Return;
  const std::string name = m >= 0 || global ? o_number
                                            : (!frames_.empty() ? frames_.back().name
                                               : defining_sub_  ? defining_name_
                                                                : "") +
                                                  "#" + o_number;
  if (m < 0 && !skipping_to_.empty()) {
    if (name != skipping_to_) return true;
    if (skipping_to_sub_ && o.kind != Kind::Sub && o.kind != Kind::None) return true;
  }
  if (block.block_delete) refuse(origin, 0, "a block-delete ('/') line may not hold an O word, M98 or M99");

  if (m == 98) {
    for (const gcode::Word& w : block.words)
      if (w.letter != 'M' && w.letter != 'P' && w.letter != 'L')
        refuse(origin, w.begin, "M98 takes only P (program number) and L (repeats) on its line");
    const gcode::Word* p = nullptr;
    const gcode::Word* l = nullptr;
    for (const gcode::Word& w : block.words) {
      if (w.letter == 'P') p = &w;
      if (w.letter == 'L') l = &w;
    }
    if (!p) refuse(origin, m_column, "M98 needs P (the O number of the subprogram)");
    double number = 0, repeats = 1;
    try {
      number = gcode::evaluate(p->value, interpreter_.parameters(), p->begin);
      if (l) repeats = gcode::evaluate(l->value, interpreter_.parameters(), l->begin);
    } catch (const gcode::SyntaxError& e) {
      refuse(origin, e.offset, e.what());
    }
    if (number < 0 || number != std::floor(number)) refuse(origin, p->begin, "M98 P must be a whole number");
    if (repeats < 0 || repeats != std::floor(repeats) || repeats > 1e6)
      refuse(origin, l->begin, "M98 L must be a whole number 0..1000000");
    if (repeats == 0) return true;
    call(std::to_string(static_cast<long>(number)), nullptr, true, static_cast<long>(repeats), origin, m_column);
    return true;
  }
  if (m == 99) {
    for (const gcode::Word& w : block.words)
      if (w.letter != 'M') refuse(origin, w.begin, "M99 must be alone on its line");
    if (frames_.empty())
      refuse(origin, m_column, "M99 in the main program repeats it forever: a pre-distorted program must end");
    if (!frames_.back().m98) refuse(origin, m_column, "M99 ends an M98 subprogram; this is an O-word subroutine");
    leave(origin);
    return true;
  }
  for (const gcode::Word& w : block.words) refuse(origin, w.begin, "an O-word line holds no other words");
  // Inside a definition only its end matters; a call is never made while skipping.
  if (defining_sub_ && o.kind != Kind::Sub && o.kind != Kind::None && o.kind != Kind::EndSub && o.kind != Kind::Return)
    return true;
  if (o.kind == Kind::Call && !skipping_to_.empty()) return true;

  switch (o.kind) {
    case Kind::None:
    case Kind::Sub: {
      if (!skipping_to_.empty()) open_label(o, name, origin);  // found by a call looking for it
      const bool called = skipping_to_sub_ || !frames_.empty();
      skipping_to_.clear();
      skipping_to_sub_ = false;
      if (o.kind == Kind::None || called) break;  // a Fanuc O number runs on; a call enters
      if (defining_sub_) refuse(origin, o.begin, "a subroutine cannot be defined inside another");
      open_label(o, name, origin);
      skipping_to_ = name;  // the definition: skipped up to its endsub
      defining_sub_ = true;
      defining_name_ = name;
      break;
    }
    case Kind::EndSub:
    case Kind::Return:
      if (frames_.empty()) {
        if (!defining_sub_) refuse(origin, o.begin, std::string(kind_name(o.kind)) + " outside a subroutine");
        if (o.kind == Kind::EndSub) {
          skipping_to_.clear();
          defining_sub_ = false;
        }
        break;
      }
      if (frames_.back().m98) refuse(origin, o.begin, "an M98 subprogram ends with M99");
      {
        // LinuxCNC sets the returned value when it reads the line: 0 (not returned) without one.
        const double value = o.args.empty() ? 0.0 : argument(o, origin);
        gcode::Parameters& p = interpreter_.parameters();
        leave(origin);
        p.set("_value", value);
        p.set("_value_returned", o.args.empty() ? 0.0 : 1.0);
      }
      break;
    case Kind::Call: {
      std::array<double, gcode::Parameters::kLocals> arguments{};
      for (std::size_t i = 0; i < o.args.size(); ++i) {
        try {
          arguments[i] = gcode::evaluate(o.args[i], interpreter_.parameters(), o.begin);
        } catch (const gcode::SyntaxError& e) {
          refuse(origin, e.offset, e.what());
        }
      }
      call(o_number, &arguments, false, 1, origin, o.begin);
      break;
    }
    case Kind::Do:
      skipping_to_.clear();
      if (!labels_.count(name)) open_label(o, name, origin);
      break;
    case Kind::Repeat: {
      Label& l = open_label(o, name, origin);
      skipping_to_.clear();
      if (l.repeats_left == -1) l.repeats_left = std::lround(argument(o, origin));
      if (l.repeats_left > 0) {
        --l.repeats_left;
      } else {
        skipping_to_ = name;
        l.repeats_left = -1;
      }
      break;
    }
    case Kind::While: {
      const auto known = labels_.find(name);
      const bool end_of_do = known != labels_.end() && known->second.kind == Kind::Do;
      if (!end_of_do) open_label(o, name, origin);
      skipping_to_.clear();
      const bool condition = argument(o, origin) != 0.0;
      if (end_of_do) {
        if (condition && !doing_break_) jump_back(known->second, origin);
        doing_break_ = false;
      } else if (!condition) {
        skipping_to_ = name;
      }
      break;
    }
    case Kind::If:
      open_label(o, name, origin);
      if (argument(o, origin) != 0.0) {
        skipping_to_.clear();
        executed_if_ = true;
      } else {
        skipping_to_ = name;
        executed_if_ = false;
      }
      break;
    case Kind::ElseIf:
      label(o, name, origin, {Kind::If});
      if (executed_if_) {
        skipping_to_ = name;
      } else if (argument(o, origin) != 0.0) {
        skipping_to_.clear();
        executed_if_ = true;
      }
      break;
    case Kind::Else:
      label(o, name, origin, {Kind::If});
      if (executed_if_) {
        skipping_to_ = name;
      } else if (skipping_to_ == name) {
        skipping_to_.clear();
        executed_if_ = true;
      }
      break;
    case Kind::EndIf:
      label(o, name, origin, {Kind::If});
      skipping_to_.clear();
      executed_if_ = true;
      break;
    case Kind::Break:
      label(o, name, origin, {Kind::While, Kind::Do});
      skipping_to_ = name;
      doing_break_ = true;
      break;
    case Kind::Continue:
      label(o, name, origin, {Kind::While, Kind::Do});
      if (skipping_to_ != name) {
        skipping_to_ = name;
        doing_continue_ = true;
      }
      break;
    case Kind::EndWhile:
    case Kind::EndRepeat: {
      Label& l = label(o, name, origin, {o.kind == Kind::EndWhile ? Kind::While : Kind::Repeat});
      if (skipping_to_ == name) {
        skipping_to_.clear();
        if (doing_continue_) {
          doing_continue_ = false;
          jump_back(l, origin);
        }
        // A break leaves doing_break set: LinuxCNC 2.9 clears it only at the end of a do loop,
        // which then runs once. Kept, so that the flat program does what the machine does.
      } else {
        jump_back(l, origin);
      }
      break;
    }
  }
  return true;
}

}  // namespace vc::interpreter
