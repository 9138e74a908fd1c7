#include "vc/init/shared_files.hpp"

#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

namespace vc::init {
namespace {

namespace fs = std::filesystem;

std::string expand_home(std::string name) {
  if (name.rfind("~/", 0) == 0)
    if (const char* home = std::getenv("HOME")) name = home + name.substr(1);
  return name;
}

std::string hallib_folder() {
  const char* dir = std::getenv("HALLIB_DIR");
  return dir && *dir ? dir : "/usr/share/linuxcnc/hallib";
}

// The words of a HAL line before its comment (quotes not needed here: file names).
std::vector<std::string> words_of(const std::string& line) {
  std::istringstream in(line.substr(0, line.find('#')));
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

class Collector {
 public:
  Collector(const std::string& folder, const std::string& user, std::map<std::string, std::string>& files)
      : folder_(folder), user_(user), files_(files) {}

  void add(const fs::path& file) {
    if (!fs::is_regular_file(file)) return;
    const std::string path = absolute_path(file.string());
    if (!seen_.insert(path).second) return;
    files_.emplace(path, user_ + " uses it too");
    if (file.extension() == ".tcl") return;
    // The files it sources (relative to the configuration folder, as halcmd opens them).
    try {
      for (const TextLine& line : read_text_file(path, "HAL file").lines) source(words_of(line.text));
    } catch (const LoadError&) {  // not a text file: nothing it sources is known
    }
  }

  void source(const std::vector<std::string>& words) {
    if (words.size() != 2 || words[0] != "source" || words[1].find('[') != std::string::npos) return;
    const fs::path name = expand_home(words[1]);
    add(name.is_absolute() ? name : fs::path(folder_) / name);
  }

 private:
  const std::string folder_, user_;
  std::map<std::string, std::string>& files_;
  std::set<std::string> seen_;
};

}  // namespace

SharedFiles files_shared_in_folder(const LinuxcncIni& ini) {
  SharedFiles shared;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(ini.folder(), error)) {
    if (entry.path().extension() != ".ini" || !entry.is_regular_file(error)) continue;
    const std::string path = absolute_path(entry.path().string());
    if (path == ini.path() || fs::equivalent(path, ini.path(), error)) continue;
    shared.inis.push_back(path);
    const std::string name = display_path(path, ini.folder());
    LinuxcncIni other;
    try {
      other = LinuxcncIni::read(path);
    } catch (const LoadError& e) {
      shared.remarks.push_back("the folder's " + name + " cannot be read (" + printable(e.what()) +
                               "): whether it uses a file the patch changes is not checked");
      continue;
    }
    Collector collect(ini.folder(), name, shared.files);
    for (const IniInclude& include : other.includes()) shared.files.emplace(include.path, name + " includes it too");
    for (const char* key : {"HALFILE", "POSTTASK_HALFILE", "POSTGUI_HALFILE"})
      for (const IniEntry* e : other.find_all("HAL", key)) {
        const std::vector<std::string> words = words_of(e->value);
        if (words.empty()) continue;
        const std::string file = expand_home(words[0]);
        if (file.rfind("LIB:", 0) == 0) continue;  // not in the folder
        if (fs::path(file).is_absolute()) {
          collect.add(file);
        } else if (fs::is_regular_file(fs::path(ini.folder()) / file)) {
          collect.add(fs::path(ini.folder()) / file);
        } else {
          collect.add(fs::path(hallib_folder()) / file);
        }
      }
    for (const IniEntry* e : other.find_all("HAL", "HALCMD")) collect.source(words_of(e->value));
  }
  return shared;
}

}  // namespace vc::init
