// The report's acceptance section (preproc/report/acceptance_section.hpp) from its pieces: two
// results files written by the acceptance writer (evaluation_file.hpp) and read back, one
// lacking a test the other has: each file's verdict and count, the "not measured" cells, every
// figure's verdict in its label's columns, the limit, the charts; the summary's line; and the
// refusals of a bad --acceptance value, a repeated label, a missing file and figures of two
// quantities.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <regex>

#include "report_test_support.hpp"
#include "vc/acceptance/evaluation_file.hpp"
#include "vc/report/acceptance_section.hpp"
#include "vc/report/drawings.hpp"
#include "vc/report/sha256.hpp"
#include "vc/tables/source_error.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
using acceptance::EvaluationRow;

EvaluationRow row(const std::string& test, const std::string& figure, double value, std::optional<double> limit,
                  const std::string& unit = "um") {
  EvaluationRow r;
  r.test = test;
  r.kind = test.rfind("body", 0) == 0 ? "body diagonal" : "face diagonal";
  r.figure = figure;
  r.name = figure == "E" ? "systematic deviation" : "repeatability";
  r.value = value;
  r.u_repeatability = 0.2;
  r.u_instrument = figure == "E" ? 0.707107 : 0;
  r.expanded = 2 * std::hypot(r.u_repeatability, r.u_instrument);
  r.limit = limit;
  if (limit) r.verdict = value <= *limit ? "PASS" : "FAIL";
  r.unit = unit;
  return r;
}

// "off": three tests, body-NPN-PNP failing E; "on": two tests (face-XY-NN-PP not measured), all passing.
class AcceptanceSection : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = test::scratch("acceptance_section");
    test::write(folder_ / "off.csv",
                acceptance::evaluation_csv("ISO 230-6 diagonals", {"u_instrument: the laser, 0.5 um per reading"},
                                           {row("body-NNN-PPP", "E", 12.5, 20), row("body-NNN-PPP", "R", 1.1, {}),
                                            row("body-NPN-PNP", "E", 34.25, 20), row("body-NPN-PNP", "R", 0.9, {}),
                                            row("face-XY-NN-PP", "E", 7.375, 20)}));
    test::write(folder_ / "on.csv",
                acceptance::evaluation_csv("ISO 230-6 diagonals", {},
                                           {row("body-NNN-PPP", "E", 2.5, 20), row("body-NNN-PPP", "R", 1.0, {}),
                                            row("body-NPN-PNP", "E", 19.0, 20), row("body-NPN-PNP", "R", 1.2, {})}));
  }
  void TearDown() override { fs::remove_all(folder_); }
  std::vector<report::AcceptanceInput> inputs() const {
    return {report::acceptance_input("compensation off=" + (folder_ / "off.csv").string()),
            report::acceptance_input(" compensation on = " + (folder_ / "on.csv").string())};
  }
  fs::path folder_;
};

