// The acceptance results' one file layout (`acceptance evaluate`'s PREFIX.csv, read back by
// `volcomp report --acceptance`): long, one row per test and figure, so that every kind of test
// (the ISO 230-6 diagonals now; circles, axis runs, the R-test later) writes the same columns
// and a spreadsheet pivots them:
//
//   # volcomp acceptance evaluate: ISO 230-6 diagonals; U expanded uncertainty (k = 2); thermal not evaluated
//   test,kind,figure,name,value,u_repeatability,u_instrument,U,limit,unit,verdict
//   body-NNN-PPP,body diagonal,E,systematic deviation,12.345000,0.201000,0.707107,1.469694,20.000000,um,PASS
//
// value, its two standard uncertainties (k = 1), U = 2 u_c (k = 2) and the limit are in the row's
// unit (one of tables/units.hpp's: mm, um, nm, deg, arcsec, rad, mrad, urad); limit and verdict
// are empty when the figure has no limit, the verdict is PASS (value <= limit) or FAIL.
// '#' lines are comments; the columns may come in any order.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace vc::acceptance {

struct EvaluationRow {
  std::string test;                                                       // e.g. body-NNN-PPP
  std::string kind;                                                       // e.g. body diagonal (one kind per test)
  std::string figure;                                                     // its symbol, e.g. E
  std::string name;                                                       // e.g. systematic deviation
  double value = 0, u_repeatability = 0, u_instrument = 0, expanded = 0;  // in `unit`
  std::optional<double> limit;                                            // in `unit`
  std::string unit;                                                       // um, arcsec, ...
  std::string verdict;                                                    // "PASS", "FAIL", or empty (no limit)
  int line = 0;                                                           // where it was read (0: not read from a file)
};

struct Evaluation {
  std::string path;
  std::vector<std::string> comments;  // the '#' lines, without the '#' and the blank after it
  std::vector<EvaluationRow> rows;    // in the file's order
};

// "PASS" when every judged figure passes, "FAIL" when one fails, "not judged" without verdicts.
std::string overall_verdict(const Evaluation& e);
// The tests in the file's order, each once.
std::vector<std::string> tests_of(const Evaluation& e);

// The file's text: `what` on the first comment line (e.g. "ISO 230-6 diagonals"), `notes` as
// further comment lines, then the header and the rows (numbers to 1e-6 of the unit).
std::string evaluation_csv(const std::string& what, const std::vector<std::string>& notes,
                           const std::vector<EvaluationRow>& rows);

// Throws vc::LoadError at file:line(:column) for a file that cannot be opened, an unknown or
// repeated column, a missing column, a row with another number of cells than the header, an
// empty test, kind or figure, a cell that is not a number (a negative uncertainty, a limit
// <= 0), an unknown unit, a verdict that is not PASS, FAIL or empty (or one without a limit, a
// limit without one), a test of two kinds, a test and figure given twice, or no row at all.
Evaluation read_evaluation(const std::string& path);

}  // namespace vc::acceptance
