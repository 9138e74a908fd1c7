// The pictures (issue 37): `identify laser --plot`, `identify circle --plot`, `plot MACHINE`,
// `balance --plot`, run as a user runs them. Golden checks of what is drawn: each plot's data
// CSV (written beside the image) holds the numbers the command prints and the input's values
// (the laser's runs and means, the ballbar's deviations at the stated scale, the machine file's
// table values at its nodes, its scale applied); every image is a real PNG (signature, the
// size asked for) or SVG; and without gnuplot on PATH the command fails with a clear message
// and leaves no file behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "test_support.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;

// A fresh, empty folder for one test.
fs::path folder(const std::string& name) {
  const fs::path f = fs::temp_directory_path() / ("vc_plot_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(f);
  fs::create_directories(f);
  return f;
}

// A PNG file: its signature, and the width and height of its IHDR chunk (big-endian).
void expect_png(const fs::path& path, int width, int height) {
  ASSERT_TRUE(fs::exists(path)) << path;
  const std::string png = test::file_text(path);
  ASSERT_GT(png.size(), 20000u) << path << ": a plot, not an empty frame";
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << path;
  EXPECT_EQ(png.substr(12, 4), "IHDR") << path;
  const auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned char>(png[at]) << 24) | (static_cast<unsigned char>(png[at + 1]) << 16) |
           (static_cast<unsigned char>(png[at + 2]) << 8) | static_cast<unsigned char>(png[at + 3]);
  };
  EXPECT_EQ(be32(16), width) << path;
  EXPECT_EQ(be32(20), height) << path;
}

// The data lines of a CSV (comments and blank lines skipped) in blocks (a header and its rows;
// blocks are separated by blank lines, as gnuplot's index reads them), by column name.
struct Block {
  std::vector<std::string> names;
  std::vector<std::vector<std::string>> rows;
  double at(std::size_t row, const std::string& name) const {
    const auto c = std::find(names.begin(), names.end(), name);
    if (c == names.end()) throw std::out_of_range("no column " + name);
    return std::stod(rows[row][static_cast<std::size_t>(c - names.begin())]);
  }
};
std::vector<Block> read_blocks(const fs::path& path) {
  std::ifstream in(path);
  std::vector<Block> blocks;
  bool header = true;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) {
      header = true;
      continue;
    }
    if (line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    if (header) {
      blocks.push_back({cells, {}});
      header = false;
    } else {
      blocks.back().rows.push_back(cells);
    }
  }
  return blocks;
}

// The text after `label` on its line of `text` ("" if absent).
std::string after(const std::string& text, const std::string& label) {
  const std::size_t at = text.find(label);
  if (at == std::string::npos) return "";
  const std::size_t begin = at + label.size();
  return text.substr(begin, text.find('\n', begin) - begin);
}

// 7 targets, 3 runs each way: up reads +0.6 um, down -0.6 um about 2 sin(x / 100) um, the
// runs off by +0.2, -0.1, -0.1 um and up's run 2 by 0.3 um more at x = -300.
std::string laser_runs(std::map<std::pair<double, std::string>, double>& readings) {
  std::string runs =
      "# instrument: XL-80\n# temperature_degC: 20.3\ntarget[mm],1+[um],1-[um],2+[um],2-[um],3+[um],3-[um]\n";
  for (int k = 0; k <= 6; ++k) {
    const double x = -100.0 * k + 0.0, v = 2 * std::sin(x / 100);  // + 0.0: no -0
    runs += std::to_string(x);
    for (int run = 1; run <= 3; ++run)
      for (const char* d : {"+", "-"}) {
        const double r =
            v + (d[0] == '+' ? 0.6 : -0.6) + (run == 1 ? 0.2 : -0.1) + (run == 2 && k == 3 && d[0] == '+' ? 0.3 : 0);
        readings[{x, std::to_string(run) + d}] = std::round(r * 1e4) / 1e4;
        std::ostringstream cell;
        cell << "," << std::round(r * 1e4) / 1e4;
        runs += cell.str();
      }
    runs += "\n";
  }
  return runs;
}

