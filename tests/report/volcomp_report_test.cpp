// `volcomp report` and `volcomp plot --volume` (issue 37), run as a user runs them, and the
// report opened in a real browser (Debian's chromium, headless): every picture decodes, the page
// makes no request and logs nothing to the console, it prints to A4 with a known number of pages,
// and a screenshot can be taken. Without chromium the browser tests are skipped, saying so.
// Bad input (a missing machine file, a measurements folder that is missing, not a folder, not
// readable or holding a bad file) stops with a clear message, a non-zero exit and no page (an
// older page stays as it was).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "report_test_support.hpp"
#include "test_support.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
using test::chromium;
using test::count;
using test::expect_refused;
using test::page_messages;
using test::probed_copy;
using test::scratch;
using test::write;

// Laser runs of X's positioning (ISO 230-2 cycle: 4 runs each way, targets -600..0 mm), a smooth
// error with a reversal and a little scatter, in identify laser's long layout; named after the
// error they measure.
std::string laser_runs() {
  std::ostringstream s;
  s << "# instrument: test laser\n# temperature_degC: 20.2\ntarget[mm],run,direction,deviation[um]\n";
  for (int run = 1; run <= 4; ++run)
    for (const int sign : {1, -1})
      for (int k = 0; k <= 6; ++k) {
        const int target = sign > 0 ? -600 + 100 * k : -100 * k;
        const double scatter = ((run * 7 + k * 3) % 5 - 2) * 0.1;
        s << target << ',' << run << ',' << (sign > 0 ? '+' : '-') << ','
          << 3.0 * std::sin(target / 150.0) + sign * 0.6 + scatter << '\n';
      }
  return s.str();
}

// A ballbar test in XY, R 150 mm, both directions (identify circle's wide layout): an
// elliptic deviation (squareness) and a hysteresis of 0.8 um.
std::string circular_test() {
  std::ostringstream s;
  s << "# plane: XY\n# radius_mm: 150\nangle[deg],ccw[um],cw[um]\n";
  for (int a = 0; a < 360; a += 15) {
    const double ccw = 3.0 * std::sin(2 * a * M_PI / 180.0);
    s << a << ',' << ccw << ',' << ccw + 0.8 << '\n';
  }
  return s.str();
}

// One MC-300 report with two measurements (and a file that is neither), made once for the suite.
class VolcompReport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new fs::path(scratch("page"));
    const fs::path measurements = *folder_ / "measurements";
    fs::create_directories(measurements);
    write(measurements / "exx.csv", laser_runs());
    write(measurements / "ballbar_xy.csv", circular_test());
    write(measurements / "readme.txt", "not a measurement\n");
    page_ = new fs::path(*folder_ / "mc300_report.html");
    output_ = new test::CommandResult(test::run_volcomp("report " + test::machine_path("mc300") + " --measurements " +
                                                        measurements.string() + " -o " + page_->string()));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*folder_);
    delete folder_;
    delete page_;
    delete output_;
  }
  static fs::path* folder_;
  static fs::path* page_;
  static test::CommandResult* output_;
};
fs::path* VolcompReport::folder_ = nullptr;
fs::path* VolcompReport::page_ = nullptr;
test::CommandResult* VolcompReport::output_ = nullptr;

// 5 axis plots, the balance's bar chart, the volume map's 4 sheets (L = 0 and 100 mm, rotary
// axes at 0 and at their worst), the laser's ISO 230-2 graph and the ballbar's polar plot.
constexpr int kFigures = 12;

