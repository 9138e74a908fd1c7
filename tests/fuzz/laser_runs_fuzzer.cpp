// libFuzzer target: any bytes as laser interferometer runs (CSV, long or wide layout) through
// read_laser_runs, then evaluated as `volcomp identify laser` does (evaluate_iso230_2 and
// suspicious_runs). Refusal is the expected answer to bad input: vc::LoadError from the
// reader, std::runtime_error (documented) from the evaluation. A crash, a hang, a sanitizer
// report, any other exception or a result that breaks what laser_runs.hpp and iso230_2.hpp
// promise (finite readings, whole run numbers >= 1; at least 2 runs each way, targets
// ascending) is a finding.
#include <cmath>
#include <stdexcept>
#include <string>

#include "fuzz_support.hpp"
#include "vc/identify/iso230_2.hpp"
#include "vc/identify/laser_runs.hpp"
#include "vc/tables/source_error.hpp"

namespace {

void check(const vc::identify::LaserRuns& runs) {
  for (const auto& r : runs.readings)
    if (!std::isfinite(r.target) || !std::isfinite(r.deviation))
      vc::fuzz::finding("line " + std::to_string(r.line) + ": a non-finite reading");
}

void check(const vc::identify::Iso230_2& e) {
  if (e.runs_up < 2 || e.runs_down < 2) vc::fuzz::finding("evaluated with fewer than 2 runs in a direction");
  for (std::size_t i = 1; i < e.targets.size(); ++i)
    if (!(e.targets[i - 1].target < e.targets[i].target)) vc::fuzz::finding("targets not ascending");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (vc::fuzz::scratch() / "input.csv").string();
  vc::fuzz::write_file(path, vc::fuzz::text_of(data, size));
  vc::identify::LaserRuns runs;
  try {
    runs = vc::identify::read_laser_runs(path);
  } catch (const vc::LoadError&) {
    return 0;
  } catch (const std::exception& e) {
    vc::fuzz::finding(std::string("read_laser_runs: not a vc::LoadError: ") + e.what());
  }
  check(runs);
  try {
    (void)vc::identify::suspicious_runs(runs);
    check(vc::identify::evaluate_iso230_2(runs));
  } catch (const std::runtime_error&) {
  } catch (const std::exception& e) {
    vc::fuzz::finding(std::string("evaluation: not a std::runtime_error: ") + e.what());
  }
  return 0;
}
