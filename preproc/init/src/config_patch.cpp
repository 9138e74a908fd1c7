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

// The edits of every file, created on first use; only files inside the configuration folder,
// and the #INCLUDEd files when they are copied (a copy goes into the folder).
class Edits {
 public:
  Edits(const LinuxcncIni& ini, const HalConfig& hal, bool copy_includes)
      : ini_(ini), hal_(hal), copy_includes_(copy_includes) {}

  bool patchable(const std::string& path) const { return display_path(path, ini_.folder()) != path; }
  bool included(const std::string& path) const {
    for (const IniInclude& include : ini_.includes())
      if (include.path == path) return true;
    return false;
  }

  FileEdits& of(const std::string& path, const SourceLocation& where, const std::string& what) {
    if (!patchable(path) && !(copy_includes_ && included(path)))
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
  const bool copy_includes_;
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
  Patcher(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& k, const NominalMachine& m,
          const PatchOptions& options)
      : ini_(ini),
        hal_(hal),
        k_(k),
        m_(m),
        options_(options),
        edits_(ini, hal, !options.edit_shared),
        prefix_(k.module + ".") {}

  ConfigPatch run(const std::string& machine_path) {
    ConfigPatch patch;
    kinematics_ = patch.kinematics = kinematics_value(machine_path);
    replace_kinematics(patch.kinematics);
    for (const HalCommand& c : hal_.commands) rewrite(c);
    remove_sets_of_emptied_signals();
    append_to_hal_section();
    patch.remarks = remarks_;
    copy_shared_files();
    for (const FileEdits* e : edits_.files()) {
      const std::string name = display_path(e->file().path, ini_.folder());
      const FileEdits::Counts n = e->counts();
      const auto copy = copies_.find(e->file().path);
      if (copy == copies_.end()) {
        patch.diff += e->unified_diff(name);
        patch.changes.push_back(name + ": " + std::to_string(n.removed) + " line(s) out, " + std::to_string(n.added) +
                                " in");
        continue;
      }
      const std::string copy_name = display_path(copy->second.path, ini_.folder());
      // A first line says what the copy is (and keeps a copy whose every line went from being empty).
      std::vector<TextLine> lines = e->result();
      lines.insert(lines.begin(),
                   TextLine{"# volcomp init: " + ini_.path().substr(ini_.folder().size() + 1) + "'s copy of " + name +
                                " (other configurations use that one), " + "volkins in place of " + k_.module,
                            lines.empty() || lines.front().end.empty() ? "\n" : lines.front().end});
      patch.diff += creation_diff(copy_name, lines);
      patch.created.push_back(copy->second.path);
      patch.changes.push_back(copy_name + ": new, a copy of " + name + " for this configuration with its " +
                              std::to_string(n.removed) + " line(s) out, " + std::to_string(n.added) + " in");
      patch.remarks.push_back(name + " is left as it is: " + copy->second.why + "; its edits go to the new " +
                              copy_name + ", which " + copy->second.named_by +
                              " now names (volcomp init --edit-shared edits it in place instead, which changes "
                              "every configuration that uses it)");
    }
    return patch;
  }

 private:
  // A file this configuration shares with others, and the copy the patch makes of it.
  struct Copy {
    std::string path;      // the copy, absolute
    std::string why;       // why it is shared
    std::string named_by;  // the lines that name the copy
  };

  // Why `path` is shared, or "" if it is this configuration's own.
  std::string shared(const std::string& path) const {
    if (options_.edit_shared || path == ini_.path()) return "";
    if (edits_.included(path)) return "an #INCLUDEd file, which other configurations may include too";
    const auto it = options_.shared_hal_files.find(path);
    return it == options_.shared_hal_files.end() ? "" : it->second;
  }

  // Shared files stay as they are; their edits go to a copy, which this configuration's lines
  // then name. Naming it is an edit of another file, which may be shared in turn.
  void copy_shared_files() {
    for (bool more = true; more;) {
      more = false;
      for (const FileEdits* e : edits_.files()) {
        const std::string path = e->file().path;
        const std::string why = shared(path);
        if (why.empty() || copies_.count(path)) continue;
        Copy& copy = copies_[path];
        copy.path = free_copy_name(path);
        copy.why = why;
        copy.named_by = name_the_copy(path, display_path(copy.path, ini_.folder()));
        more = true;
        break;  // edits_ has changed
      }
    }
  }

  // `<name>.volkins<ext>` beside the file (in the configuration folder if the file is outside
  // it), `<name>.volkins-2<ext>` ... if that exists.
  std::string free_copy_name(const std::string& path) const {
    const fs::path file = path;
    const fs::path folder = edits_.patchable(path) ? file.parent_path() : fs::path(ini_.folder());
    for (int n = 1;; ++n) {
      const fs::path candidate = folder / (file.stem().string() + ".volkins" + (n == 1 ? "" : "-" + std::to_string(n)) +
                                           file.extension().string());
      bool taken = fs::exists(fs::symlink_status(candidate));
      for (const auto& [original, copy] : copies_) taken = taken || copy.path == candidate.string();
      if (!taken) return candidate.string();
    }
  }

  // Every line of this configuration that names `path` names `name` instead (the copy, relative
  // to the configuration folder: LinuxCNC looks #INCLUDEs, HALFILEs and sourced files up from
  // there); which lines, for the summary.
  std::string name_the_copy(const std::string& path, const std::string& name) {
    std::vector<std::string> lines;
    for (const IniInclude& include : ini_.includes()) {
      if (include.path != path) continue;
      FileEdits& f = edits_.of(ini_.path(), {ini_.path(), include.line}, "#INCLUDE");
      const std::string& text = f.file().line(include.line).text;
      f.replace(include.line,
                text.substr(0, include.name_offset) + name + text.substr(include.name_offset + include.written.size()));
      lines.push_back(display_path(ini_.path(), ini_.folder()) + ":" + std::to_string(include.line));
    }
    for (const HalFileUse& use : hal_.uses) {
      if (use.path != path || !use.entry) continue;
      const IniEntry& e = *use.entry;
      if (e.line != e.last_line)
        throw LoadError(e.where(), e.key +
                                       " continues on the next line ('\\'): write it on one line for init to "
                                       "name the copy of " +
                                       display_path(path, ini_.folder()) + " there");
      FileEdits& f = edits_.of(e.path, e.where(), "[HAL]" + e.key);
      const std::string& text = f.file().line(e.line).text;
      const std::size_t end = text.find_first_of(" \t", e.value_offset);
      f.replace(e.line, text.substr(0, e.value_offset) + name + (end == std::string::npos ? "" : text.substr(end)));
      lines.push_back(display_path(e.path, ini_.folder()) + ":" + std::to_string(e.line));
    }
    for (const HalSource& source : hal_.sources) {
      if (source.path != path) continue;
      const HalCommand& c = hal_.commands[source.command];
      if (!c.word_is_token(1))
        throw LoadError(c.where(), "the file of " + quoted_line(c.text) +
                                       " comes from an INI reference: write "
                                       "its name for init to name the copy of " +
                                       display_path(path, ini_.folder()));
      FileEdits& f = edits_for(c, "sources a file the patch copies");
      f.replace(c.line, rewritten(c, f.file().line(c.line).text, {{c.word_token[1], name}}));
      lines.push_back(display_path(c.path, ini_.folder()) + ":" + std::to_string(c.line));
    }
    std::string text;
    for (const std::string& line : lines) text += (text.empty() ? "" : ", ") + line;
    return text;
  }

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
    FileEdits& f = edits_.of(c.path, c.where(), quoted_line(c.text) + " " + what);
    if (c.line != c.last_line)
      throw LoadError(c.where(), quoted_line(c.text) + " " + what +
                                     " and continues on the next line ('\\'): write it on one "
                                     "line for init to rewrite it");
    return f;
  }