TEST_F(VolcompReport, PageHoldsEveryPartAndNeedsNothingElse) {
  ASSERT_EQ(output_->exit_code, 0) << output_->out;
  EXPECT_NE(output_->out.find("(7 sections, 12 figures, 2 measurements"), std::string::npos) << output_->out;
  const std::string html = test::file_text(*page_);
  for (const char* id : {"machine", "tables", "location", "compensation", "balance", "volume", "measurements"})
    EXPECT_NE(html.find("<section id=\"" + std::string(id) + "\">"), std::string::npos) << id;
  // Self-contained: no script, style sheet, font or frame from elsewhere, no address at all.
  for (const char* outside : {"http://", "https://", "<script", "<link", "@import", "url(", "<iframe", "//fonts"})
    EXPECT_EQ(html.find(outside), std::string::npos) << outside;
  // Every picture a PNG embedded whole (base64 of the PNG signature, over 20 kB).
  EXPECT_EQ(count(html, "<figure"), static_cast<std::size_t>(kFigures));
  EXPECT_EQ(count(html, "<img "), static_cast<std::size_t>(kFigures));
  // (Found by hand: std::regex recurses per character and overflows the stack on a 1.8 MB page.)
  const std::string prefix = "<img src=\"data:image/png;base64,";
  int images = 0;
  for (std::size_t at = html.find(prefix); at != std::string::npos; at = html.find(prefix, at + 1), ++images) {
    const std::size_t begin = at + prefix.size(), end = html.find('"', begin);
    ASSERT_NE(end, std::string::npos);
    const std::string data = html.substr(begin, end - begin);
    EXPECT_EQ(data.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/="),
              std::string::npos)
        << "picture " << images << ": not base64";
    EXPECT_EQ(data.rfind("iVBORw0KGgo", 0), 0u) << "picture " << images << " is not a PNG";
    EXPECT_GT(data.size(), 20000u) << "picture " << images << " is nearly empty";
  }
  EXPECT_EQ(images, kFigures);
  // The full correction is stated, not drawn as zeros.
  EXPECT_NE(html.find("volkins: 0 on the model; what remains is measurement uncertainty"), std::string::npos);
  // The location errors as the machine file has them (arcsec).
  EXPECT_NE(html.find("<td>EC0Y</td><td>squareness: the Y line turned about z</td><td>-5.000</td><td>arcsec</td>"),
            std::string::npos);
  // The compensation types the MC-300 provides (ISO/TR 16907 Annex A), declared in the summary
  // and in their section with what provides them.
  EXPECT_NE(html.find("<td>compensation types (ISO/TR 16907 Annex A)</td><td>L-POS, L-STR, L-SQU, L-ANG, L-VOL, FOR, "
                      "L-VOL+, R-POS, R-RAX, R-POR, R-ANG, R-VOL, R-VOL+</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<td>R-POR</td><td>position and orientation of rotary axes (location errors)</td><td>B: EA0B, "
                      "EC0B; C: EA0C</td>"),
            std::string::npos);
  // C's zero position EC0C is an angular positioning error.
  EXPECT_NE(html.find("<td>R-POS</td><td>angular positioning of rotary axes</td><td>B: EBB (b.csv); C: EC0C (zero "
                      "position); C: ECC (c.csv)</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<td>R-VOL+</td><td>R-VOL with the functional orientation (R-VOL + FOR)</td><td>complete: "
                      "R-POS + R-RAX + R-POR + R-ANG + FOR</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<td>thermal</td><td>not an Annex A type</td><td>none</td>"), std::string::npos);
  // The measurements: the ISO figures, the file that is neither named as skipped.
  EXPECT_NE(html.find("ISO 230-2: EXX positioning of axis X, MC-300"), std::string::npos);
  EXPECT_NE(html.find("Circular test (ISO 230-4), plane XY, radius 150.0 mm"), std::string::npos);
  EXPECT_NE(html.find("circular hysteresis H</td><td>0.80 um"), std::string::npos);
  EXPECT_NE(html.find("skipped: readme.txt: not a .csv file"), std::string::npos);
}

