// libFuzzer target: any bytes as the log of a probe_plan program (sphere probing) through
// read_probe_log on the MC-300 (machines/data/mc300.toml: X Y Z B C), as `volcomp identify
// sphere` reads it. Refusal (vc::LoadError) is the expected answer to bad input; a crash, a
// hang, a sanitizer report, any other exception or an accepted log that breaks what
// probe_log.hpp promises (a pose at least, each with the machine's joints, finite; the
// diameters read) is a finding.
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "vc/identify/probe_log.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/source_error.hpp"

namespace {

void check(const vc::identify::ProbeLog& log, const vc::machine::Model& model) {
  if (log.centres.empty()) vc::fuzz::finding("accepted a log without poses");
  if (!(log.sphere_diameter_mm > 0) || !(log.ball_diameter_mm >= 0))
    vc::fuzz::finding("accepted without the diameters");
  for (const auto& pose : log.centres)
    if (pose.joints.size() != model.joint_count() || !pose.joints.allFinite())
      vc::fuzz::finding("line " + std::to_string(pose.line) + ": the centre's joints are not the machine's, finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const vc::machine::Model model =
      vc::machine::load_machine(vc::fuzz::source_path("machines/data/mc300.toml").string());
  static const std::string path = (vc::fuzz::scratch() / "input.log").string();
  vc::fuzz::write_file(path, vc::fuzz::text_of(data, size));
  try {
    check(vc::identify::read_probe_log(path, model), model);
  } catch (const vc::LoadError&) {
  } catch (const std::exception& e) {
    vc::fuzz::finding(std::string("not a vc::LoadError: ") + e.what());
  }
  return 0;
}