TEST(VolcompPlot, LaserGraphDrawsThePrintedEvaluation) {
  const fs::path dir = folder("laser");
  std::map<std::pair<double, std::string>, double> readings;
  std::ofstream(dir / "runs.csv") << laser_runs(readings);
  const auto r = test::run_volcomp("identify laser " + (dir / "runs.csv").string() + " --error EXX -o " +
                                   (dir / "exx_table.csv").string() + " --plot " + (dir / "exx.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  expect_png(dir / "exx.png", 1400, 820);
  const std::string data = test::file_text(dir / "exx.csv");
  // The figures on the graph are the printed ones, text for text.
  for (const auto& [printed, symbol] :
       std::vector<std::pair<std::string, std::string>>{{"reversal value B", "B"},
                                                        {"repeatability R", "R"},
                                                        {"systematic deviation E", "E"},
                                                        {"mean bidirectional range M", "M"},
                                                        {"accuracy A", "A"}}) {
    const std::string text = test::trimmed(after(r.out, printed));
    ASSERT_FALSE(text.empty()) << printed << "\n" << r.out;
    EXPECT_EQ(after(data, "# " + symbol + " = "), text) << symbol;
  }
  const std::vector<Block> blocks = read_blocks(dir / "exx.csv");
  ASSERT_EQ(blocks.size(), 1u);
  const Block& b = blocks[0];
  ASSERT_EQ(b.rows.size(), 7u);
  double lowest = 1e9, highest = -1e9, band_top = -1e9, band_bottom = 1e9;
  for (std::size_t i = 0; i < b.rows.size(); ++i) {
    const double x = b.at(i, "target[mm]");
    EXPECT_EQ(x, -600 + 100.0 * static_cast<double>(i));  // ascending
    // Each run drawn is the file's run.
    for (int run = 1; run <= 3; ++run) {
      EXPECT_NEAR(b.at(i, "run" + std::to_string(run) + "_up[um]"), readings.at({x, std::to_string(run) + "+"}), 1e-9);
      EXPECT_NEAR(b.at(i, "run" + std::to_string(run) + "_down[um]"), readings.at({x, std::to_string(run) + "-"}),
                  1e-9);
    }
    // The means drawn are the printed per-target table's (3 decimals).
    std::ostringstream target;
    target << "  " << x << "  ";
    std::stringstream printed(after(r.out, target.str()));
    double mean_up, mean_down, mean;
    printed >> mean_up >> mean_down >> mean;
    ASSERT_FALSE(printed.fail()) << x << "\n" << r.out;
    EXPECT_NEAR(b.at(i, "mean_up[um]"), mean_up, 5e-4);
    EXPECT_NEAR(b.at(i, "mean_down[um]"), mean_down, 5e-4);
    EXPECT_NEAR(b.at(i, "mean_bidirectional[um]"), mean, 5e-4);
    lowest = std::min(lowest, b.at(i, "mean_bidirectional[um]"));
    highest = std::max(highest, b.at(i, "mean_bidirectional[um]"));
    band_top = std::max({band_top, b.at(i, "mean_up+2s[um]"), b.at(i, "mean_down+2s[um]")});
    band_bottom = std::min({band_bottom, b.at(i, "mean_up-2s[um]"), b.at(i, "mean_down-2s[um]")});
  }
  // ISO 230-2's M and A are read off exactly these lines: the drawn bands give the printed A.
  EXPECT_NEAR(highest - lowest, std::stod(after(r.out, "mean bidirectional range M")), 0.006);
  EXPECT_NEAR(band_top - band_bottom, std::stod(after(r.out, "accuracy A")), 0.006);
  EXPECT_TRUE(fs::exists(dir / "exx_table.csv"));  // -o is still the error table, not the plot's data

  // SVG by extension; another extension is refused before anything is written.
  auto s = test::run_volcomp("identify laser " + (dir / "runs.csv").string() + " --error EXX --plot " +
                             (dir / "exx.svg").string());
  ASSERT_EQ(s.exit_code, 0) << s.out;
  EXPECT_NE(test::file_text(dir / "exx.svg").find("<svg"), std::string::npos);
  s = test::run_volcomp("identify laser " + (dir / "runs.csv").string() + " --error EXX --plot " +
                        (dir / "exx.pdf").string());
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.out.find("the picture is a .png or an .svg file"), std::string::npos) << s.out;
  EXPECT_FALSE(fs::exists(dir / "exx.pdf"));
  // The plot's data would overwrite the table: refused.
  s = test::run_volcomp("identify laser " + (dir / "runs.csv").string() + " --error EXX -o " +
                        (dir / "same.csv").string() + " --plot " + (dir / "same.png").string());
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.out.find("give the plot another name"), std::string::npos) << s.out;
  EXPECT_FALSE(fs::exists(dir / "same.csv"));
  EXPECT_FALSE(fs::exists(dir / "same.png"));
}