// The checksums on the page are the files' (coreutils' sha256sum, the tool a reader uses).
TEST_F(VolcompReport, ChecksumsAreTheFilesOwn) {
  ASSERT_EQ(output_->exit_code, 0) << output_->out;
  const std::string html = test::file_text(*page_);
  for (const std::string& file :
       {test::machine_path("mc300"), test::source_path("tables/data/mc300/x.csv"),
        test::source_path("tables/data/mc300/y.csv"), test::source_path("tables/data/mc300/z.csv"),
        test::source_path("tables/data/mc300/b.csv"), test::source_path("tables/data/mc300/c.csv")}) {
    const test::CommandResult sum = test::run_command("sha256sum '" + file + "'");
    ASSERT_EQ(sum.exit_code, 0);
    const std::string row = "<td>" + fs::absolute(file).lexically_normal().string() + "</td>";
    const std::size_t at = html.find(row);
    ASSERT_NE(at, std::string::npos) << file << " is not listed";
    EXPECT_NE(html.find(sum.out.substr(0, 64), at), std::string::npos) << file;
  }
}

// ---- in the browser ------------------------------------------------------------------------

TEST_F(VolcompReport, BrowserDecodesEveryPictureWithoutRequestsOrConsoleMessages) {
  SKIP_WITHOUT_CHROMIUM();
  ASSERT_EQ(output_->exit_code, 0) << output_->out;
  const fs::path folder = scratch("dom");
  const test::CommandResult dom = chromium("--dump-dom", probed_copy(*page_, folder), folder / "chromium.log");
  ASSERT_EQ(dom.exit_code, 0) << test::file_text(folder / "chromium.log");
  EXPECT_EQ(test::probe_report(dom.out), "images=12 decoded=12 fetched=0 []");
  EXPECT_EQ(count(dom.out, "<figure"), static_cast<std::size_t>(kFigures));
  EXPECT_EQ(page_messages(folder / "chromium.log"), std::vector<std::string>{});
  fs::remove_all(folder);
}

// The probe itself is checked: on a page with a broken picture, a fetched one and a script error
// it reports them (else a passing test above would prove nothing).
TEST(VolcompReportBrowser, ProbeSeesBrokenPicturesRequestsAndConsoleErrors) {
  SKIP_WITHOUT_CHROMIUM();
  const fs::path folder = scratch("probe");
  write(folder / "bad.html",
        "<!DOCTYPE html><html><body><img src=\"missing.png\"><img src=\"http://192.0.2.1/x.png\">"
        "<script>console.error('boom'); not_defined();</script></body></html>\n");
  const test::CommandResult dom =
      chromium("--dump-dom", probed_copy(folder / "bad.html", folder), folder / "chromium.log");
  ASSERT_EQ(dom.exit_code, 0);
  EXPECT_NE(dom.out.find("images=2 decoded=0 fetched=1 [http://192.0.2.1/x.png]"), std::string::npos) << dom.out;
  EXPECT_EQ(page_messages(folder / "chromium.log").size(), 2u) << test::file_text(folder / "chromium.log");
  fs::remove_all(folder);
}

// Printed to PDF on A4: the header and summary, the machine, 3 pages for the 5 axis plots (two
// a page), the location errors (2 pages: 36 rows, the MC-300 file's comments on its non-zero
// values as "where from"), the compensation types (a page), the balance, the volume map's text and table and its 4 sheets (a
// page each), and a page per measurement: 16. (Each section starts a page; a sheet or an axis
// plot that did not fit its page's share, or a section that did not break, would change it.)
TEST_F(VolcompReport, PrintsToSixteenA4Pages) {
  SKIP_WITHOUT_CHROMIUM();
  ASSERT_EQ(output_->exit_code, 0) << output_->out;
  const fs::path folder = scratch("pdf");
  const fs::path pdf = folder / "report.pdf";
  const test::CommandResult r =
      chromium("--no-pdf-header-footer --print-to-pdf='" + pdf.string() + "'", *page_, folder / "chromium.log");
  ASSERT_EQ(r.exit_code, 0) << test::file_text(folder / "chromium.log");
  const std::string bytes = test::file_text(pdf);
  ASSERT_EQ(bytes.rfind("%PDF-", 0), 0u) << "not a PDF";
  const std::regex page_object("/Type\\s*/Page[^s]");
  const auto pages =
      std::distance(std::sregex_iterator(bytes.begin(), bytes.end(), page_object), std::sregex_iterator());
  EXPECT_EQ(pages, 16);
  // A4 is 595.28 x 841.89 pt; chromium writes its page size in its own rounding.
  const std::regex media_box("/MediaBox \\[0 0 (59[45]\\.[0-9]+) (84[12]\\.[0-9]+)\\]");
  EXPECT_EQ(std::distance(std::sregex_iterator(bytes.begin(), bytes.end(), media_box), std::sregex_iterator()), pages);
  fs::remove_all(folder);
}

