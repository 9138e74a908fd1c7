// libFuzzer target: any bytes as a circular test (ballbar CSV, either layout) through
// read_circular_test, then evaluated as `volcomp identify circle` does (evaluate_circular_test).
// Refusal is the expected answer to bad input: vc::LoadError from the reader,
// std::runtime_error (documented) from the evaluation. A crash, a hang, a sanitizer report,
// any other exception or a result that breaks what circular_test.hpp promises (plane XY, YZ
// or ZX; a run per direction present; finite points, ordered by angle) is a finding.
#include <cmath>
#include <stdexcept>
#include <string>

#include "fuzz_support.hpp"
#include "vc/identify/iso230_4.hpp"
#include "vc/tables/source_error.hpp"

namespace {

void check(const vc::identify::CircularTest& t) {
  if (t.plane != "XY" && t.plane != "YZ" && t.plane != "ZX") vc::fuzz::finding("accepted plane '" + t.plane + "'");
  if (t.runs.empty() || t.runs.size() > 2) vc::fuzz::finding("accepted " + std::to_string(t.runs.size()) + " runs");
  for (const auto& run : t.runs)
    for (std::size_t i = 0; i < run.points.size(); ++i) {
      if (!std::isfinite(run.points[i].first) || !std::isfinite(run.points[i].second))
        vc::fuzz::finding("a non-finite point");
      if (i > 0 && run.points[i - 1].first > run.points[i].first) vc::fuzz::finding("points not ordered by angle");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (vc::fuzz::scratch() / "input.csv").string();
  vc::fuzz::write_file(path, vc::fuzz::text_of(data, size));
  vc::identify::CircularTest test;
  try {
    test = vc::identify::read_circular_test(path);
  } catch (const vc::LoadError&) {
    return 0;
  } catch (const std::exception& e) {
    vc::fuzz::finding(std::string("read_circular_test: not a vc::LoadError: ") + e.what());
  }
  check(test);
  try {
    (void)vc::identify::evaluate_circular_test(test);
  } catch (const std::runtime_error&) {
  } catch (const std::exception& e) {
    vc::fuzz::finding(std::string("evaluation: not a std::runtime_error: ") + e.what());
  }
  return 0;
}
