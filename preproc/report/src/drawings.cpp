#include "vc/report/drawings.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace vc::report {

namespace fs = std::filesystem;

Drawings::Drawings() {
  std::string pattern = (fs::temp_directory_path() / "volcomp-report-XXXXXX").string();
  if (!::mkdtemp(pattern.data()))
    throw std::runtime_error("cannot make a scratch folder for the report's pictures in " +
                             fs::temp_directory_path().string());
  folder_ = pattern;
}

Drawings::~Drawings() {
  std::error_code ignored;
  fs::remove_all(folder_, ignored);
}

std::string Drawings::path(const std::string& name) const { return (fs::path(folder_) / name).string(); }

std::string Drawings::png(const plot::Figure& figure) const {
  plot::draw(figure);
  std::ifstream in(figure.image, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in || bytes.str().empty()) throw std::runtime_error("cannot read back the picture " + figure.image);
  return bytes.str();
}

}  // namespace vc::report
