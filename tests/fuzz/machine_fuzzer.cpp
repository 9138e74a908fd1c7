// libFuzzer target: any bytes as a machine file (TOML) through load_machine, with its error
// tables. Refusal (vc::LoadError) is the expected answer to bad input; a crash, a hang, a
// sanitizer report, any other exception or an accepted model that breaks what the loader
// promises (every number finite, directions unit, travel min < max, at most kMaxAxes joints)
// is a finding.
//
// The input is written where both kinds of table reference in the seeds resolve:
//   <scratch>/machine/data/input.toml
//   <scratch>/machine/data/tables -> tests/golden/bad_machines/tables  ("tables/x.csv")
//   <scratch>/machine/tables      -> tests/golden/bad_machines/tables  ("../tables/x.csv")
//   <scratch>/tables              -> tables                           ("../../tables/data/...")
#include <cmath>
#include <filesystem>
#include <string>

#include "fuzz_support.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/source_error.hpp"

namespace {

namespace fs = std::filesystem;

void link_folder(const fs::path& at, const std::string& target) {
  if (!fs::exists(at)) fs::create_directory_symlink(vc::fuzz::source_path(target), at);
}

std::string machine_path() {
  const fs::path data = vc::fuzz::scratch() / "machine" / "data";
  fs::create_directories(data);
  link_folder(data / "tables", "tests/golden/bad_machines/tables");
  link_folder(data.parent_path() / "tables", "tests/golden/bad_machines/tables");
  link_folder(vc::fuzz::scratch() / "tables", "tables");
  return (data / "input.toml").string();
}

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

void check(const vc::machine::Model& m) {
  if (m.joint_count() < 1 || m.joint_count() > vc::machine::kMaxAxes)
    vc::fuzz::finding("accepted a machine of " + std::to_string(m.joint_count()) + " joints");
  for (const vc::machine::Axis& a : m.axes) {
    const std::string name = std::string("axis ") + a.letter;
    if (!finite(a.direction) || std::abs(a.direction.norm() - 1.0) > 1e-9)
      vc::fuzz::finding(name + ": direction not a unit vector");
    if (!finite(a.pole_mm) || !finite(a.location_mm) || !finite(a.location_rad))
      vc::fuzz::finding(name + ": a non-finite pole or location");
    if (!std::isfinite(a.travel_min) || !std::isfinite(a.travel_max) || !(a.travel_min < a.travel_max))
      vc::fuzz::finding(name + ": travel not finite with min < max");
  }
  if (!finite(m.spindle.gauge_point_mm) || !std::isfinite(m.tool_length_mm))
    vc::fuzz::finding("spindle or tool length not finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = machine_path();
  vc::fuzz::write_file(path, vc::fuzz::text_of(data, size));
  try {
    check(vc::machine::load_machine(path));
  } catch (const vc::LoadError&) {
  } catch (const std::exception& e) {
    vc::fuzz::finding(std::string("not a vc::LoadError: ") + e.what());
  }
  return 0;
}
