// M70-M73: saving the modal state and restoring it (LinuxCNC 2.9's save_settings and
// restore_settings, interp_convert.cc). LinuxCNC restores by running G-code it writes from the
// difference between the state saved and the state now (gen_settings, gen_m_codes): units
// first, then F and S (always, F with one decimal, S with none), the G codes that differ, the
// path mode, then the M codes that differ. Here the same text is made and run as lines of the
// flat program (ProgramReader), so that the pre-distorted program restores by itself what the
// original restored: it has no subroutine to return from and no saved state of its own.
#include "vc/tables/number_text.hpp"
#include "words.hpp"

namespace vc::interpreter {
namespace {

// LinuxCNC's G code values as it writes them into the text (x10: 591 is G59.1).
std::string code_text(char letter, int code_x10) {
  return std::string(" ") + letter + std::to_string(code_x10 / 10) +
         (code_x10 % 10 ? "." + std::to_string(code_x10 % 10) : std::string());
}

}  // namespace

Interpreter::ModalState Interpreter::modal_state() const {
  ModalState s;
  s.inches = inches_;
  s.g[0] = plane_;
  s.g[1] = compensation_.side() == CutterCompensation::kLeft    ? G_41
           : compensation_.side() == CutterCompensation::kRight ? G_42
                                                                : G_40;
  s.g[2] = incremental_ ? G_91 : G_90;
  s.g[3] = inverse_time_ ? G_93 : G_94;
  s.g[4] = coordinate_system_ < 7 ? G_53 + 10 * coordinate_system_ : G_59_1 + coordinate_system_ - 7;  // G54 .. G59.3
  s.g[5] = tool_offset_ != 0.0 ? G_43 : G_49;
  s.g[6] = retract_to_r_ ? G_99 : G_98;
  s.g[7] = constant_surface_speed_ ? G_96 : G_97;
  s.g[8] = arc_absolute_ ? G_90_1 : G_91_1;
  s.g[9] = G_8;  // G8: radius mode (G7 is not translated)
  s.g[10] = parameters_[kG92Applied] != 0.0 ? G_92_3 : -1;
  s.path_mode = path_mode_;
  s.path_p = path_p_ < 0 ? -1.0 : path_p_ / (inches_ ? kInch : 1.0);  // as the program gave it
  s.feed = feed_;
  s.speed = spindle_rpm_;
  s.m[0] = !spindle_on_ ? 5 : spindle_clockwise_ ? 3 : 4;
  s.m[1] = mist_ ? 7 : flood_ ? -1 : 9;
  s.m[2] = flood_ ? 8 : -1;
  s.m[3] = feed_override_ ? (spindle_override_ ? 48 : 50) : spindle_override_ ? 51 : 49;
  s.m[4] = adaptive_feed_ ? 52 : -1;
  s.m[5] = feed_hold_ ? 53 : -1;
  return s;
}

void Interpreter::state_codes(const Words& w, int line, Effect& effect) {
  const Words::Code* code = w.find_m({M_70, M_71, M_72, M_73});
  if (!code) return;
  for (const Words::Code& g : w.g) refuse(line, g.offset, "M70-M73 are translated on a line of their own");
  for (const Words::Code& m : w.m)
    if (m.index != code->index) refuse(line, m.offset, "M70-M73 are translated on a line of their own");
  for (int i = 0; i < static_cast<int>(w.letters.size()); ++i)
    if (w.letters[static_cast<std::size_t>(i)].has && i != static_cast<int>(Words::slot('M')))
      refuse(line, w.letters[static_cast<std::size_t>(i)].offset, "M70-M73 are translated on a line of their own");
  effect.dropped_words.push_back(code->index);  // what they do is written out instead
  const std::size_t level = static_cast<std::size_t>(call_level_);
  if (contexts_.size() <= level) contexts_.resize(level + 1);
  Context& context = contexts_[level];
  switch (code->code) {
    case M_70:
    case M_73:
      context.saved = modal_state();
      context.restore_on_return = code->code == M_73 && call_level_ > 0;
      break;
    case M_71:
      context.saved.reset();
      break;
    case M_72:
      if (!context.saved)
        refuse(line, code->offset, "cannot restore context from invalid stack frame - missing M70/M73?");
      restore_lines_ = restore_text(*context.saved);
      break;
  }
}

std::string Interpreter::restore_text(const ModalState& saved) const {
  const ModalState now = modal_state();
  std::string text;
  if (saved.inches != now.inches) text += saved.inches ? "G20\n" : "G21\n";
  text += " F" + fixed_text(saved.feed, 1) + " S" + fixed_text(saved.speed, 0);
  for (std::size_t i = 0; i < saved.g.size(); ++i)
    if (saved.g[i] != now.g[i] && saved.g[i] != -1) {
      if (i == 1) throw std::logic_error("cutter compensation differs at M72");  // refused before
      text += code_text('G', saved.g[i]);
    }
  if (saved.path_mode == G_64)
    text += saved.path_p < 0 ? std::string(" G64") : " G64 P" + fixed_text(saved.path_p, 6);
  else if (saved.path_mode != now.path_mode)
    text += code_text('G', saved.path_mode);
  for (std::size_t i = 0; i < saved.m.size(); ++i)
    if (saved.m[i] != now.m[i] && saved.m[i] != -1) text += "M" + std::to_string(saved.m[i]) + "\n";
  if (text.back() != '\n') text += '\n';
  return text;
}

void Interpreter::enter_call_level() {
  ++call_level_;
  const std::size_t level = static_cast<std::size_t>(call_level_);
  if (contexts_.size() <= level) contexts_.resize(level + 1);
  contexts_[level] = Context{};
}

void Interpreter::leave_call_level() {
  const std::size_t level = static_cast<std::size_t>(call_level_);
  --call_level_;
  if (level < contexts_.size() && contexts_[level].saved && contexts_[level].restore_on_return)
    restore_lines_ = restore_text(*contexts_[level].saved);  // M73: restored on return
  if (level < contexts_.size()) contexts_[level] = Context{};
}

std::string Interpreter::take_restore_lines() {
  std::string lines;
  lines.swap(restore_lines_);
  return lines;
}

}  // namespace vc::interpreter
