// `volcomp report --acceptance` end to end, as a user runs it (issue 47): `volcomp acceptance
// plan` on the MC-300 (5 targets, 2 runs: small), `acceptance simulate` compensation off and on
// with a `volcomp perturb --seed 3` file (the MC-300's real file is the truth), `acceptance
// evaluate` of each against limits that the uncompensated machine fails and the compensated one
// passes, then the report of both, opened in headless chromium: every test's name, every
// acceptance chart decoded, both verdicts, no request and no console message. Bad --acceptance
// values and files: a clear message, a non-zero exit, no page.
#include <gtest/gtest.h>

#include "report_test_support.hpp"
#include "test_support.hpp"
#include "vc/acceptance/evaluation_file.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;

// 5 axis plots, the balance, the volume map's 4 sheets; then A and E (the figures with limits)
// for the body and the face diagonals, E for the axis runs, G(b) (its limit) for the circles and
// X (the kind's first, no limit) for the R-test.
constexpr int kAcceptanceFigures = 7;
constexpr int kFigures = 10 + kAcceptanceFigures;

const std::vector<std::string> kTests = {"body-NNN-PPP",  "body-NNP-PPN",  "body-NPN-PNP",  "body-NPP-PNN",
                                         "face-XY-NN-PP", "face-XY-NP-PN", "face-YZ-NN-PP", "face-YZ-NP-PN",
                                         "face-ZX-NN-PP", "face-ZX-NP-PN"};
const std::vector<std::string> kCircles = {"circle-XY", "circle-YZ", "circle-ZX"};
const std::vector<std::string> kAxisRuns = {"axis-X", "axis-Y", "axis-Z"};
const std::vector<std::string> kRTest = {"rtest-B", "rtest-C", "rtest-BC"};

// Runs `command` through volcomp, expecting `exit_code`.
void volcomp(const std::string& command, int exit_code = 0) {
  const test::CommandResult r = test::run_volcomp(command);
  ASSERT_EQ(r.exit_code, exit_code) << command << "\n" << r.out;
}

