// The report's acceptance section (`volcomp report --acceptance LABEL=FILE.csv`, repeatable;
// ISO/TR 16907 11.3): `volcomp acceptance evaluate`'s results files (evaluation_file.hpp), each
// under a label ("compensation off", "compensation on"), side by side: per file its path,
// SHA-256, overall verdict and number of tests; per kind of test a table (a row per test and
// figure, a column group per label: value, U, verdict; the limit) and a bar chart per figure
// that has limits (E always): the tests along x, a colour per label, the limit as a line; then
// what U holds and what it does not. A test one file has and another lacks is "not measured"
// in the other's columns.
#pragma once

#include <string>
#include <vector>

#include "vc/acceptance/evaluation_file.hpp"
#include "vc/report/drawings.hpp"

namespace vc::report {

struct AcceptanceInput {
  std::string label;  // non-empty, unique over the report
  std::string path;   // an `acceptance evaluate` results CSV
};

// "LABEL=FILE" (the first '=' splits; blanks around either part dropped). Throws
// std::runtime_error quoting the value when there is no '=', or the label or file is empty.
AcceptanceInput acceptance_input(const std::string& value);

struct LabelledEvaluation {
  std::string label;
  acceptance::Evaluation evaluation;
  std::string sha256;  // of the file as read
};

// Reads every file. Throws std::runtime_error for a repeated or empty label or a path that is
// no file, vc::LoadError (file:line) for a file that cannot be read, and std::runtime_error
// when two files give one test's figure in units of different quantities (um against arcsec).
std::vector<LabelledEvaluation> read_acceptance(const std::vector<AcceptanceInput>& inputs);

// The summary's line: "off: FAIL (10 tests); on: PASS (10 tests)".
std::string acceptance_summary(const std::vector<LabelledEvaluation>& evaluations);

// The section's HTML; its charts are drawn in `drawings` and added to `figures`.
std::string acceptance_section(const std::vector<LabelledEvaluation>& evaluations, const Drawings& drawings,
                               int& figures);

}  // namespace vc::report
