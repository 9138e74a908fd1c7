#include "vc/acceptance/evaluation_file.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "vc/tables/csv.hpp"
#include "vc/tables/number_text.hpp"
#include "vc/tables/source_error.hpp"
#include "vc/tables/units.hpp"

namespace vc::acceptance {
namespace {

constexpr std::array<const char*, 11> kColumns = {"test",         "kind", "figure", "name", "value",  "u_repeatability",
                                                  "u_instrument", "U",    "limit",  "unit", "verdict"};
enum Column { Test, Kind, FigureSymbol, Name, Value, URepeatability, UInstrument, Expanded, Limit, Unit, Verdict };

std::string columns_text() {
  std::string s;
  for (const char* c : kColumns) s += (s.empty() ? "" : ",") + std::string(c);
  return s;
}

// A text cell as written: no comma or line break could be read back.
const std::string& text_cell(const std::string& text) {
  if (text.find_first_of(",\n\r") != std::string::npos)
    throw std::invalid_argument("an acceptance result's text '" + text + "' holds a comma or a line break");
  return text;
}

std::string number(double v) { return without_negative_zero(fixed_text(v, 6)); }

}  // namespace

std::string overall_verdict(const Evaluation& e) {
  bool judged = false;
  for (const EvaluationRow& r : e.rows) {
    if (r.verdict == "FAIL") return "FAIL";
    judged = judged || r.verdict == "PASS";
  }
  return judged ? "PASS" : "not judged";
}

std::vector<std::string> tests_of(const Evaluation& e) {
  std::vector<std::string> tests;
  for (const EvaluationRow& r : e.rows)
    if (std::find(tests.begin(), tests.end(), r.test) == tests.end()) tests.push_back(r.test);
  return tests;
}

std::string evaluation_csv(const std::string& what, const std::vector<std::string>& notes,
                           const std::vector<EvaluationRow>& rows) {
  std::ostringstream out;
  out << "# volcomp acceptance evaluate: " << what << "; U expanded uncertainty (k = 2); thermal not evaluated\n";
  for (const std::string& n : notes) out << "# " << n << "\n";
  out << columns_text() << "\n";
  for (const EvaluationRow& r : rows)
    out << text_cell(r.test) << "," << text_cell(r.kind) << "," << text_cell(r.figure) << "," << text_cell(r.name)
        << "," << number(r.value) << "," << number(r.u_repeatability) << "," << number(r.u_instrument) << ","
        << number(r.expanded) << "," << (r.limit ? number(*r.limit) : "") << "," << text_cell(r.unit) << ","
        << text_cell(r.verdict) << "\n";
  return out.str();
}

Evaluation read_evaluation(const std::string& path) {
  const std::vector<tables::CsvRow> lines = tables::read_csv_rows(path, "acceptance results");
  if (lines.empty()) throw LoadError({path}, "no header: an acceptance results file starts with " + columns_text());
  // The header: every column once, in any order.
  const tables::CsvRow& header = lines.front();
  std::array<int, kColumns.size()> at{};
  at.fill(-1);
  for (std::size_t c = 0; c < header.cells.size(); ++c) {
    const tables::CsvCell& cell = header.cells[c];
    const auto known = std::find_if(kColumns.begin(), kColumns.end(), [&](const char* k) { return cell.text == k; });
    if (known == kColumns.end())
      throw LoadError({path, header.line, cell.column},
                      "unknown column '" + cell.text + "' (an acceptance results file has " + columns_text() + ")");
    int& slot = at[static_cast<std::size_t>(known - kColumns.begin())];
    if (slot >= 0) throw LoadError({path, header.line, cell.column}, "column '" + cell.text + "' twice");
    slot = static_cast<int>(c);
  }
  for (std::size_t k = 0; k < kColumns.size(); ++k)
    if (at[k] < 0)
      throw LoadError({path, header.line}, "no column '" + std::string(kColumns[k]) +
                                               "' (an acceptance results file has " + columns_text() + ")");

  Evaluation e;
  e.path = path;
  std::map<std::pair<std::string, std::string>, int> seen;   // test, figure -> line
  std::map<std::string, std::pair<std::string, int>> kinds;  // test -> kind, line
  for (std::size_t l = 1; l < lines.size(); ++l) {
    const tables::CsvRow& row = lines[l];
    if (row.cells.size() != header.cells.size())
      throw LoadError({path, row.line}, std::to_string(row.cells.size()) + " cells; the header has " +
                                            std::to_string(header.cells.size()) + " columns");
    const auto cell = [&](Column c) -> const tables::CsvCell& { return row.cells[static_cast<std::size_t>(at[c])]; };
    const auto where = [&](Column c) { return SourceLocation{path, row.line, cell(c).column}; };
    const auto text = [&](Column c) {
      if (cell(c).text.empty()) throw LoadError(where(c), "empty " + std::string(kColumns[c]));
      return cell(c).text;
    };
    const auto at_least_zero = [&](Column c) {
      const double v = tables::csv_number(path, row.line, cell(c));
      if (v < 0)
        throw LoadError(where(c),
                        std::string(kColumns[c]) + " " + cell(c).text + " is negative: an uncertainty is >= 0");
      return v;
    };
    EvaluationRow r;
    r.line = row.line;
    r.test = text(Test);
    r.kind = text(Kind);
    r.figure = text(FigureSymbol);
    r.name = cell(Name).text;
    r.value = tables::csv_number(path, row.line, cell(Value));
    r.u_repeatability = at_least_zero(URepeatability);
    r.u_instrument = at_least_zero(UInstrument);
    r.expanded = at_least_zero(Expanded);
    if (!cell(Limit).text.empty()) {
      r.limit = tables::csv_number(path, row.line, cell(Limit));
      if (!(*r.limit > 0)) throw LoadError(where(Limit), "limit " + cell(Limit).text + ": a limit is > 0");
    }
    r.unit = text(Unit);
    if (!tables::find_unit(r.unit))
      throw LoadError(where(Unit), "unknown unit '" + r.unit +
                                       "' (lengths: " + std::string(tables::unit_names(tables::Quantity::Length)) +
                                       "; angles: " + std::string(tables::unit_names(tables::Quantity::Angle)) + ")");
    r.verdict = cell(Verdict).text;
    if (!r.verdict.empty() && r.verdict != "PASS" && r.verdict != "FAIL")
      throw LoadError(where(Verdict), "verdict '" + r.verdict + "': PASS, FAIL or empty (no limit)");
    if (r.verdict.empty() != !r.limit)
      throw LoadError(where(Verdict),
                      r.limit ? "a limit without a verdict (PASS or FAIL)" : "a verdict without a limit");
    const auto [kind, inserted] = kinds.emplace(r.test, std::make_pair(r.kind, row.line));
    if (!inserted && kind->second.first != r.kind)
      throw LoadError(where(Kind), "test " + r.test + " is a " + r.kind + " here and a " + kind->second.first +
                                       " on line " + std::to_string(kind->second.second));
    const auto [first, fresh] = seen.emplace(std::make_pair(r.test, r.figure), row.line);
    if (!fresh)
      throw LoadError({path, row.line}, "test " + r.test + ", figure " + r.figure + " again (first on line " +
                                            std::to_string(first->second) + ")");
    e.rows.push_back(r);
  }
  if (e.rows.empty()) throw LoadError({path, header.line}, "no results after the header");
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    const std::size_t hash = line.find_first_not_of(" \t");
    if (hash != std::string::npos && line[hash] == '#') {
      const std::size_t text = line.find_first_not_of(" \t\r", hash + 1);
      if (text != std::string::npos) e.comments.push_back(line.substr(text, line.find_last_not_of(" \t\r") - text + 1));
    }
  }
  return e;
}

}  // namespace vc::acceptance
