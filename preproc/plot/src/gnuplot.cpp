#include "vc/plot/gnuplot.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace vc::plot {
namespace {

namespace fs = std::filesystem;

// A file made by mkstemp, removed when this goes out of scope unless it was renamed into place.
class TemporaryFile {
 public:
  // `pattern` ends in XXXXXX.
  explicit TemporaryFile(std::string pattern, const std::string& what) : path_(std::move(pattern)) {
    const int fd = ::mkstemp(path_.data());
    if (fd < 0) throw std::runtime_error("cannot create a temporary file for " + what + " (does its folder exist?)");
    ::close(fd);
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile() {
    std::error_code ignored;
    if (!path_.empty()) fs::remove(path_, ignored);
  }
  const std::string& path() const { return path_; }
  // Renamed over `target` (same file system), readable by all like any file the user writes.
  void move_to(const std::string& target) {
    fs::permissions(path_,
                    fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
    fs::rename(path_, target);
    path_.clear();
  }

 private:
  std::string path_;
};

// The pattern of a temporary file beside `target` (the same folder: a rename is atomic).
std::string beside(const fs::path& target) {
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  return (folder / ("." + target.filename().string() + ".XXXXXX")).string();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The last lines of gnuplot's messages: where its script failed.
std::string tail(const std::string& text, std::size_t lines) {
  std::size_t at = text.size();
  while (at > 0 && std::isspace(static_cast<unsigned char>(text[at - 1]))) --at;
  const std::size_t end = at;
  for (std::size_t n = 0; at > 0 && n < lines; --at)
    if (text[at - 1] == '\n' && ++n == lines) break;
  return text.substr(at, end - at);
}

}  // namespace

std::string data_path(const std::string& image) { return fs::path(image).replace_extension(".csv").string(); }

std::string text_literal(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n')
      out += "\\n";
    else
      out += c;
  }
  return out + "\"";
}

void draw(const Figure& figure) {
  std::string extension = fs::path(figure.image).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const std::string size = " size " + std::to_string(figure.width) + "," + std::to_string(figure.height);
  std::string terminal;
  if (extension == ".png")
    terminal = "set terminal pngcairo" + size + " noenhanced font 'sans,11'";
  else if (extension == ".svg")
    terminal = "set terminal svg" + size + " dynamic noenhanced font 'sans,11' background '#ffffff'";
  else
    throw std::runtime_error("--plot " + figure.image +
                             ": the picture is a .png or an .svg file (its extension chooses)");
  const std::string data = data_path(figure.image);

  TemporaryFile image_part(beside(figure.image), figure.image), data_part(beside(data), data);
  TemporaryFile script((fs::temp_directory_path() / "volcomp-plot-XXXXXX").string(), "the gnuplot script");
  TemporaryFile messages((fs::temp_directory_path() / "volcomp-gnuplot-XXXXXX").string(), "gnuplot's messages");
  {
    std::ofstream out(data_part.path(), std::ios::binary | std::ios::trunc);
    out << figure.data;
    if (!out.flush()) throw std::runtime_error("cannot write " + data_part.path());
  }
  {
    std::ofstream gp(script.path(), std::ios::trunc);
    gp << terminal << "\nset output " << text_literal(image_part.path())
       << "\nset encoding utf8\nDATA = " << text_literal(data_part.path()) << "\n"
       << figure.script << "\nunset output\n";
    if (!gp.flush()) throw std::runtime_error("cannot write the gnuplot script " + script.path());
  }
  // The shell finds gnuplot on PATH; 127 is the shell's "command not found".
  const int status = std::system(("gnuplot '" + script.path() + "' >/dev/null 2>'" + messages.path() + "'").c_str());
  const int code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == 127)
    throw std::runtime_error("gnuplot was not found (is it installed and on PATH?): the plot " + figure.image +
                             " was not written");
  if (code != 0)
    throw std::runtime_error("gnuplot failed (exit " + std::to_string(code) + "): the plot " + figure.image +
                             " was not written; gnuplot said: " + tail(read_text(messages.path()), 4));
  const std::string image = read_text(image_part.path());
  const bool valid = extension == ".png"
                         ? image.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0
                         : image.find("<svg") != std::string::npos && image.find("</svg>") != std::string::npos;
  if (!valid)
    throw std::runtime_error("gnuplot wrote no valid " + extension.substr(1) + " image: the plot " + figure.image +
                             " was not written");
  data_part.move_to(data);
  image_part.move_to(figure.image);
}

}  // namespace vc::plot
