#include "vc/init/output_check.hpp"

#include <filesystem>
#include <stdexcept>

#include "vc/init/text_file.hpp"

namespace vc::init {

namespace fs = std::filesystem;

bool same_file(const std::string& a, const std::string& b) {
  std::error_code error;
  if (fs::exists(a, error) && fs::exists(b, error)) return fs::equivalent(a, b, error);
  const fs::path ca = fs::weakly_canonical(fs::absolute(a), error);
  const fs::path cb = fs::weakly_canonical(fs::absolute(b), error);
  return ca.lexically_normal() == cb.lexically_normal() || absolute_path(a) == absolute_path(b);
}

void refuse_input_as_output(const std::vector<InputFile>& inputs, const std::string& option, const std::string& path) {
  for (const InputFile& input : inputs)
    if (same_file(path, input.path))
      throw std::runtime_error("error: " + option + " " + printable(path) + " is " + printable(input.path) + ", " +
                               input.what + ", which init reads: init never overwrites its inputs; choose " +
                               "another file (nothing was written)");
}

}  // namespace vc::init