TEST_F(AcceptanceSection, ShowsEachLabelsVerdictsSideBySideAndWhatOneDidNotMeasure) {
  const auto evaluations = report::read_acceptance(inputs());
  ASSERT_EQ(evaluations.size(), 2u);
  EXPECT_EQ(evaluations[1].label, "compensation on");  // blanks around the label and the file dropped
  EXPECT_EQ(evaluations[0].sha256, report::sha256_file_hex((folder_ / "off.csv").string()));
  EXPECT_EQ(report::acceptance_summary(evaluations),
            "compensation off: FAIL (3 tests); compensation on: PASS (2 tests)");
  const report::Drawings drawings;
  int figures = 0;
  const std::string html = report::acceptance_section(evaluations, drawings, figures);
  // The files: path, checksum, overall verdict, count of tests.
  EXPECT_NE(html.find("<td>compensation off</td><td>" + (folder_ / "off.csv").string() + "</td><td class=\"hash\">" +
                      evaluations[0].sha256 + "</td><td class=\"fail\">FAIL</td><td>3</td>"),
            std::string::npos)
      << html.substr(0, 2000);
  EXPECT_NE(html.find("<td class=\"pass\">PASS</td><td>2</td>"), std::string::npos);
  EXPECT_NE(html.find("compensation off: u_instrument: the laser, 0.5 um per reading"), std::string::npos);
  // A table per kind, a column group per label.
  EXPECT_NE(html.find("<h3>body diagonal</h3>"), std::string::npos);
  EXPECT_NE(html.find("<h3>face diagonal</h3>"), std::string::npos);
  EXPECT_EQ(test::count(html, "<th colspan=\"3\">compensation off</th><th colspan=\"3\">compensation on</th>"), 2u);
  // Each figure's value, U and verdict under its label, then the limit (within U of it: marked).
  const std::string u = "1.470";  // 2 sqrt(0.2^2 + 0.707107^2)
  EXPECT_NE(html.find("<td>body-NPN-PNP</td><td>E systematic deviation</td><td>um</td><td>34.250</td><td>" + u +
                      "</td><td class=\"fail\">FAIL</td><td>19.000</td><td>" + u +
                      "</td><td class=\"pass\">PASS (within U)</td><td>20.000</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<td>body-NNN-PPP</td><td>R repeatability</td><td>um</td><td>1.100</td><td>0.400</td><td>-</td>"
                      "<td>1.000</td><td>0.400</td><td>-</td><td>-</td>"),
            std::string::npos);
  // The test "on" lacks: not measured in its columns, once (it has one figure).
  EXPECT_NE(html.find("<td>face-XY-NN-PP</td><td>E systematic deviation</td><td>um</td><td>7.375</td><td>" + u +
                      "</td><td class=\"pass\">PASS</td><td colspan=\"3\" class=\"missing\">not measured</td>"
                      "<td>20.000</td>"),
            std::string::npos);
  EXPECT_EQ(test::count(html, "not measured</td>"), 1u);
  // A chart per kind for E (the figure with limits; R has none): 2, each an embedded PNG.
  EXPECT_EQ(figures, 2);
  EXPECT_EQ(test::count(html, "<img src=\"data:image/png;base64,iVBORw0KGgo"), 2u);
  EXPECT_NE(html.find("alt=\"acceptance body diagonal E\""), std::string::npos);
  EXPECT_NE(html.find("alt=\"acceptance face diagonal E\""), std::string::npos);
  // The uncertainty statement: what U holds, what it does not.
  EXPECT_NE(html.find("U = 2 sqrt(u_repeatability^2 + u_instrument^2)"), std::string::npos);
  EXPECT_NE(html.find("<b>Not in U</b>: the thermal term"), std::string::npos);
  EXPECT_NE(html.find("no ISO 230-9"), std::string::npos);
}

TEST_F(AcceptanceSection, LimitsThatDifferAreShownPerLabel) {
  test::write(folder_ / "on.csv",
              acceptance::evaluation_csv("ISO 230-6 diagonals", {}, {row("body-NNN-PPP", "E", 2.5, 25)}));
  const auto evaluations = report::read_acceptance(inputs());
  const report::Drawings drawings;
  int figures = 0;
  const std::string html = report::acceptance_section(evaluations, drawings, figures);
  EXPECT_NE(html.find("<td>compensation off 20.000; compensation on 25.000</td>"), std::string::npos);
  EXPECT_EQ(report::acceptance_summary(evaluations),
            "compensation off: FAIL (3 tests); compensation on: PASS (1 test)");
}

// Runs `f`, which must throw a std::exception whose text matches `message`.
template <class F>
void expect_refusal(F f, const std::string& message) {
  try {
    f();
    ADD_FAILURE() << "accepted; expected: " << message;
  } catch (const std::exception& e) {
    EXPECT_TRUE(std::regex_search(e.what(), std::regex(message))) << e.what();
  }
}

