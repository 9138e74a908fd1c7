// libFuzzer target: any bytes as `volcomp acceptance`'s four inputs: a plan (plan.toml,
// read_plan_file), a tolerance file (read_tolerances), a diagonal's laser runs (CSV) read
// against the golden good plan's first diagonal and evaluated as `acceptance evaluate` does
// (read_diagonal_runs, evaluate_diagonal), and a results file as `volcomp report --acceptance`
// reads it (read_evaluation). Refusal is the expected answer to bad input:
// vc::LoadError (file:line). A crash, a hang, a sanitizer report, any other exception or a
// result that breaks what the headers promise (a plan: runs 2..1000, every diagonal with 5
// targets or more, increasing from 0 to its length, finite ends apart; limits finite and > 0; an
// evaluation: at least 2 runs each way, finite figures; results: at least a row, each with a
// test, kind and figure, finite numbers, uncertainties >= 0, a limit > 0 exactly when a verdict
// PASS or FAIL, each test and figure once) is a finding.
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "fuzz_support.hpp"
#include "vc/acceptance/diagonal_evaluation.hpp"
#include "vc/acceptance/diagonal_measurements.hpp"
#include "vc/acceptance/evaluation_file.hpp"
#include "vc/acceptance/plan_file.hpp"
#include "vc/acceptance/tolerances.hpp"
#include "vc/tables/source_error.hpp"
#include "vc/tables/units.hpp"

namespace {

void check(const vc::acceptance::Plan& p) {
  if (p.settings.runs < 2 || p.settings.runs > 1000) vc::fuzz::finding("runs out of 2..1000");
  if (p.diagonals.empty()) vc::fuzz::finding("a plan without diagonals");
  for (const auto& d : p.diagonals) {
    if (!d.start_mm.allFinite() || !d.end_mm.allFinite() || !(d.length_mm() > 0))
      vc::fuzz::finding(d.name + ": ends not finite and apart");
    if (d.targets_mm.size() < 5) vc::fuzz::finding(d.name + ": fewer than 5 targets");
    for (std::size_t i = 0; i < d.targets_mm.size(); ++i)
      if (!(d.targets_mm[i] >= 0 && d.targets_mm[i] <= d.length_mm() + 1e-3) ||
          (i && !(d.targets_mm[i] > d.targets_mm[i - 1])))
        vc::fuzz::finding(d.name + ": targets not increasing on the line");
  }
}

void check(const vc::acceptance::Evaluation& e) {
  if (e.rows.empty()) vc::fuzz::finding("results without a row");
  std::set<std::pair<std::string, std::string>> seen;
  for (const auto& r : e.rows) {
    if (r.test.empty() || r.kind.empty() || r.figure.empty()) vc::fuzz::finding("a row without test, kind or figure");
    if (!std::isfinite(r.value) || !std::isfinite(r.expanded) || !(r.u_repeatability >= 0) || !(r.u_instrument >= 0) ||
        !(r.expanded >= 0) || !std::isfinite(r.u_repeatability) || !std::isfinite(r.u_instrument))
      vc::fuzz::finding(r.test + " " + r.figure + ": a number not finite or an uncertainty < 0");
    if (r.limit && !(std::isfinite(*r.limit) && *r.limit > 0)) vc::fuzz::finding(r.test + ": a limit not > 0");
    if (r.limit ? r.verdict != "PASS" && r.verdict != "FAIL" : !r.verdict.empty())
      vc::fuzz::finding(r.test + " " + r.figure + ": verdict '" + r.verdict + "' against its limit");
    if (!vc::tables::find_unit(r.unit)) vc::fuzz::finding(r.test + ": unit '" + r.unit + "' unknown");
    if (!seen.emplace(r.test, r.figure).second) vc::fuzz::finding(r.test + " " + r.figure + " twice");
  }
}

template <class Read>
void refused_or(const char* what, Read read) {
  try {
    read();
  } catch (const vc::LoadError&) {
  } catch (const std::exception& e) {
    vc::fuzz::finding(std::string(what) + ": not a vc::LoadError: " + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string toml = (vc::fuzz::scratch() / "plan.toml").string();
  static const std::string csv = (vc::fuzz::scratch() / "runs.csv").string();
  static const vc::acceptance::Plan good =
      vc::acceptance::read_plan(vc::fuzz::source_path("tests/golden/bad_acceptance/good").string());
  const std::string_view text = vc::fuzz::text_of(data, size);
  vc::fuzz::write_file(toml, text);
  refused_or("read_plan_file", [&] { check(vc::acceptance::read_plan_file(toml)); });
  refused_or("read_tolerances", [&] {
    for (const auto& [symbol, limit] : vc::acceptance::read_tolerances(toml).diagonal_mm)
      if (!std::isfinite(limit) || !(limit > 0)) vc::fuzz::finding("limit " + symbol + " not finite and > 0");
  });
  vc::fuzz::write_file(csv, text);
  refused_or("read_diagonal_runs", [&] {
    const auto& d = good.diagonals.front();
    const auto r = vc::acceptance::evaluate_diagonal(d, vc::acceptance::read_diagonal_runs(csv, d), 0.5e-3, nullptr);
    if (r.iso.runs_up < 2 || r.iso.runs_down < 2) vc::fuzz::finding("evaluated with fewer than 2 runs in a direction");
    for (const auto& f : r.figures)
      if (!std::isfinite(f.value_mm) || !std::isfinite(f.expanded_mm())) vc::fuzz::finding(f.symbol + " not finite");
  });
  refused_or("read_evaluation", [&] { check(vc::acceptance::read_evaluation(csv)); });
  return 0;
}
