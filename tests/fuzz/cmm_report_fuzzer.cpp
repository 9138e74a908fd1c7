// libFuzzer target: any bytes as a CMM plan or report through read_cmm_points (our CSV, or a
// CMM software's export), read four ways: as a plan, as a report as selftune reads it without
// options, and as a report with the options a user gives an export (--report-unit,
// --deviation-sign, --decimal-comma). Refusal (vc::LoadError) is the expected answer to bad
// input; a crash, a hang, a sanitizer report, any other exception or accepted points that
// break what cmm.hpp promises (at least one point, finite nominal, unit normal, a deviation on
// every point of a report) is a finding.
#include <cmath>
#include <stdexcept>
#include <string>

#include "fuzz_support.hpp"
#include "vc/shop/cmm.hpp"
#include "vc/tables/source_error.hpp"

namespace {

using vc::shop::DeviationSign;
using vc::shop::ReportFormat;

void check(const std::vector<vc::shop::CmmPoint>& points, bool report) {
  if (points.empty()) vc::fuzz::finding("accepted a file without points");
  for (const auto& p : points) {
    const std::string at = "point " + p.id + " (line " + std::to_string(p.line) + "): ";
    if (!p.nominal.allFinite()) vc::fuzz::finding(at + "nominal not finite");
    if (!p.normal.allFinite() || std::abs(p.normal.norm() - 1.0) > 1e-9)
      vc::fuzz::finding(at + "normal not a unit vector");
    if (report && !p.deviation_mm) vc::fuzz::finding(at + "a report's point without a deviation");
    if (p.deviation_mm && !std::isfinite(*p.deviation_mm)) vc::fuzz::finding(at + "deviation not finite");
  }
}

void read(const std::string& path, bool report, const ReportFormat& format) {
  try {
    std::string layout;
    check(vc::shop::read_cmm_points(path, report, format, &layout), report);
  } catch (const vc::LoadError&) {
  } catch (const std::runtime_error& e) {
    if (!format.any()) vc::fuzz::finding(std::string("without options, not a vc::LoadError: ") + e.what());
  } catch (const std::exception& e) {
    vc::fuzz::finding(std::string("not a vc::LoadError: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (vc::fuzz::scratch() / "input.csv").string();
  vc::fuzz::write_file(path, vc::fuzz::text_of(data, size));
  read(path, false, {});
  read(path, true, {});
  read(path, true, {"mm", DeviationSign::ActualMinusNominal, false});
  read(path, true, {"inch", DeviationSign::NominalMinusActual, true});
  return 0;
}