// A ballbar run by the first-order formula (centre off, squareness, scales) with a 2 um
// reversal spike where X reverses (90 deg, ccw) and cw 0.5 um longer, one reading a degree.
TEST(VolcompPlot, BallbarPolarPlotDrawsTheRunAtItsStatedScale) {
  const fs::path dir = folder("circle");
  const double R = 150, cx = 0.003, cy = -0.002, ex = 5e-6, ey = -3e-6, theta = 10 * M_PI / 648000;
  std::map<std::pair<std::string, double>, double> deviation_um;
  std::ostringstream run;
  run << "# plane: XY\n# radius_mm: 150\n# feed_mm_min: 1000\nangle[deg],ccw[um],cw[um]\n";
  for (int deg = 0; deg < 360; ++deg) {
    const double phi = deg * M_PI / 180, c = std::cos(phi), s = std::sin(phi);
    const double d = -cx * c - cy * s + R * (ex * c * c + ey * s * s) + R * theta * s * c;
    const double ccw = std::round((d + 0.002 * std::exp(-std::pow(deg - 90.0, 2))) * 1e7) / 1e4;
    const double cw = std::round((d + 0.0005) * 1e7) / 1e4;
    deviation_um[{"ccw", deg}] = ccw;
    deviation_um[{"cw", deg}] = cw;
    run << deg << ',' << ccw << ',' << cw << '\n';
  }
  std::ofstream(dir / "run.csv") << run.str();
  const auto r =
      test::run_volcomp("identify circle " + (dir / "run.csv").string() + " --plot " + (dir / "ballbar.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  expect_png(dir / "ballbar.png", 1400, 900);
  const std::string data = test::file_text(dir / "ballbar.csv");
  // The printed figures are written on the plot as printed.
  for (const std::string label : {"bidirectional circular deviation G(b) ", "circular hysteresis H "}) {
    const std::string printed =
        label + test::trimmed(after(r.out, label)).substr(0, after(r.out, label).find(" um") + 3);
    EXPECT_NE(data.find("# " + printed), std::string::npos) << printed << "\n" << data.substr(0, 2000);
  }
  for (const std::string label : {"squareness ", "centre offset X ", "theta = "}) {
    const std::string value = after(r.out, label);
    ASSERT_FALSE(value.empty()) << label;
    EXPECT_NE(data.find(label + value.substr(0, value.find_first_of(";,"))), std::string::npos) << label;
  }
  // The scale, stated, is what the radii are drawn at: 5 divisions + deviation / scale.
  const double scale = std::stod(after(data, "# scale "));
  const std::vector<Block> blocks = read_blocks(dir / "ballbar.csv");
  ASSERT_EQ(blocks.size(), 2u);
  double largest = 0;
  for (const Block& b : blocks) {
    ASSERT_EQ(b.rows.size(), 361u);  // a reading a degree and the first repeated at 360 to close the curve
    for (std::size_t i = 0; i < b.rows.size(); ++i) {
      const std::string direction = b.rows[i][0];
      const double angle = b.at(i, "angle[deg]"), dev = b.at(i, "deviation[um]");
      EXPECT_NEAR(dev, deviation_um.at({direction, std::fmod(std::round(angle), 360.0)}), 1e-9) << direction << angle;
      EXPECT_NEAR(b.at(i, "plotted_radius[div]"), 5 + dev / scale, 1e-9);
      largest = std::max(largest, std::abs(dev));
    }
  }
  EXPECT_EQ(blocks[0].rows[0][0], "ccw");
  EXPECT_EQ(blocks[1].rows[0][0], "cw");
  // The scale fits the largest deviation in 3.5 divisions and is 1, 2 or 5 x 10^k um.
  EXPECT_LE(largest / scale, 3.5);
  EXPECT_GT(largest / scale, 3.5 / 2.5);

  // run.png's data would be run.csv, the run itself: refused, the run untouched.
  const auto same =
      test::run_volcomp("identify circle " + (dir / "run.csv").string() + " --plot " + (dir / "run.png").string());
  EXPECT_EQ(same.exit_code, 2);
  EXPECT_NE(same.out.find("a file of this command: give the plot another name"), std::string::npos) << same.out;
  EXPECT_EQ(test::file_text(dir / "run.csv"), run.str());
  EXPECT_FALSE(fs::exists(dir / "run.png"));
}

// Numbers of a table file's data rows by column, comments skipped.
std::map<std::string, std::vector<double>> table_columns(const std::string& path) {
  const std::vector<Block> blocks = read_blocks(path);
  std::map<std::string, std::vector<double>> columns;
  for (std::size_t c = 0; c < blocks.at(0).names.size(); ++c)
    for (std::size_t i = 0; i < blocks[0].rows.size(); ++i)
      columns[blocks[0].names[c]].push_back(blocks[0].at(i, blocks[0].names[c]));
  return columns;
}

TEST(VolcompPlot, MachinePlotDrawsTheFilesTablesAtTheirNodes) {
  const fs::path dir = folder("machine");
  const auto r = test::run_volcomp("plot " + test::machine_path("mc300") + " -o " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  for (const char* axis : {"x", "y", "z", "b", "c"}) expect_png(dir / (std::string(axis) + "_axis.png"), 1400, 1000);

  // Each drawn row is the file's row at the same position (the files list their nodes descending,
  // the plots draw them ascending).
  const auto file_row = [](const std::map<std::string, std::vector<double>>& file, const std::string& position,
                           double at) {
    const std::vector<double>& p = file.at(position);
    const auto row = std::find(p.begin(), p.end(), at);
    if (row == p.end()) throw std::out_of_range(position + " has no node at " + std::to_string(at));
    return static_cast<std::size_t>(row - p.begin());
  };
  // X: x.csv in mm and arcsec, no scale: drawn in um and arcsec, node for node.
  const auto x_file = table_columns(test::source_path("tables/data/mc300/x.csv"));
  const std::vector<Block> x = read_blocks(dir / "x_axis.csv");
  ASSERT_EQ(x.size(), 1u);
  ASSERT_EQ(x[0].rows.size(), x_file.at("x[mm]").size());
  for (std::size_t i = 0; i < x[0].rows.size(); ++i) {
    if (i > 0) {
      EXPECT_LT(x[0].at(i - 1, "x[mm]"), x[0].at(i, "x[mm]"));
    }
    const std::size_t f = file_row(x_file, "x[mm]", x[0].at(i, "x[mm]"));
    for (const char* e : {"EXX", "EYX", "EZX"})
      EXPECT_NEAR(x[0].at(i, std::string(e) + "[um]"), x_file.at(std::string(e) + "[mm]")[f] * 1e3, 1e-9) << e << i;
    for (const char* e : {"EAX", "EBX", "ECX"})
      EXPECT_NEAR(x[0].at(i, std::string(e) + "[arcsec]"), x_file.at(std::string(e) + "[arcsec]")[f], 1e-9) << e << i;
  }
  // C: the machine file's scale ECC = 10 is drawn (the model's values), B's ECB = -1 likewise.
  const auto c_file = table_columns(test::source_path("tables/data/mc300/c.csv"));
  const std::vector<Block> c = read_blocks(dir / "c_axis.csv");
  ASSERT_EQ(c[0].rows.size(), c_file.at("c[deg]").size());
  for (std::size_t i = 0; i < c[0].rows.size(); ++i) {
    const std::size_t f = file_row(c_file, "c[deg]", c[0].at(i, "c[deg]"));
    EXPECT_NEAR(c[0].at(i, "ECC[arcsec]"), 10 * c_file.at("ECC[arcsec]")[f], 1e-9) << i;
    EXPECT_NEAR(c[0].at(i, "EXC[um]"), 1e3 * c_file.at("EXC[mm]")[f], 1e-9) << i;
  }
  const auto b_file = table_columns(test::source_path("tables/data/mc300/b.csv"));
  const std::vector<Block> b = read_blocks(dir / "b_axis.csv");
  ASSERT_EQ(b[0].rows.size(), b_file.at("b[deg]").size());
  for (std::size_t i = 0; i < b[0].rows.size(); ++i) {
    const std::size_t f = file_row(b_file, "b[deg]", b[0].at(i, "b[deg]"));
    EXPECT_NEAR(b[0].at(i, "ECB[arcsec]"), -b_file.at("ECB[arcsec]")[f], 1e-9) << i;
    EXPECT_NEAR(b[0].at(i, "EBB[arcsec]"), b_file.at("EBB[arcsec]")[f], 1e-9) << i;
  }

  // The location errors with units, as the machine file gives them (mc300.toml's arcsec keys).
  const std::string listing = test::file_text(dir / "location_errors.csv");
  for (const char* row : {"\nY,EC0Y,", "\nZ,EA0Z,", "\nZ,EB0Z,", "\nB,EA0B,", "\nB,EC0B,", "\nC,EA0C,", "\nC,EC0C,"})
    EXPECT_NE(listing.find(row), std::string::npos) << row;
  EXPECT_NE(listing.find("\nY,EC0Y,squareness: the Y line turned about z,-5,arcsec\n"), std::string::npos) << listing;
  EXPECT_NE(listing.find("\nC,EX0C,position of the C line along x,0,um\n"), std::string::npos) << listing;
  EXPECT_NE(r.out.find("EA0Z = 5.000 arcsec"), std::string::npos) << r.out;

  // SVG on request; an unknown format refused.
  const fs::path svg = folder("machine_svg");
  auto s = test::run_volcomp("plot " + test::machine_path("mill3") + " -o " + svg.string() + " --format svg");
  ASSERT_EQ(s.exit_code, 0) << s.out;
  EXPECT_NE(test::file_text(svg / "x_axis.svg").find("</svg>"), std::string::npos);
  s = test::run_volcomp("plot " + test::machine_path("mill3") + " -o " + svg.string() + " --format pdf");
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.out.find("--format must be png or svg"), std::string::npos) << s.out;
}

// Without gnuplot: a clear error, exit 2, and no file at all (no image, no data, no temporary,
// and not the other outputs the plot precedes: the laser's table, the balance CSV).
TEST(VolcompPlot, WithoutGnuplotNothingIsWritten) {
  const fs::path dir = folder("no_gnuplot");
  std::map<std::pair<double, std::string>, double> readings;
  const fs::path runs = folder("no_gnuplot_input") / "runs.csv";
  std::ofstream(runs) << laser_runs(readings);
  const std::string no_gnuplot = "PATH=/nonexistent " + std::string(VC_VOLCOMP) + " ";
  auto r = test::run_command(no_gnuplot + "identify laser " + runs.string() + " --error EXX -o " +
                             (dir / "t.csv").string() + " --plot " + (dir / "exx.png").string() + " 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("gnuplot was not found (is it installed and on PATH?): the plot " + (dir / "exx.png").string() +
                       " was not written"),
            std::string::npos)
      << r.out;
  r = test::run_command(no_gnuplot + "balance " + test::machine_path("mill3") + " --levels 2 -o " +
                        (dir / "balance_table.csv").string() + " --plot " + (dir / "balance.png").string() + " 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("gnuplot was not found"), std::string::npos) << r.out;
  r = test::run_command(no_gnuplot + "plot " + test::machine_path("mc300") + " -o " + dir.string() + " 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("gnuplot was not found"), std::string::npos) << r.out;
  for (const auto& entry : fs::directory_iterator(dir)) ADD_FAILURE() << "left behind: " << entry.path();
}

TEST(VolcompPlot, BalanceBarChartGoesThroughTheSameHelper) {
  const fs::path dir = folder("balance");
  const auto r = test::run_volcomp("balance " + test::machine_path("mc300") + " --levels 3 --plot " +
                                   (dir / "balance.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  expect_png(dir / "balance.png", 1400, 700);
  const std::vector<Block> data = read_blocks(dir / "balance.csv");
  ASSERT_EQ(data.size(), 1u);
  EXPECT_EQ(data[0].rows.size(), 37u);  // the bars: every deviation the printout lists
  // The first bar is the printout's first row.
  const std::string first = data[0].rows[0][0];
  EXPECT_NE(r.out.find("  " + first + " "), std::string::npos) << first;
  EXPECT_NEAR(data[0].at(0, "M[um]"), std::stod(after(r.out, "  " + first + " ")), 6e-4);
}

}  // namespace
}  // namespace vc
