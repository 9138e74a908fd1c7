#include "vc/init/config_patch.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "vc/init/unified_diff.hpp"

namespace vc::init {
namespace {

namespace fs = std::filesystem;

// The edits of every file, created on first use; only files inside the configuration folder.
class Edits {
 public:
  Edits(const LinuxcncIni& ini, const HalConfig& hal) : ini_(ini), hal_(hal) {}

  bool patchable(const std::string& path) const { return display_path(path, ini_.folder()) != path; }

  FileEdits& of(const std::string& path, const SourceLocation& where, const std::string& what) {
    if (!patchable(path))
      throw LoadError(where, what + ", in a file outside the configuration folder " + ini_.folder() +
                                 ": init patches the configuration's own files only (copy the file into the folder "
                                 "and name it from the INI)");
    const auto it = edits_.find(path);
    if (it != edits_.end()) return it->second;
    const TextFile* file = hal_.file(path);
    for (const TextFile& f : ini_.files())
      if (f.path == path) file = &f;
    return edits_.emplace(path, FileEdits(*file)).first->second;
  }

  // The INI file first, then the others by name.
  std::vector<const FileEdits*> files() const {
    std::vector<const FileEdits*> all;
    for (const auto& [path, e] : edits_)
      if (!e.empty()) all.push_back(&e);
    std::stable_sort(all.begin(), all.end(), [&](const FileEdits* a, const FileEdits* b) {
      return (a->file().path == ini_.path()) > (b->file().path == ini_.path());
    });
    return all;
  }

 private:
  const LinuxcncIni& ini_;
  const HalConfig& hal_;
  std::map<std::string, FileEdits> edits_;
};

// One command's line with tokens replaced ("" text) or removed (nullopt), right to left; a
// removed token takes the blanks before it along.
std::string rewritten(const HalCommand& c, const std::string& line, std::map<int, std::optional<std::string>> tokens) {
  std::string text = line;
  for (auto it = tokens.rbegin(); it != tokens.rend(); ++it) {
    const HalToken& t = c.tokens[static_cast<std::size_t>(it->first)];
    if (it->second) {
      text.replace(t.offset, t.length, *it->second);
    } else {
      std::size_t start = t.offset;
      while (start > 0 && (text[start - 1] == ' ' || text[start - 1] == '\t')) --start;
      text.erase(start, t.offset + t.length - start);
    }
  }
  return text;
}

class Patcher {
 public:
  Patcher(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& k, const NominalMachine& m)
      : ini_(ini), hal_(hal), k_(k), m_(m), edits_(ini, hal), prefix_(k.module + ".") {}

  ConfigPatch run(const std::string& machine_path) {
    ConfigPatch patch;
    kinematics_ = patch.kinematics = kinematics_value(machine_path);
    replace_kinematics(patch.kinematics);
    for (const HalCommand& c : hal_.commands) rewrite(c);
    remove_sets_of_emptied_signals();
    append_to_hal_section();
    for (const FileEdits* e : edits_.files()) {
      const std::string name = display_path(e->file().path, ini_.folder());
      patch.diff += e->unified_diff(name);
      const FileEdits::Counts n = e->counts();
      patch.changes.push_back(name + ": " + std::to_string(n.removed) + " line(s) out, " + std::to_string(n.added) +
                              " in");
    }
    return patch;
  }

 private:
  std::string kinematics_value(const std::string& machine_path) const {
    if (machine_path.find_first_of(" \t") != std::string::npos)
      throw LoadError(k_.entry->where(), "the machine file's path `" + machine_path +
                                             "` has a blank, and LinuxCNC splits KINEMATICS at blanks: choose "
                                             "another -o");
    return "volkins machine=" + machine_path + " coordinates=" + m_.coordinates +
           (m_.world.empty() ? "" : " world=" + m_.world) + (m_.identity_first ? " sparm=identityfirst" : "") +
           (m_.units.inch() ? " units=inch" : "");
  }

  void replace_kinematics(const std::string& value) {
    const IniEntry& e = *k_.entry;
    if (e.line != e.last_line)
      throw LoadError(e.where(),
                      "KINEMATICS continues on the next line ('\\'): write it on one line for init to replace it");
    FileEdits& f = edits_.of(e.path, e.where(), "[KINS]KINEMATICS");
    f.replace(e.line, f.file().line(e.line).text.substr(0, e.value_offset) + value);
  }

  bool is_stock_pin(const std::string& word) const { return word.rfind(prefix_, 0) == 0; }