TEST(VolcompReportAcceptance, OffAndOnSideBySideInTheBrowser) {
  const fs::path dir = test::scratch("acceptance_page");
  const std::string mc300 = test::machine_path("mc300"), plan = (dir / "plan").string();
  volcomp("acceptance plan " + mc300 + " --targets 5 --runs 2 -o " + plan);
  volcomp("perturb " + mc300 + " -o " + (dir / "other").string() + " --seed 3");
  const std::string simulate = "acceptance simulate " + plan + " --true " + mc300 + " --noise-um 0.3 --seed 5 ";
  volcomp(simulate + "-o " + (dir / "m_off").string());
  volcomp(simulate + "--compensation " + (dir / "other" / "mc300.toml").string() + " -o " + (dir / "m_on").string());
  // E off 7 to 34 um, on 2.5 to 10 um; G(b) off 6.6 to 10.7 um, on 3.1 to 3.5 um, 2 um more of
  // the ballbar's noise (tests/cli/volcomp_acceptance_test.cpp): off fails, on passes.
  test::write(dir / "limits.toml", "[diagonal]\nE_um = 15\nA_um = 20\n[circle]\nGb_um = 8\n");
  const std::string evaluate = "acceptance evaluate " + plan + " --tolerances " + (dir / "limits.toml").string();
  volcomp(evaluate + " --measurements " + (dir / "m_off").string() + " -o " + (dir / "off").string(), 1);
  volcomp(evaluate + " --measurements " + (dir / "m_on").string() + " -o " + (dir / "on").string(), 0);
  const fs::path page = dir / "report.html";
  const test::CommandResult r =
      test::run_volcomp("report " + mc300 + " --acceptance 'compensation off=" + (dir / "off.csv").string() +
                        "' --acceptance 'compensation on=" + (dir / "on.csv").string() + "' -o " + page.string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(
      r.out.find("(7 sections, " + std::to_string(kFigures) + " figures, 0 measurements, 2 acceptance evaluations"),
      std::string::npos)
      << r.out;
  const std::string html = test::file_text(page);
  EXPECT_NE(html.find("<section id=\"acceptance\">\n<h2>Acceptance (ISO/TR 16907 11.3)</h2>"), std::string::npos);
  EXPECT_NE(html.find("<td>acceptance verdict (ISO/TR 16907 11.3)</td><td>compensation off: FAIL (19 tests); "
                      "compensation on: PASS (19 tests)</td>"),
            std::string::npos);
  for (const char* file : {"off.csv", "on.csv"}) {
    const test::CommandResult sum = test::run_command("sha256sum '" + (dir / file).string() + "'");
    EXPECT_NE(html.find("<td>" + (dir / file).string() + "</td><td class=\"hash\">" + sum.out.substr(0, 64) + "</td>"),
              std::string::npos)
        << file;
  }
  // Per test and figure a row; each label's E verdict as its results file says.
  const acceptance::Evaluation off = acceptance::read_evaluation((dir / "off.csv").string());
  std::size_t failed = 0, failed_e = 0;
  for (const acceptance::EvaluationRow& row : off.rows) {
    failed += row.verdict == "FAIL";
    failed_e += row.figure == "E" && row.verdict == "FAIL";
  }
  EXPECT_GT(failed_e, 0u);
  EXPECT_LT(failed_e, 10u);  // some diagonals pass uncompensated: a verdict is a figure's
  // Each failed figure marked in its row, and the file's overall verdict; "on" fails none.
  EXPECT_EQ(test::count(html, "<td class=\"fail\">FAIL"), failed + 1);
  EXPECT_EQ(acceptance::overall_verdict(acceptance::read_evaluation((dir / "on.csv").string())), "PASS");

  // In the browser: every picture decoded, no request, no console message; every test, every
  // acceptance chart and both verdicts on the rendered page.
  SKIP_WITHOUT_CHROMIUM();
  const test::CommandResult dom = test::chromium("--dump-dom", test::probed_copy(page, dir), dir / "chromium.log");
  ASSERT_EQ(dom.exit_code, 0) << test::file_text(dir / "chromium.log");
  EXPECT_EQ(test::probe_report(dom.out),
            "images=" + std::to_string(kFigures) + " decoded=" + std::to_string(kFigures) + " fetched=0 []");
  EXPECT_EQ(test::page_messages(dir / "chromium.log"), std::vector<std::string>{});
  const std::size_t section = dom.out.find("<section id=\"acceptance\">");
  ASSERT_NE(section, std::string::npos);
  const std::string rendered = dom.out.substr(section, dom.out.find("</section>", section) - section);
  for (const std::string& test : kTests) EXPECT_EQ(test::count(rendered, "<td>" + test + "</td>"), 5u) << test;
  for (const std::string& test : kAxisRuns) EXPECT_EQ(test::count(rendered, "<td>" + test + "</td>"), 5u) << test;
  EXPECT_EQ(test::count(rendered, "alt=\"acceptance axis run E\""), 1u);
  for (const std::string& test : kRTest) EXPECT_EQ(test::count(rendered, "<td>" + test + "</td>"), 4u) << test;
  EXPECT_EQ(test::count(rendered, "alt=\"acceptance R-test X\""), 1u);
  for (const std::string& test : kCircles) EXPECT_EQ(test::count(rendered, "<td>" + test + "</td>"), 3u) << test;
  EXPECT_EQ(test::count(rendered, "alt=\"acceptance circle G(b)\""), 1u);
  for (const char* kind : {"body diagonal", "face diagonal"})
    for (const char* symbol : {"A", "E"})
      EXPECT_EQ(test::count(rendered, "alt=\"acceptance " + std::string(kind) + " " + symbol + "\""), 1u)
          << kind << " " << symbol;
  EXPECT_EQ(test::count(rendered, "<img src=\"data:image/png;base64,"), static_cast<std::size_t>(kAcceptanceFigures));
  EXPECT_NE(rendered.find("<td class=\"fail\">FAIL</td><td>19</td>"), std::string::npos);
  EXPECT_NE(rendered.find("<td class=\"pass\">PASS</td><td>19</td>"), std::string::npos);
  fs::remove_all(dir);
}

TEST(VolcompReportAcceptance, BadValuesAndFilesAreRefusedWithoutAPage) {
  const fs::path dir = test::scratch("acceptance_refused");
  const fs::path page = dir / "report.html";
  const std::string mc300 = test::machine_path("mc300");
  acceptance::EvaluationRow row;
  row.test = "body-NNN-PPP";
  row.kind = "body diagonal";
  row.figure = "E";
  row.unit = "um";
  test::write(dir / "good.csv", acceptance::evaluation_csv("ISO 230-6 diagonals", {}, {row}));
  test::write(dir / "bad.csv",
              "test,kind,figure,name,value,u_repeatability,u_instrument,U,limit,unit,verdict\n"
              "body-NNN-PPP,body diagonal,E,systematic deviation,12.3,0.2,0.7,1.5,20,um,OK\n");
  const std::string good = (dir / "good.csv").string();
  test::expect_refused(mc300 + " --acceptance " + good, "give LABEL=FILE.csv", page);
  test::expect_refused(mc300 + " --acceptance '=" + good + "'", "the label before '=' is empty", page);
  test::expect_refused(mc300 + " --acceptance a=" + good + " --acceptance a=" + good, "the label 'a' twice", page);
  test::expect_refused(mc300 + " --acceptance a=" + (dir / "none.csv").string(),
                       "none.csv: error: cannot open the acceptance results", page);
  test::expect_refused(mc300 + " --acceptance a=" + (dir / "bad.csv").string(),
                       "bad.csv:2:74: error: verdict 'OK': PASS, FAIL or empty (no limit)", page);
  test::expect_refused(mc300 + " --acceptance a=" + dir.string(), "not a file", page);
  EXPECT_FALSE(fs::exists(page));
  // An older page stays as it was.
  test::write(page, "<html>an older report</html>\n");
  test::expect_refused(mc300 + " --acceptance a=" + (dir / "bad.csv").string(), "bad.csv:2:", page);
  EXPECT_EQ(test::file_text(page), "<html>an older report</html>\n");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vc