  void check_pin(const HalCommand& c, const std::string& pin, int word) const {
    const std::string name = pin.substr(prefix_.size());
    if (std::find(m_.pins.begin(), m_.pins.end(), name) == m_.pins.end())
      throw LoadError(c.where(), k_.module + " has no pin " + pin + (m_.pins.empty() ? " (it has none)" : ""));
    if (!c.word_is_token(word))
      throw LoadError(c.where(), pin + " comes from an INI reference in " + quoted_line(c.text) +
                                     ": write the pin's name for init to rewrite the line");
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
        throw LoadError(c.where(), quoted_line(c.text) + " names " + c.words[w] +
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
      throw LoadError(c.where(), quoted_line(c.text) + " loads " + k_.module +
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
    const std::string joints = upper(m_.coordinates);
    const std::string loaded =
        coordinates.empty() ? std::string("XYZABCUVW").substr(0, joints.size()) : upper(coordinates);
    const std::string* ini_type = k_.parameter("kinstype");
    return loaded == joints && trivkins_type(kinstype.empty() ? nullptr : &kinstype) == trivkins_type(ini_type);
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
    net_locking_indexers(lines);
    edits_.of(path, {path, after}, "the [HAL] section").insert_after(after, lines);
  }

  // A joint LinuxCNC runs as a locking indexer ([JOINT_n]LOCKING_INDEXER, a boolean as its
  // inifile reads one): volkins reads the indexer's unlock request and the clamp's answer on the
  // same signals as motion (its volkins.joint.N.unlock and .is-unlocked), so that it holds the
  // joint's correction while the clamp is engaged and corrects the tip with the other joints.
  void net_locking_indexers(std::vector<std::string>& lines) {
    for (std::size_t k = 0; k < m_.coordinates.size(); ++k) {
      const std::string section = "JOINT_" + std::to_string(k);
      const IniEntry* e = ini_.find(section, "LOCKING_INDEXER");
      if (!e || !ini_true(*e)) continue;
      const char letter = static_cast<char>(std::tolower(static_cast<unsigned char>(m_.coordinates[k])));
      const std::size_t principal = std::min(m_.coordinates.find(letter),
                                             m_.coordinates.find(static_cast<char>(std::toupper(letter))));
      if (letter < 'a' || letter > 'c')
        throw LoadError(e->where(), "joint " + std::to_string(k) + " (" +
                                        std::string(1, static_cast<char>(std::toupper(letter))) +
                                        ") is a locking indexer, and volkins holds rotary joints only (a clamped "
                                        "linear joint could not take its correction): make it a rotary axis's "
                                        "joint or remove LOCKING_INDEXER");
      if (principal != k)
        throw LoadError(e->where(), "joint " + std::to_string(k) + " is a locking indexer and the second joint of " +
                                        std::string(1, m_.coordinates[k]) +
                                        ": volkins follows the clamp of an axis's first joint only");
      const std::string joint = "joint." + std::to_string(k) + ".", volkins = "volkins." + joint;
      lines.push_back("# joint " + std::to_string(k) + " is a locking indexer (" + ini_.cite(*e) +
                      "): volkins holds its correction while it is clamped");
      remarks_.push_back("joint " + std::to_string(k) + " is a locking indexer (" + ini_.cite(*e) +
                         "): volkins reads its unlock and is-unlocked and, while the clamp holds it, keeps its "
                         "correction and corrects the tip's position with the other joints (kins/README.md, "
                         "\"Clamped rotary axes\")");
      for (const char* pin : {"unlock", "is-unlocked"}) {
        std::string signal;  // motion's pin on a signal of its own, or on a new one
        net_of_pin(hal_, joint + pin, &signal);
        lines.push_back("HALCMD = net " +
                        (signal.empty() ? ":volkins-joint-" + std::to_string(k) + "-" + pin + " " + joint + pin
                                        : signal) +
                        " " + volkins + pin);
      }
    }
  }

  // LinuxCNC's inifile reads a boolean as 1/0, TRUE/FALSE, YES/NO, ON/OFF (any case).
  static bool ini_true(const IniEntry& e) {
    std::string v = e.value;
    for (char& ch : v) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    if (v == "1" || v == "TRUE" || v == "YES" || v == "ON") return true;
    if (v == "0" || v == "FALSE" || v == "NO" || v == "OFF") return false;
    throw LoadError(e.where(), e.key + " = " + e.value + ": LinuxCNC reads a boolean there (1 or 0, TRUE or FALSE)");
  }

  const LinuxcncIni& ini_;
  const HalConfig& hal_;
  const KinematicsLine& k_;
  const NominalMachine& m_;
  const PatchOptions& options_;
  Edits edits_;
  std::map<std::string, Copy> copies_;  // original -> its copy
  const std::string prefix_;
  std::string kinematics_;
  bool tool_offset_replaced_ = false;
  std::vector<std::string> remarks_;  // for the summary
  std::map<std::string, int> nets_;  // signal -> nets kept on it
};

}  // namespace

ConfigPatch patch_config(const LinuxcncIni& ini, const HalConfig& hal, const KinematicsLine& kinematics,
                         const NominalMachine& machine, const std::string& machine_path, const PatchOptions& options) {
  return Patcher(ini, hal, kinematics, machine, options).run(machine_path);
}

}  // namespace vc::init
