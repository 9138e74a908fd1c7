#include "vc/report/acceptance_section.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "vc/plot/gnuplot.hpp"
#include "vc/report/html.hpp"
#include "vc/report/sha256.hpp"
#include "vc/tables/units.hpp"

namespace vc::report {
namespace {

namespace fs = std::filesystem;
using acceptance::EvaluationRow;

std::string trimmed(const std::string& s) {
  const std::size_t b = s.find_first_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// One test's figure over every label: the row of each (null: not measured there).
struct Line {
  std::string kind, test, figure, name, unit;  // the first label's that has it
  std::vector<const EvaluationRow*> rows;      // per label
};

// Every test's figures, grouped by kind, then by test, each in the order the files first give it.
std::vector<Line> lines_of(const std::vector<LabelledEvaluation>& evaluations) {
  std::vector<Line> lines;
  std::vector<std::string> kinds, tests;
  for (std::size_t l = 0; l < evaluations.size(); ++l)
    for (const EvaluationRow& r : evaluations[l].evaluation.rows) {
      if (std::find(kinds.begin(), kinds.end(), r.kind) == kinds.end()) kinds.push_back(r.kind);
      if (std::find(tests.begin(), tests.end(), r.test) == tests.end()) tests.push_back(r.test);
      auto it = std::find_if(lines.begin(), lines.end(),
                             [&](const Line& x) { return x.test == r.test && x.figure == r.figure; });
      if (it == lines.end()) {
        lines.push_back(
            {r.kind, r.test, r.figure, r.name, r.unit, std::vector<const EvaluationRow*>(evaluations.size())});
        it = lines.end() - 1;
      }
      it->rows[l] = &r;
    }
  const auto index = [](const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) - v.begin();
  };
  std::stable_sort(lines.begin(), lines.end(), [&](const Line& a, const Line& b) {
    return std::make_pair(index(kinds, a.kind), index(tests, a.test)) <
           std::make_pair(index(kinds, b.kind), index(tests, b.test));
  });
  return lines;
}

// `v` in `from` as a value in `to` (units of one quantity: read_acceptance checked them).
double in_unit(double v, const std::string& from, const std::string& to) {
  return v * tables::find_unit(from)->to_core / tables::find_unit(to)->to_core;
}

// PASS or FAIL, marked when the figure is within U of its limit (the uncertainty could turn it).
std::string verdict_text(const EvaluationRow& r) {
  if (r.verdict.empty()) return "-";
  const bool close = r.limit && std::abs(*r.limit - r.value) < r.expanded;
  return r.verdict + (close ? " (within U)" : "");
}

// The limit column: the one limit all labels share, else each label's.
std::string limit_text(const Line& line, const std::vector<LabelledEvaluation>& evaluations) {
  std::vector<std::pair<std::string, double>> limits;
  for (std::size_t l = 0; l < line.rows.size(); ++l)
    if (line.rows[l] && line.rows[l]->limit)
      limits.emplace_back(evaluations[l].label, in_unit(*line.rows[l]->limit, line.rows[l]->unit, line.unit));
  if (limits.empty()) return "-";
  const bool shared = std::all_of(limits.begin(), limits.end(),
                                  [&](const auto& x) { return fixed(x.second, 3) == fixed(limits[0].second, 3); });
  if (shared) return fixed(limits[0].second, 3);
  std::string s;
  for (const auto& [label, limit] : limits) s += (s.empty() ? "" : "; ") + label + " " + fixed(limit, 3);
  return s;
}

std::string kind_table(const std::vector<Line>& lines, const std::vector<LabelledEvaluation>& evaluations) {
  std::string html =
      "<table class=\"numeric acceptance\">\n<thead><tr><th rowspan=\"2\">test</th><th rowspan=\"2\">"
      "figure</th><th rowspan=\"2\">unit</th>";
  for (const LabelledEvaluation& e : evaluations) html += "<th colspan=\"3\">" + escaped(e.label) + "</th>";
  html += "<th rowspan=\"2\">limit</th></tr>\n<tr>";
  for (std::size_t l = 0; l < evaluations.size(); ++l) html += "<th>value</th><th>U</th><th>verdict</th>";
  html += "</tr></thead>\n<tbody>\n";
  for (const Line& line : lines) {
    html += "<tr><td>" + escaped(line.test) + "</td><td>" + escaped(line.figure + " " + line.name) + "</td><td>" +
            escaped(line.unit) + "</td>";
    for (const EvaluationRow* r : line.rows) {
      if (!r) {
        html += "<td colspan=\"3\" class=\"missing\">not measured</td>";
        continue;
      }
      const std::string css = r->verdict == "PASS" ? " class=\"pass\"" : r->verdict == "FAIL" ? " class=\"fail\"" : "";
      html += "<td>" + fixed(in_unit(r->value, r->unit, line.unit), 3) + "</td><td>" +
              fixed(in_unit(r->expanded, r->unit, line.unit), 3) + "</td><td" + css + ">" + escaped(verdict_text(*r)) +
              "</td>";
    }
    html += "<td>" + escaped(limit_text(line, evaluations)) + "</td></tr>\n";
  }
  return html + "</tbody></table>\n";
}

constexpr const char* kColours[] = {"#c0392b", "#2e86c1", "#27ae60", "#8e44ad", "#d68910", "#566573"};

// A bar chart of one figure of one kind: the tests along x, a bar per label, each label's limit
// (one line when all labels share it) dashed across each test's bars.
std::string figure_chart(const std::string& kind, const std::vector<const Line*>& lines,
                         const std::vector<LabelledEvaluation>& evaluations, const Drawings& drawings,
                         const std::string& image) {
  const std::size_t labels = evaluations.size();
  const std::string unit = lines.front()->unit;
  // Each label's limit per test, converted ("NaN": none); one shared column when, test by test,
  // the labels that have a limit agree.
  std::vector<std::vector<std::string>> limits(labels);
  for (const Line* line : lines)
    for (std::size_t l = 0; l < labels; ++l) {
      const EvaluationRow* r = line->rows[l];
      limits[l].push_back(r && r->limit ? fixed(in_unit(*r->limit, r->unit, unit), 6) : "NaN");
    }
  std::vector<std::string> shared(lines.size(), "NaN");
  bool one = true;
  for (std::size_t t = 0; t < lines.size(); ++t)
    for (std::size_t l = 0; l < labels; ++l)
      if (limits[l][t] != "NaN") {
        one = one && (shared[t] == "NaN" || shared[t] == limits[l][t]);
        shared[t] = limits[l][t];
      }
  std::vector<std::size_t> limit_columns;  // the labels whose limits are drawn (one: the shared column)
  for (std::size_t l = 0; l < labels; ++l)
    if (std::any_of(limits[l].begin(), limits[l].end(), [](const std::string& x) { return x != "NaN"; }))
      limit_columns.push_back(l);
  if (one && !limit_columns.empty()) {
    limits[limit_columns.front()] = shared;
    limit_columns.resize(1);
  }
  std::ostringstream data;
  data << "# " << kind << ", " << lines.front()->figure << " " << lines.front()->name << " [" << unit
       << "] per test; NaN: not measured or no limit\n# test";
  for (const LabelledEvaluation& e : evaluations) data << "," << e.label << "[" << unit << "]";
  for (const std::size_t l : limit_columns)
    data << ",limit" << (limit_columns.size() == 1 ? "" : " " + evaluations[l].label) << "[" << unit << "]";
  data << "\n";
  for (std::size_t t = 0; t < lines.size(); ++t) {
    data << lines[t]->test;
    for (const EvaluationRow* r : lines[t]->rows)
      data << "," << (r ? fixed(in_unit(r->value, r->unit, unit), 6) : "NaN");
    for (const std::size_t l : limit_columns) data << "," << limits[l][t];
    data << "\n";
  }
  std::ostringstream gp;
  gp << "set datafile separator ','\nset datafile missing 'NaN'\nset style data histograms\n"
     << "set style histogram clustered gap 1\nset style fill solid 0.8 border -1\nset boxwidth 0.9\n"
     << "set grid ytics\nset key top right\nset xtics rotate by -45 font 'sans,11'\nset offsets 0, 0, graph 0.1, 0\n"
     << "set title "
     << plot::text_literal(kind + ": " + lines.front()->figure + " " + lines.front()->name + " per test")
     << "\nset ylabel " << plot::text_literal(lines.front()->figure + " (" + unit + ")") << "\nplot ";
  for (std::size_t l = 0; l < labels; ++l)
    gp << (l ? ", '' using " : "DATA using ") << l + 2 << (l ? "" : ":xtic(1)") << " title "
       << plot::text_literal(evaluations[l].label) << " lc rgb '" << kColours[l % std::size(kColours)] << "'";
  for (std::size_t k = 0; k < limit_columns.size(); ++k) {
    const std::size_t l = limit_columns[k];
    gp << ", '' using ($0 - 0.5):" << labels + 2 + k << ":(1):(0) with vectors nohead dt 2 lw 3 lc rgb '"
       << (limit_columns.size() == 1 ? std::string("#000000") : kColours[l % std::size(kColours)]) << "' title "
       << plot::text_literal(limit_columns.size() == 1 ? "limit" : "limit " + evaluations[l].label);
  }
  gp << "\n";
  return drawings.png({drawings.path(image), data.str(), gp.str(), 1400, 700});
}

}  // namespace

AcceptanceInput acceptance_input(const std::string& value) {
  const std::size_t eq = value.find('=');
  if (eq == std::string::npos)
    throw std::runtime_error("--acceptance '" + value +
                             "': give LABEL=FILE.csv (e.g. \"compensation on=on/evaluation.csv\")");
  AcceptanceInput in{trimmed(value.substr(0, eq)), trimmed(value.substr(eq + 1))};
  if (in.label.empty()) throw std::runtime_error("--acceptance '" + value + "': the label before '=' is empty");
  if (in.path.empty()) throw std::runtime_error("--acceptance '" + value + "': the file after '=' is empty");
  return in;
}

std::vector<LabelledEvaluation> read_acceptance(const std::vector<AcceptanceInput>& inputs) {
  std::vector<LabelledEvaluation> read;
  for (const AcceptanceInput& in : inputs) {
    if (in.label.empty()) throw std::runtime_error("--acceptance " + in.path + ": an empty label");
    for (const LabelledEvaluation& e : read)
      if (e.label == in.label)
        throw std::runtime_error("--acceptance: the label '" + in.label + "' twice (" + e.evaluation.path + " and " +
                                 in.path + "): each evaluation needs a label of its own");
    if (fs::exists(in.path) && !fs::is_regular_file(in.path))
      throw std::runtime_error("--acceptance " + in.label + "=" + in.path + ": not a file");
    read.push_back({in.label, acceptance::read_evaluation(in.path), sha256_file_hex(in.path)});
  }
  // One test is one kind in every file, and each figure a quantity (um and mm compare; um and arcsec do not).
  for (const Line& line : lines_of(read))
    for (std::size_t l = 0; l < line.rows.size(); ++l) {
      const EvaluationRow* r = line.rows[l];
      if (!r) continue;
      const std::string where = read[l].evaluation.path + ":" + std::to_string(r->line) + ": error: ";
      if (r->kind != line.kind)
        throw std::runtime_error(where + "test " + r->test + " is a " + r->kind + " here and a " + line.kind +
                                 " in an earlier --acceptance file");
      if (tables::find_unit(r->unit)->quantity != tables::find_unit(line.unit)->quantity)
        throw std::runtime_error(where + "test " + r->test + ", figure " + r->figure + " in " + r->unit +
                                 " here and in " + line.unit + " in an earlier --acceptance file: not comparable");
    }
  return read;
}

std::string acceptance_summary(const std::vector<LabelledEvaluation>& evaluations) {
  std::string s;
  for (const LabelledEvaluation& e : evaluations) {
    const std::size_t tests = acceptance::tests_of(e.evaluation).size();
    s += (s.empty() ? "" : "; ") + e.label + ": " + acceptance::overall_verdict(e.evaluation) + " (" +
         std::to_string(tests) + (tests == 1 ? " test)" : " tests)");
  }
  return s;
}

std::string acceptance_section(const std::vector<LabelledEvaluation>& evaluations, const Drawings& drawings,
                               int& figures) {
  std::string html =
      "<p>The compensated machine is accepted by the standard tests, run with the compensation on, at other points "
      "than the compensation was measured at (ISO/TR 16907 11.3): <code>volcomp acceptance plan</code> plans them, "
      "<code>acceptance evaluate</code> evaluates their measurements (preproc/acceptance/README.md). Each results "
      "file below under its label, with its SHA-256 (<code>sha256sum FILE</code> prints the same).</p>\n";
  html +=
      "<table>\n<thead><tr><th>label</th><th>file</th><th>SHA-256</th><th>verdict</th><th>tests</th></tr></thead>\n"
      "<tbody>\n";
  for (const LabelledEvaluation& e : evaluations) {
    const std::string verdict = acceptance::overall_verdict(e.evaluation);
    html += "<tr><td>" + escaped(e.label) + "</td><td>" + escaped(shown_path(e.evaluation.path)) +
            "</td><td class=\"hash\">" + e.sha256 + "</td><td class=\"" +
            (verdict == "PASS"   ? "pass"
             : verdict == "FAIL" ? "fail"
                                 : "missing") +
            "\">" + verdict + "</td><td>" + std::to_string(acceptance::tests_of(e.evaluation).size()) + "</td></tr>\n";
  }
  html += "</tbody></table>\n";
  for (const LabelledEvaluation& e : evaluations)
    for (const std::string& c : e.evaluation.comments)
      html += "<p class=\"note\">" + escaped(e.label) + ": " + escaped(c) + "</p>\n";

  const std::vector<Line> lines = lines_of(evaluations);
  std::vector<std::string> kinds;
  for (const Line& l : lines)
    if (kinds.empty() || kinds.back() != l.kind) kinds.push_back(l.kind);
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    std::vector<Line> of_kind;
    std::copy_if(lines.begin(), lines.end(), std::back_inserter(of_kind),
                 [&](const Line& l) { return l.kind == kinds[k]; });
    html += "<h3>" + escaped(kinds[k]) + "</h3>\n" + kind_table(of_kind, evaluations);
    // The figures charted: those with a limit in any file, E always; else the kind's first.
    std::vector<std::string> symbols;
    for (const Line& l : of_kind) {
      const bool limited =
          std::any_of(l.rows.begin(), l.rows.end(), [](const EvaluationRow* r) { return r && r->limit; });
      if ((limited || l.figure == "E") && std::find(symbols.begin(), symbols.end(), l.figure) == symbols.end())
        symbols.push_back(l.figure);
    }
    if (symbols.empty()) symbols.push_back(of_kind.front().figure);
    for (const std::string& symbol : symbols) {
      std::vector<const Line*> charted;
      for (const Line& l : of_kind)
        if (l.figure == symbol) charted.push_back(&l);
      const std::string png = figure_chart(kinds[k], charted, evaluations, drawings,
                                           "acceptance_" + std::to_string(k) + "_" + std::to_string(figures) + ".png");
      html += html_png_figure(png, "acceptance " + kinds[k] + " " + symbol,
                              kinds[k] + ": " + symbol + " " + charted.front()->name + " (" + charted.front()->unit +
                                  ") of each test, a bar per label (none: not measured); dashed: the limit.");
      ++figures;
    }
  }
  html +=
      "<h3>Uncertainty</h3>\n<p>U is each figure's expanded uncertainty (k = 2), U = 2 sqrt(u_repeatability^2 + "
      "u_instrument^2): the repeatability part from the test's own runs, and the instrument's part (for the diagonals "
      "the laser's uncertainty of one reading, in each file's comments above). <b>Not in U</b>: the thermal term "
      "(ISO/TR 16907 8.3: the machine's thermal state, ISO 230-3; ISO/TR 16015's thermal influence on the length "
      "measurement), the instrument's misalignment (a laser's cosine error) and dead path; it is no ISO 230-9 "
      "uncertainty budget. A verdict is the figure against its limit, U not applied (no ISO 14253-1 decision rule); "
      "\"within U\" marks a verdict the uncertainty could turn.</p>\n";
  return html;
}

}  // namespace vc::report
