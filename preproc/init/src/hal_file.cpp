#include "vc/init/hal_file.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace vc::init {
namespace {

namespace fs = std::filesystem;

bool blank(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

// The text up to a '#' outside quotes (halcmd's strip_comments).
std::size_t comment_start(const std::string& text, std::size_t from) {
  char quote = 0;
  for (std::size_t i = from; i < text.size(); ++i) {
    if (quote) {
      if (text[i] == quote) quote = 0;
    } else if (text[i] == '\'' || text[i] == '"') {
      quote = text[i];
    } else if (text[i] == '#') {
      return i;
    }
  }
  return text.size();
}

// Blank-separated words of text[from, to), quotes keeping blanks inside a word.
std::vector<HalToken> split(const std::string& text, std::size_t from, std::size_t to) {
  std::vector<HalToken> tokens;
  std::size_t i = from;
  while (i < to) {
    while (i < to && blank(text[i])) ++i;
    if (i >= to) break;
    const std::size_t start = i;
    char quote = 0;
    for (; i < to && (quote || !blank(text[i])); ++i)
      if (quote ? text[i] == quote : (text[i] == '\'' || text[i] == '"')) quote = quote ? 0 : text[i];
    tokens.push_back({start, i - start});
  }
  return tokens;
}

std::string unquoted(const std::string& word) {
  std::string s;
  for (char c : word)
    if (c != '\'' && c != '"') s += c;
  return s;
}

// halcmd's replace_vars for INI references: [SECTION]KEY and [SECTION](KEY); $ENV is left as
// written (LinuxCNC sets its own variables when it runs the file).
std::string replace_references(const std::string& token, const LinuxcncIni& ini, const SourceLocation& where) {
  static const char* const kKeyCharacters = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.-_";
  std::string out;
  for (std::size_t i = 0; i < token.size();) {
    if (token[i] != '[') {
      out += token[i++];
      continue;
    }
    const std::size_t close = token.find(']', i);
    if (close == std::string::npos)
      throw LoadError(where, "'[' without ']' in " + quoted_line(token) + " (halcmd stops here)");
    const std::string section = token.substr(i + 1, close - i - 1);
    std::size_t key_start = close + 1, key_end;
    if (key_start < token.size() && token[key_start] == '(') {
      key_end = token.find(')', ++key_start);
      if (key_end == std::string::npos)
        throw LoadError(where, "'(' without ')' in " + quoted_line(token) + " (halcmd stops here)");
      i = key_end + 1;
    } else {
      key_end = key_start;
      while (key_end < token.size() && std::strchr(kKeyCharacters, token[key_end])) ++key_end;
      i = key_end;
    }
    const std::string key = token.substr(key_start, key_end - key_start);
    const std::string reference = "[" + section + "]" + key;
    if (key.empty()) throw LoadError(where, quoted_line(reference) + " names no INI key (halcmd stops here)");
    const IniEntry* value = ini.find(section, key);  // []KEY: any section, as halcmd
    if (!value)
      throw LoadError(where, printable(reference) + " is not defined in " + display_path(ini.path(), ini.folder()) +
                                 ": halcmd stops at this line (LinuxCNC would not start)");
    out += value->value;
  }
  return out;
}

// How a command's INI references are taken: replaced (halcmd -i INI), left as written (a
// HALCMD: halcmd gets it as arguments), or refused (a file sourced from a HALCMD: halcmd has no
// INI file to look them up in).
enum class References { kReplace, kAsWritten, kRefuse };

HalCommand command_from(const std::string& path, int line, int last_line, bool in_ini, const std::string& text,
                        std::size_t from, const LinuxcncIni& ini, References references) {
  HalCommand c;
  c.path = path;
  c.line = line;
  c.last_line = last_line;
  c.in_ini = in_ini;
  c.text = trim(text);
  c.tokens = split(text, from, comment_start(text, from));
  for (std::size_t t = 0; t < c.tokens.size(); ++t) {
    const std::string written = text.substr(c.tokens[t].offset, c.tokens[t].length);
    if (references == References::kRefuse && written.find('[') != std::string::npos)
      throw LoadError(c.where(), quoted_line(written) +
                                     " in a file sourced from a [HAL]HALCMD: LinuxCNC runs HALCMDs "
                                     "without the INI file (no halcmd -i), so halcmd cannot replace "
                                     "an INI reference there and stops at this line");
    const std::string expanded =
        references == References::kReplace ? replace_references(written, ini, c.where()) : written;
    for (const HalToken& w : split(expanded, 0, expanded.size())) {
      c.words.push_back(unquoted(expanded.substr(w.offset, w.length)));
      c.word_token.push_back(expanded == written ? static_cast<int>(t) : -1 - static_cast<int>(t));
    }
  }
  return c;
}

std::string hallib_folder() {
  const char* dir = std::getenv("HALLIB_DIR");
  return dir && *dir ? dir : "/usr/share/linuxcnc/hallib";
}

// The file LinuxCNC runs for a HALFILE entry's name: LIB:name from the library, an absolute
// path as it is, else the configuration folder first, then the library.
std::string find_hal_file(std::string name, const IniEntry& entry, const LinuxcncIni& ini) {
  if (!name.empty() && name[0] == '~')
    if (const char* home = std::getenv("HOME")) name = home + name.substr(1);
  std::vector<fs::path> candidates;
  if (name.rfind("LIB:", 0) == 0) {
    candidates.push_back(fs::path(hallib_folder()) / name.substr(4));
  } else if (fs::path(name).is_absolute()) {
    candidates.push_back(name);
  } else {
    candidates.push_back(fs::path(ini.folder()) / name);
    candidates.push_back(fs::path(hallib_folder()) / name);
  }
  for (const fs::path& p : candidates)
    if (fs::is_regular_file(p)) return absolute_path(p.string());
  throw LoadError(entry.where(), entry.key + " " + name + ": no such file in " +
                                     (candidates.size() == 2 ? ini.folder() + " nor in " : std::string()) +
                                     candidates.back().parent_path().string() + " (LinuxCNC would not start)");
}

bool is_tcl(const std::string& path) { return fs::path(path).extension() == ".tcl"; }

// Reads HAL files and the files their `source` commands run, in halcmd's order.
class HalReader {
 public:
  HalReader(const LinuxcncIni& ini, HalConfig& hal) : ini_(ini), hal_(hal) {}

  // A HALFILE's file (halcmd -f: lines continued with '\\', INI references replaced).
  void read_file(const std::string& path) { read(path, true, References::kReplace); }

  // A command just added to hal_.commands: if it is `source FILE`, FILE's commands follow it.
  void follow_source(References references) {
    const std::size_t index = hal_.commands.size() - 1;
    const HalCommand& c = hal_.commands[index];
    if (c.words.empty() || c.words[0] != "source") return;
    if (c.words.size() != 2)
      throw LoadError(c.where(), quoted_line(c.text) + ": source takes one file name (halcmd refuses this line)");
    std::string written = c.words[1];
    if (written.rfind("~/", 0) == 0)  // halcmd's A_TILDE
      if (const char* home = std::getenv("HOME")) written = home + written.substr(1);
    const fs::path name = written;
    // halcmd opens the name as it is (no library), from LinuxCNC's working folder: the
    // configuration folder.
    const std::string path = absolute_path((name.is_absolute() ? name : fs::path(ini_.folder()) / name).string());
    if (const std::string why = unreadable_reason(path); !why.empty())
      throw LoadError(c.where(), "source " + printable(c.words[1]) + ": cannot read " + path + ": " + why +
                                     " (halcmd opens it from the configuration folder; LinuxCNC would not start)");
    if (std::find(stack_.begin(), stack_.end(), path) != stack_.end())
      throw LoadError(c.where(), "source " + printable(c.words[1]) + ": a loop: " + display_path(path, ini_.folder()) +
                                     " is running this file already (halcmd would source them in turn until it runs "
                                     "out of open files)");
    hal_.sources.push_back({index, path, cite(c.path, c.line, c.text, ini_.folder())});
    read(path, false, references == References::kReplace ? References::kReplace : References::kRefuse);
  }

 private:
  void read(const std::string& path, bool continued_lines, References references) {
    const TextFile file = read_text_file(path, "HAL file");
    hal_.files.push_back(file);
    stack_.push_back(file.path);
    const int count = static_cast<int>(file.lines.size());
    for (int n = 1; n <= count; ++n) {
      std::string text = file.line(n).text;
      const int first = n;
      // halcmd -f continues a line ending in '\\'; source (do_source_cmd) reads line by line.
      while (continued_lines && !text.empty() && text.back() == '\\' && n < count) {
        text.pop_back();
        text += file.line(++n).text;
      }
      HalCommand c = command_from(file.path, first, n, false, text, 0, ini_, references);
      if (c.words.empty()) continue;
      hal_.commands.push_back(std::move(c));
      follow_source(references);
    }
    stack_.pop_back();
  }

  const LinuxcncIni& ini_;
  HalConfig& hal_;
  std::vector<std::string> stack_;  // the files being read, outermost first
};

}  // namespace

bool HalCommand::word_is_token(int word) const {
  const int token = word_token[static_cast<std::size_t>(word)];
  if (token < 0) return false;
  int words_of_token = 0;
  for (int t : word_token) words_of_token += t == token;
  return words_of_token == 1;
}

const TextFile* HalConfig::file(const std::string& path) const {
  for (const TextFile& f : files)
    if (f.path == path) return &f;
  return nullptr;
}

HalConfig read_hal(const LinuxcncIni& ini) {
  HalConfig hal;
  auto uses_of = [&](const char* key) {
    std::vector<HalFileUse> uses;
    for (const IniEntry* e : ini.find_all("HAL", key)) {
      const std::vector<HalToken> words = split(e->value, 0, e->value.size());
      if (words.empty()) continue;
      const std::string name = e->value.substr(words[0].offset, words[0].length);
      HalFileUse use{key, e->value, find_hal_file(name, *e, ini), ini.cite(*e), false, e};
      use.read = !is_tcl(use.path);
      uses.push_back(use);
    }
    return uses;
  };
  const std::vector<HalFileUse> halfiles = uses_of("HALFILE"), posttask = uses_of("POSTTASK_HALFILE"),
                                postgui = uses_of("POSTGUI_HALFILE");
  HalReader reader(ini, hal);
  auto run = [&](const std::vector<HalFileUse>& uses) {
    for (const HalFileUse& use : uses) {
      hal.uses.push_back(use);
      if (use.read) reader.read_file(use.path);
    }
  };
  run(halfiles);
  run(posttask);
  for (const IniEntry* e : ini.find_all("HAL", "HALCMD")) {
    const TextFile* file = nullptr;
    for (const TextFile& f : ini.files())
      if (f.path == e->path) file = &f;
    const bool one_line = e->line == e->last_line;
    // A HALCMD runs as written (no INI references): halcmd gets it as its arguments.
    HalCommand c = command_from(e->path, e->line, e->last_line, true, one_line ? file->line(e->line).text : e->value,
                                one_line ? e->value_offset : 0, ini, References::kAsWritten);
    c.text = e->text;
    if (c.words.empty()) continue;
    hal.commands.push_back(std::move(c));
    reader.follow_source(References::kAsWritten);
  }
  run(postgui);
  return hal;
}

std::optional<Net> net_of(const HalCommand& c) {
  if (c.words.size() < 2 || c.words[0] != "net") return std::nullopt;
  Net net{c.words[1], {}};
  bool after_out_arrow = false;  // after "=>": readers
  for (int w = 2; w < static_cast<int>(c.words.size()); ++w) {
    const std::string& word = c.words[static_cast<std::size_t>(w)];
    if (word == "=>" || word == "<=>") {
      after_out_arrow = word == "=>";
      continue;
    }
    if (word == "<=") {  // what stands before it is read from the signal
      for (NetPin& p : net.pins) p.reader = true;
      after_out_arrow = false;
      continue;
    }
    net.pins.push_back({word, w, after_out_arrow});
  }
  return net;
}

const HalCommand* net_of_pin(const HalConfig& hal, const std::string& pin, std::string* signal) {
  for (const HalCommand& c : hal.commands)
    if (const auto net = net_of(c))
      for (const NetPin& p : net->pins)
        if (p.name == pin) {
          if (signal) *signal = net->signal;
          return &c;
        }
  return nullptr;
}

std::optional<Assignment> setp_of(const HalCommand& c) {
  if (c.words.size() == 3 && c.words[0] == "setp") return Assignment{c.words[1], c.words[2], 1};
  if (c.words.size() == 3 && c.words[1] == "=") return Assignment{c.words[0], c.words[2], 0};
  return std::nullopt;
}

std::optional<Assignment> sets_of(const HalCommand& c) {
  if (c.words.size() == 3 && c.words[0] == "sets") return Assignment{c.words[1], c.words[2], 1};
  return std::nullopt;
}

std::optional<Load> loadrt_of(const HalCommand& c) {
  if (c.words.size() < 2 || c.words[0] != "loadrt") return std::nullopt;
  return Load{c.words[1], std::vector<std::string>(c.words.begin() + 2, c.words.end())};
}

// halcmd's do_loadusr_cmd: getopt "+wWin:", the first other word is the program.
std::optional<Load> loadusr_of(const HalCommand& c) {
  if (c.words.empty() || c.words[0] != "loadusr") return std::nullopt;
  std::size_t w = 1;
  for (; w < c.words.size() && c.words[w].size() > 1 && c.words[w][0] == '-'; ++w) {
    const std::string& options = c.words[w];
    const std::size_t n = options.find('n');
    if (n != std::string::npos && n + 1 == options.size()) ++w;  // -n NAME, -Wn NAME: the name is the next word
  }
  if (w >= c.words.size()) return std::nullopt;
  return Load{c.words[w], std::vector<std::string>(c.words.begin() + static_cast<long>(w) + 1, c.words.end())};
}

}  // namespace vc::init