TEST_F(VolcompReport, ScreenshotShowsThePage) {
  SKIP_WITHOUT_CHROMIUM();
  ASSERT_EQ(output_->exit_code, 0) << output_->out;
  const fs::path folder = scratch("screenshot");
  const fs::path png = folder / "report.png";
  const test::CommandResult r = chromium(
      "--hide-scrollbars --window-size=1280,1600 --screenshot='" + png.string() + "'", *page_, folder / "chromium.log");
  ASSERT_EQ(r.exit_code, 0) << test::file_text(folder / "chromium.log");
  const std::string bytes = test::file_text(png);
  ASSERT_GT(bytes.size(), 50000u) << "an empty page";
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned char>(bytes[at]) << 24) | (static_cast<unsigned char>(bytes[at + 1]) << 16) |
           (static_cast<unsigned char>(bytes[at + 2]) << 8) | static_cast<unsigned char>(bytes[at + 3]);
  };
  EXPECT_EQ(be32(16), 1280);
  EXPECT_EQ(be32(20), 1600);
  fs::remove_all(folder);
}

// ---- the volume map ------------------------------------------------------------------------

// A volume map's CSV: its blocks (gnuplot's index: two blank lines apart), rows first, second,
// e[um].
std::vector<std::vector<std::array<double, 3>>> map_blocks(const fs::path& path) {
  std::vector<std::vector<std::array<double, 3>>> blocks;
  std::ifstream csv(path);
  int blank = 0;
  for (std::string line; std::getline(csv, line);) {
    if (line.empty()) {
      ++blank;
      continue;
    }
    if (line[0] == '#') continue;
    if (blocks.empty() || blank >= 2) blocks.emplace_back();
    blank = 0;
    std::array<double, 3> row{};
    std::sscanf(line.c_str(), "%lf,%lf,%lf", &row[0], &row[1], &row[2]);
    blocks.back().push_back(row);
  }
  return blocks;
}