  FileEdits& edits_for(const HalCommand& c, const std::string& what) {
    FileEdits& f = edits_.of(c.path, c.where(), "`" + c.text + "` " + what);
    if (c.line != c.last_line)
      throw LoadError(c.where(), "`" + c.text + "` " + what +
                                     " and continues on the next line ('\\'): write it on one "
                                     "line for init to rewrite it");
    return f;
  }

  void check_pin(const HalCommand& c, const std::string& pin, int word) const {
    const std::string name = pin.substr(prefix_.size());
    if (std::find(m_.pins.begin(), m_.pins.end(), name) == m_.pins.end())
      throw LoadError(c.where(), k_.module + " has no pin " + pin + (m_.pins.empty() ? " (it has none)" : ""));
    if (!c.word_is_token(word))
      throw LoadError(c.where(), pin + " comes from an INI reference in `" + c.text +
                                     "`: write the pin's name for init to rewrite the line");
  }

  void rewrite(const HalCommand& c) {
    if (const auto setp = setp_of(c); setp && is_stock_pin(setp->target)) {
      check_pin(c, setp->target, setp->target_word);
      edits_for(c, "sets a " + k_.module + " pin").remove(c.line);
      return;
    }
    if (const auto net = net_of(c)) {
      std::map<int, std::optional<std::string>> tokens;
      int left = 0;
      for (const NetPin& p : net->pins) {
        if (!is_stock_pin(p.name)) {
          ++left;
          continue;
        }
        check_pin(c, p.name, p.word);
        const int token = c.word_token[static_cast<std::size_t>(p.word)];
        if (p.name == prefix_ + m_.tool_offset_pin) {
          tokens[token] = "volkins.tool-offset";
          tool_offset_replaced_ = true;
          ++left;
        } else {
          tokens[token] = std::nullopt;
        }
      }
      int& kept = nets_[net->signal];  // nets left on the signal
      if (tokens.empty()) {
        ++kept;
        return;
      }
      FileEdits& f = edits_for(c, "nets a " + k_.module + " pin");
      if (left == 0) {
        f.remove(c.line);
      } else {
        remove_dangling_arrows(c, tokens);
        f.replace(c.line, rewritten(c, f.file().line(c.line).text, tokens));
        ++kept;
      }
      return;
    }
    if (c.words.size() >= 2 && c.words[0] == "loadrt" && c.words[1] == k_.module && c.word_token[1] >= 0) {
      rewrite_loadrt(c);
      return;
    }
    for (std::size_t w = 0; w < c.words.size(); ++w)
      if (is_stock_pin(c.words[w]))
        throw LoadError(c.where(), "`" + c.text + "` names " + c.words[w] +
                                       ": init rewrites the setp and net lines of " + k_.module +
                                       " pins only; change this one by hand (volkins has no such pin)");
  }

  // An arrow left before another arrow or at the end of a net whose pins were removed goes too
  // (`net :p sum.out => 5axiskins.pivot-length` -> `net :p sum.out`; halcmd ignores arrows).
  static void remove_dangling_arrows(const HalCommand& c, std::map<int, std::optional<std::string>>& tokens) {
    auto removed = [&](int word) {
      const int token = c.word_token[static_cast<std::size_t>(word)];
      const auto it = tokens.find(token);
      return token >= 0 && it != tokens.end() && !it->second;
    };
    auto arrow = [&](int word) {
      const std::string& w = c.words[static_cast<std::size_t>(word)];
      return w == "=>" || w == "<=" || w == "<=>";
    };
    bool next_is_arrow_or_end = true;  // of the words kept after this one
    for (int w = static_cast<int>(c.words.size()) - 1; w >= 2; --w) {
      if (removed(w)) continue;
      if (arrow(w) && next_is_arrow_or_end && c.word_is_token(w)) {
        tokens[c.word_token[static_cast<std::size_t>(w)]] = std::nullopt;
        continue;
      }
      next_is_arrow_or_end = arrow(w);
    }
  }

