// libFuzzer target: any bytes as a LinuxCNC tool table (.tbl) through read_tool_table, in a
// machine set up in mm and in inches. Refusal (vc::LoadError) is the expected answer to bad
// input; a crash, a hang, a sanitizer report, any other exception or an accepted table that
// breaks what linuxcnc_files.hpp promises (each entry under its own number, >= 0; finite
// offsets and diameter; orientation 0..9) is a finding.
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "vc/interpreter/linuxcnc_files.hpp"
#include "vc/tables/source_error.hpp"

namespace {

void check(const vc::interpreter::ToolTable& table) {
  for (const auto& [number, tool] : table) {
    if (number != tool.number || number < 0)
      vc::fuzz::finding("tool " + std::to_string(tool.number) + " filed as " + std::to_string(number));
    for (const double v : tool.offset)
      if (!std::isfinite(v)) vc::fuzz::finding("a non-finite offset");
    if (!std::isfinite(tool.diameter) || !std::isfinite(tool.front_angle) || !std::isfinite(tool.back_angle))
      vc::fuzz::finding("a non-finite diameter or angle");
    if (tool.orientation < 0 || tool.orientation > 9) vc::fuzz::finding("orientation out of 0..9");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (vc::fuzz::scratch() / "input.tbl").string();
  vc::fuzz::write_file(path, vc::fuzz::text_of(data, size));
  for (const double unit_mm : {1.0, 25.4}) {
    try {
      check(vc::interpreter::read_tool_table(path, unit_mm));
    } catch (const vc::LoadError&) {
    } catch (const std::exception& e) {
      vc::fuzz::finding(std::string("not a vc::LoadError: ") + e.what());
    }
  }
  return 0;
}