// volcomp plot --volume: the sheets drawn with their data; the uncompensated |e| in the CSV at a
// pose is what `volcomp error` gives there; the printed maxima are the CSV's; the modified
// method's tables leave less than the usual practice's on every sheet (the MC-300's known gain).
TEST(VolcompPlotVolume, MapAgreesWithTheModelAndIsQuick) {
  const fs::path folder = scratch("volume");
  const test::CommandResult r = test::run_volcomp("plot " + test::machine_path("mc300") + " -o " + folder.string() +
                                                  " --volume --tool-lengths 100");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("volkins: 0 on the model; what remains is measurement uncertainty"), std::string::npos);
  const std::regex seconds("volume map: 2646 poses \\(21 x 21 x 3 levels per sheet\\), ([0-9.]+) s");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, seconds)) << r.out;
  EXPECT_LT(std::stod(m[1]), 10.0) << "the map is to be quick";
  for (const char* sheet : {"volume_L100_rotary0", "volume_L100_worst"}) {
    ASSERT_TRUE(fs::exists(folder / (std::string(sheet) + ".png"))) << sheet;
    // The blocks: none, usual, modified at Z = -310, -155, 0 mm; 21 x 21 rows each.
    const auto blocks = map_blocks(folder / (std::string(sheet) + ".csv"));
    ASSERT_EQ(blocks.size(), 9u) << sheet;
    for (const auto& b : blocks) EXPECT_EQ(b.size(), 441u);
    // The printed line: "  L 100 mm, <rotary>: none N, usual practice U, modified method M  (<image>)".
    const std::size_t at = r.out.find(std::string(sheet) + ".png");
    const std::string line = r.out.substr(r.out.rfind("\n", at) + 1, at - r.out.rfind("\n", at));
    std::smatch f;
    ASSERT_TRUE(
        std::regex_search(line, f, std::regex("none ([0-9.]+), usual practice ([0-9.]+), modified method ([0-9.]+)")))
        << line;
    for (int c = 0; c < 3; ++c) {
      double largest = 0;
      for (int level = 0; level < 3; ++level)
        for (const auto& row : blocks[static_cast<std::size_t>(c * 3 + level)]) largest = std::max(largest, row[2]);
      EXPECT_NEAR(std::stod(f[c + 1]), largest, 0.05) << sheet << " compensation " << c;
    }
    EXPECT_LT(std::stod(f[3]), std::stod(f[2])) << sheet << ": the modified method leaves less than the usual practice";
    if (std::string(sheet) == "volume_L100_rotary0") {
      // A corner and an inner point of the lowest level, uncompensated, against `volcomp error`.
      const fs::path poses = folder / "poses.csv";
      const auto& low = blocks[0];
      write(poses, "x,y,z,b,c\n" + std::to_string(low[0][0]) + "," + std::to_string(low[0][1]) + ",-310,0,0\n" +
                       std::to_string(low[200][0]) + "," + std::to_string(low[200][1]) + ",-310,0,0\n");
      const test::CommandResult e = test::run_volcomp("error " + test::machine_path("mc300") + " --poses " +
                                                      poses.string() + " --tool-length 100");
      ASSERT_EQ(e.exit_code, 0) << e.out;
      const std::string errors_csv = (folder / "errors.csv").string();
      write(errors_csv, e.out);
      const test::CsvTable errors(errors_csv);
      for (std::size_t k = 0; k < 2; ++k) {
        const double um = 1e3 * std::hypot(errors.at(k, "ex"), errors.at(k, "ey"), errors.at(k, "ez"));
        EXPECT_NEAR(low[k == 0 ? 0 : 200][2], um, 1e-6) << "pose " << k;
      }
    }
  }
  fs::remove_all(folder);
}

// --plane xz --controller none: the X-Z sheets at three Y levels, no compensation only, named
// volume_xz_...; a point of the lowest Y level is the |e| `volcomp error` gives there. A plane
// that is not two linear axes is refused before any picture.
TEST(VolcompPlotVolume, AnotherPlaneIsTheModelsErrorThere) {
  const fs::path folder = scratch("volume_xz");
  const test::CommandResult r = test::run_volcomp("plot " + test::machine_path("mc300") + " -o " + folder.string() +
                                                  " --volume --plane xz --controller none --tool-lengths 0");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto blocks = map_blocks(folder / "volume_xz_L0_rotary0.csv");
  ASSERT_EQ(blocks.size(), 3u);  // none at Y -320, -160, 0
  const auto& low = blocks[0];
  ASSERT_EQ(low.size(), 441u);
  const fs::path poses = folder / "poses.csv";
  write(poses, "x,y,z,b,c\n" + std::to_string(low[123][0]) + ",-320," + std::to_string(low[123][1]) + ",0,0\n");
  const test::CommandResult e =
      test::run_volcomp("error " + test::machine_path("mc300") + " --poses " + poses.string() + " --tool-length 0");
  ASSERT_EQ(e.exit_code, 0) << e.out;
  write(folder / "errors.csv", e.out);
  const test::CsvTable errors((folder / "errors.csv").string());
  EXPECT_NEAR(low[123][2], 1e3 * std::hypot(errors.at(0, "ex"), errors.at(0, "ey"), errors.at(0, "ez")), 1e-6);
  const test::CommandResult bad = test::run_volcomp("plot " + test::machine_path("mc300") + " -o " +
                                                    (folder / "bad").string() + " --volume --plane xb");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.out.find("the volume map's plane 'xb' is not two of MC-300's linear axes (xyz)"), std::string::npos)
      << bad.out;
  EXPECT_FALSE(fs::exists(folder / "bad"));
  fs::remove_all(folder);
}