TEST_F(AcceptanceSection, BadValuesLabelsAndFilesAreRefused) {
  expect_refusal([] { report::acceptance_input("off.csv"); }, "--acceptance 'off.csv': give LABEL=FILE.csv");
  expect_refusal([] { report::acceptance_input(" =off.csv"); }, "the label before '=' is empty");
  expect_refusal([] { report::acceptance_input("off="); }, "the file after '=' is empty");
  const std::string off = (folder_ / "off.csv").string();
  expect_refusal([&] { report::read_acceptance({{"a", off}, {"a", off}}); }, "the label 'a' twice");
  expect_refusal(
      [&] {
        report::read_acceptance({{"a", (folder_ / "none.csv").string()}});
      },
      "none.csv: error: cannot open the acceptance results");
  expect_refusal([&] { report::read_acceptance({{"a", folder_.string()}}); }, "not a file");
  // E in arcsec in one file and in um in the other: no comparison.
  test::write(folder_ / "angles.csv",
              acceptance::evaluation_csv("ISO 230-6 diagonals", {}, {row("body-NNN-PPP", "E", 2.5, 20, "arcsec")}));
  expect_refusal(
      [&] {
        report::read_acceptance({{"off", off}, {"angles", (folder_ / "angles.csv").string()}});
      },
      "angles.csv:3: error: test body-NNN-PPP, figure E in arcsec here and in um");
  // Other units of one quantity compare: mm shown in the first file's um.
  test::write(folder_ / "mm.csv",
              acceptance::evaluation_csv("ISO 230-6 diagonals", {}, {row("body-NNN-PPP", "E", 0.0025, 0.02, "mm")}));
  const auto evaluations = report::read_acceptance({{"off", off}, {"mm", (folder_ / "mm.csv").string()}});
  const report::Drawings drawings;
  int figures = 0;
  EXPECT_NE(report::acceptance_section(evaluations, drawings, figures)
                .find("<td>body-NNN-PPP</td><td>E systematic deviation</td><td>um</td><td>12.500</td>"),
            std::string::npos);
}

// The writer and the reader agree: every field read back as written (numbers to 1e-6).
TEST(AcceptanceEvaluationFile, ReadsBackWhatTheWriterWrote) {
  const fs::path folder = test::scratch("evaluation_file");
  const std::vector<EvaluationRow> rows = {row("body-NNN-PPP", "E", 12.3456784, 20), row("body-NNN-PPP", "R", 1.1, {}),
                                           row("face-ZX-NP-PN", "E", 21.0, 20)};
  test::write(folder / "e.csv", acceptance::evaluation_csv("ISO 230-6 diagonals", {"a note"}, rows));
  const acceptance::Evaluation e = acceptance::read_evaluation((folder / "e.csv").string());
  ASSERT_EQ(e.rows.size(), rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(e.rows[k].test, rows[k].test);
    EXPECT_EQ(e.rows[k].kind, rows[k].kind);
    EXPECT_EQ(e.rows[k].figure, rows[k].figure);
    EXPECT_EQ(e.rows[k].name, rows[k].name);
    EXPECT_NEAR(e.rows[k].value, rows[k].value, 5e-7);
    EXPECT_NEAR(e.rows[k].expanded, rows[k].expanded, 5e-7);
    EXPECT_EQ(e.rows[k].limit, rows[k].limit);
    EXPECT_EQ(e.rows[k].verdict, rows[k].verdict);
    EXPECT_EQ(e.rows[k].line, static_cast<int>(k) + 4);  // after 2 comments and the header
  }
  EXPECT_EQ(e.comments, (std::vector<std::string>{"volcomp acceptance evaluate: ISO 230-6 diagonals; U expanded "
                                                  "uncertainty (k = 2); thermal not evaluated",
                                                  "a note"}));
  EXPECT_EQ(acceptance::overall_verdict(e), "FAIL");
  EXPECT_EQ(acceptance::tests_of(e), (std::vector<std::string>{"body-NNN-PPP", "face-ZX-NP-PN"}));
  // A text with a comma could not be read back: the writer refuses it.
  EXPECT_THROW(acceptance::evaluation_csv("x", {}, {row("a,b", "E", 1, {})}), std::invalid_argument);
  fs::remove_all(folder);
}

}  // namespace
}  // namespace vc
