// The HAL commands of a LinuxCNC configuration, in the order LinuxCNC runs them, each with
// its file and line: the [HAL]HALFILE files, the [HAL]POSTTASK_HALFILE files (task runs them
// when it starts, which LinuxCNC does just before the HALCMDs), the [HAL]HALCMD entries, then
// the [HAL]POSTGUI_HALFILE files (the GUI runs those last).
//
// As LinuxCNC 2.9 finds and reads them (scripts/linuxcnc, src/hal/utils/halcmd.c):
// - a HALFILE is taken from the configuration folder, else from the HAL library
//   (/usr/share/linuxcnc/hallib, or $HALLIB_DIR); `LIB:name` from the library only; words
//   after the name are the file's arguments; `.tcl` files are run by haltcl: not read here
//   (HalFileUse::read is false), the caller says so;
// - in a HAL file '#' starts a comment (outside quotes), a line ending in '\' continues, and
//   `[SECTION]KEY` / `[SECTION](KEY)` is replaced by the INI's value (an undefined one is
//   refused with its line, as halcmd stops there); a HALCMD entry is run as it is written;
// - `source FILE` (halcmd_commands.cc do_source_cmd) runs FILE's commands at that point: FILE
//   is opened as written (after the line's INI references are replaced; `~/` expanded), from the
//   configuration folder (LinuxCNC runs halcmd there); its lines are not continued with '\\';
//   its INI references are replaced when the chain began in a HAL file (halcmd -i INI), and
//   refused when it began in a HALCMD (LinuxCNC runs those without -i: halcmd stops there). A
//   missing FILE and a file that sources itself (a loop) are refused at the source line.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vc/init/linuxcnc_ini.hpp"

namespace vc::init {

// A word of a command as written: where it is in its line's text.
struct HalToken {
  std::size_t offset = 0, length = 0;
};

struct HalCommand {
  std::string path;                // the HAL file, or the INI file (or an included one) for a HALCMD
  int line = 0;                    // first line
  int last_line = 0;               // last line (continued with '\')
  bool in_ini = false;             // a [HAL]HALCMD entry
  std::string text;                // the first line, trimmed
  std::vector<HalToken> tokens;    // the words as written, in the first line's text
  std::vector<std::string> words;  // the words halcmd runs (references replaced, quotes removed)
  std::vector<int> word_token;     // the token each word comes from

  SourceLocation where() const { return {path, line}; }
  // The word is its token exactly (no reference that expands to several words): the patch can
  // remove or replace that token.
  bool word_is_token(int word) const;
};

// A [HAL]HALFILE, POSTTASK_HALFILE or POSTGUI_HALFILE entry and the file LinuxCNC runs for it.
struct HalFileUse {
  std::string key;                  // HALFILE, POSTTASK_HALFILE or POSTGUI_HALFILE
  std::string written;              // the entry's value: file name and arguments
  std::string path;                 // the file found
  std::string cite;                 // the INI line naming it
  bool read = false;                // false: a Tcl file, not read
  const IniEntry* entry = nullptr;  // the INI entry naming it
};

// A `source FILE` command and the file it runs.
struct HalSource {
  std::size_t command = 0;  // the source command, in HalConfig::commands
  std::string path;         // the file, absolute
  std::string cite;         // the source line
};

struct HalConfig {
  std::vector<TextFile> files;       // the HAL files read
  std::vector<HalFileUse> uses;      // every HAL file entry, in LinuxCNC's order
  std::vector<HalSource> sources;    // every source command, in LinuxCNC's order
  std::vector<HalCommand> commands;  // in LinuxCNC's order

  const TextFile* file(const std::string& path) const;
};

// Throws vc::LoadError (file:line) for a HAL file that cannot be found or read and for an
// undefined [SECTION]KEY reference.
HalConfig read_hal(const LinuxcncIni& ini);

// `net SIGNAL [<=|=>|<=>] PIN ...`: the signal and its pins. A pin after "=>" or before "<="
// is marked as read from the signal (halcmd does not check the arrows; they say what the
// author meant, nothing more).
struct NetPin {
  std::string name;
  int word = 0;
  bool reader = false;
};
struct Net {
  std::string signal;
  std::vector<NetPin> pins;
};
std::optional<Net> net_of(const HalCommand& command);
// The first net that puts `pin` on a signal (HAL links a pin to one signal at most) and that
// signal, or nullptr.
const HalCommand* net_of_pin(const HalConfig& hal, const std::string& pin, std::string* signal = nullptr);

// `setp PIN VALUE` or `PIN = VALUE` (halcmd's short form), and `sets SIGNAL VALUE`.
struct Assignment {
  std::string target, value;
  int target_word = 0;
};
std::optional<Assignment> setp_of(const HalCommand& command);
std::optional<Assignment> sets_of(const HalCommand& command);

// `loadrt MODULE ARG...`, and `loadusr [-w] [-W] [-i] [-n NAME] PROGRAM ARG...` (halcmd's
// options; module: the program as written).
struct Load {
  std::string module;
  std::vector<std::string> arguments;
};
std::optional<Load> loadrt_of(const HalCommand& command);
std::optional<Load> loadusr_of(const HalCommand& command);

}  // namespace vc::init