TEST(VolcompPlotVolume, BadToolLengthsAreRefusedWithoutFiles) {
  const fs::path folder = scratch("volume_refused");
  const test::CommandResult r =
      test::run_volcomp("plot " + test::machine_path("mc300") + " -o " + folder.string() + " --tool-lengths 0,100");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("--tool-lengths, --plane and --controller are for the volume map: add --volume"),
            std::string::npos)
      << r.out;
  // A negative tool length is refused before any picture is drawn: the folder stays empty.
  const test::CommandResult negative = test::run_volcomp("plot " + test::machine_path("mc300") + " -o " +
                                                         folder.string() + " --volume --tool-lengths 0,-5");
  EXPECT_NE(negative.exit_code, 0);
  EXPECT_NE(negative.out.find("tool lengths must be numbers >= 0 mm"), std::string::npos) << negative.out;
  EXPECT_TRUE(fs::is_empty(folder)) << "pictures were drawn before the refusal";
  fs::remove_all(folder);
}

// ---- bad input -----------------------------------------------------------------------------

TEST(VolcompReportBadInput, ClearErrorAndNoPage) {
  const fs::path folder = scratch("bad");
  const fs::path page = folder / "report.html";
  expect_refused((folder / "no_such_machine.toml").string(), "no_such_machine.toml", page);
  EXPECT_FALSE(fs::exists(page));
  const std::string mc300 = test::machine_path("mc300");
  expect_refused(mc300 + " --measurements " + (folder / "nowhere").string(), "nowhere: no such folder", page);
  write(folder / "plain_file", "x\n");
  expect_refused(mc300 + " --measurements " + (folder / "plain_file").string(), "plain_file: not a folder", page);
  // A laser file that cannot be read names its line; one whose error is unknown says how to name it.
  const fs::path broken = folder / "broken";
  fs::create_directories(broken);
  write(broken / "exx.csv", "target[mm],run,direction,deviation[um]\n0,1,+,1.0\n100,1,+,abc\n");
  expect_refused(mc300 + " --measurements " + broken.string(), "exx.csv:3", page);
  const fs::path unnamed = folder / "unnamed";
  fs::create_directories(unnamed);
  write(unnamed / "run1.csv", laser_runs());
  expect_refused(mc300 + " --measurements " + unnamed.string(), "laser runs of which component error?", page);
  // An older page stays as it was.
  write(page, "<html>an older report</html>\n");
  expect_refused(mc300 + " --measurements " + (folder / "nowhere").string(), "no such folder", page);
  EXPECT_EQ(test::file_text(page), "<html>an older report</html>\n");
  fs::remove_all(folder);
}

TEST(VolcompReportBadInput, UnreadableMeasurementsFolder) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root: a folder's permissions do not stop root from reading it";
  const fs::path folder = scratch("unreadable");
  const fs::path locked = folder / "locked";
  fs::create_directories(locked);
  write(locked / "exx.csv", laser_runs());
  fs::permissions(locked, fs::perms::none);
  const fs::path page = folder / "report.html";
  expect_refused(test::machine_path("mc300") + " --measurements " + locked.string(), "cannot read the folder", page);
  EXPECT_FALSE(fs::exists(page));
  fs::permissions(locked, fs::perms::owner_all);
  fs::remove_all(folder);
}

}  // namespace
}  // namespace vc
