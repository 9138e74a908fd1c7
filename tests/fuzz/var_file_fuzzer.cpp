// libFuzzer target: any bytes as a LinuxCNC parameter file (.var) through read_var_file.
// Refusal (vc::LoadError) is the expected answer to bad input; a crash, a hang, a sanitizer
// report, any other exception or an accepted file that breaks what linuxcnc_files.hpp
// promises (one parameter per line read, so no more than the lines; finite values) is a finding.
#include <algorithm>
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "vc/interpreter/linuxcnc_files.hpp"
#include "vc/tables/source_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (vc::fuzz::scratch() / "input.var").string();
  const std::string_view text = vc::fuzz::text_of(data, size);
  vc::fuzz::write_file(path, text);
  vc::gcode::Parameters parameters;
  try {
    const int count = vc::interpreter::read_var_file(path, parameters);
    const auto lines = std::count(text.begin(), text.end(), '\n') + 1;
    if (count < 0 || count > lines)
      vc::fuzz::finding(std::to_string(count) + " parameters read from " + std::to_string(lines) + " lines");
    for (int i = 1; i < vc::gcode::Parameters::kCount; ++i)
      if (!std::isfinite(parameters[i])) vc::fuzz::finding("parameter " + std::to_string(i) + " is not finite");
  } catch (const vc::LoadError&) {
  } catch (const std::exception& e) {
    vc::fuzz::finding(std::string("not a vc::LoadError: ") + e.what());
  }
  return 0;
}