  // `loadrt <module> ...` written out (not `loadrt [KINS]KINEMATICS`): fine if it loads what
  // [KINS]KINEMATICS says.
  void rewrite_loadrt(const HalCommand& c) {
    std::multiset<std::string> here(c.words.begin() + 1, c.words.end()), ini;
    std::istringstream words(k_.entry->value);
    for (std::string w; words >> w;) ini.insert(w);
    if (here != ini && !same_trivkins(c))
      throw LoadError(c.where(), "`" + c.text + "` loads " + k_.module +
                                     " with other parameters than [KINS]KINEMATICS (" + ini_.cite(*k_.entry) +
                                     "): make them the same (`loadrt [KINS]KINEMATICS`)");
    FileEdits& f = edits_for(c, "loads " + k_.module);
    const std::string& line = f.file().line(c.line).text;
    const HalToken& first = c.tokens[1];
    const HalToken& last = c.tokens.back();
    // A HALCMD is run without INI references: it gets volkins' line written out.
    const std::string value = c.in_ini ? kinematics_ : std::string("[KINS]KINEMATICS");
    f.replace(c.line, line.substr(0, first.offset) + value + line.substr(last.offset + last.length));
  }

  // trivkins loaded as written here and as [KINS]KINEMATICS says are the same kinematics when
  // they map the same letters to the joints (trivkins' default coordinates=XYZABCUVW maps joint n
  // to the n-th letter; the letters' case does not matter) and have the same kinstype (trivkins.c:
  // B, F or I by its first letter, any other the identity).
  bool same_trivkins(const HalCommand& c) const {
    if (k_.kind != StockModule::Trivkins) return false;
    std::string coordinates, kinstype;
    for (std::size_t w = 2; w < c.words.size(); ++w) {
      const std::string& word = c.words[w];
      if (word.rfind("coordinates=", 0) == 0)
        coordinates = word.substr(12);
      else if (word.rfind("kinstype=", 0) == 0)
        kinstype = word.substr(9);
      else
        return false;
    }
    const auto upper = [](std::string s) {
      for (char& ch : s) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
      return s;
    };
    const auto type = [&](const std::string* t) {
      const char first = t && !t->empty() ? upper(*t)[0] : '1';
      return first == 'B' || first == 'F' || first == 'I' ? first : '1';
    };
    const std::string joints = upper(m_.coordinates);
    const std::string loaded =
        coordinates.empty() ? std::string("XYZABCUVW").substr(0, joints.size()) : upper(coordinates);
    const std::string* ini_type = k_.parameter("kinstype");
    return loaded == joints && type(kinstype.empty() ? nullptr : &kinstype) == type(ini_type);
  }

  // A `sets` of a signal whose nets were all deleted would fail: deleted too.
  void remove_sets_of_emptied_signals() {
    for (const HalCommand& c : hal_.commands)
      if (const auto sets = sets_of(c)) {
        const auto it = nets_.find(sets->target);
        if (it != nets_.end() && it->second == 0)
          edits_for(c, "sets a signal that only " + k_.module + " pins were on").remove(c.line);
      }
  }

  void append_to_hal_section() {
    const IniSection* hal = ini_.section("HAL");
    if (!hal)
      throw LoadError({ini_.path()}, "no [HAL] section: LinuxCNC needs one, and init adds volkins' lines to it");
    std::string path = hal->path;
    int after = hal->line;
    if (!hal->entries.empty()) {
      path = hal->entries.back().path;
      after = hal->entries.back().last_line;
    }
    std::vector<std::string> lines{
        "# volkins (volcomp init): its update function runs first in the servo thread" +
            std::string(tool_offset_replaced_ ? "" : "; it takes LinuxCNC's tool length offset"),
        "HALCMD = addf volkins.update servo-thread 1"};
    if (!tool_offset_replaced_) {
      std::string signal;
      for (const HalCommand& c : hal_.commands)
        if (const auto net = net_of(c))
          for (const NetPin& p : net->pins)
            if (p.name == "motion.tooloffset.z" && signal.empty()) signal = net->signal;
      lines.push_back(signal.empty() ? "HALCMD = net :volkins-tool-offset motion.tooloffset.z volkins.tool-offset"
                                     : "HALCMD = net " + signal + " volkins.tool-offset");
    }
    edits_.of(path, {path, after}, "the [HAL] section").insert_after(after, lines);
  }

  const LinuxcncIni& ini_;
  const HalConfig& hal_;
  const KinematicsLine& k_;
  const NominalMachine& m_;
  Edits edits_;
  const std::string prefix_;
  std::string kinematics_;
  bool tool_offset_replaced_ = false;
  std::map<std::string, int> nets_;  // signal -> nets kept on it
};

}  // namespace

ConfigPatch patch_config(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& kinematics,
                         const NominalMachine& machine, const std::string& machine_path) {
  return Patcher(ini, hal, kinematics, machine).run(machine_path);
}

}  // namespace vc::init
