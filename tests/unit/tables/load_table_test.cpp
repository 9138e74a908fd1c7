// Reading error-table CSV files (load_table.hpp): units, grid order, layout tolerance, options,
// cross-axis grids, periodic rotary grids. Each test writes real files to its own temporary
// directory. The refusals and their exact messages are in tests/golden (bad_files_test).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "vc/tables/load_table.hpp"

namespace vc::tables {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;
constexpr double kArcsec = kPi / (180.0 * 3600.0);

class LoadTable : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("vc_load_table_test_" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + "_" +
            std::to_string(counter++) + "_" + info->name());
    ASSERT_TRUE(fs::create_directories(dir_)) << dir_;
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  // Writes `text` (exactly, no newline added) to a file of the temporary directory.
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path path = dir_ / name;
    std::ofstream out(path, std::ios::binary);
    out << text;
    return path.string();
  }

  ErrorTable load(const std::string& name, const std::string& text, const TableOptions& options = {}) const {
    return load_table(write(name, text), options);
  }

  fs::path dir_;
};

double lookup(const ErrorTable& t, std::initializer_list<double> position, int column = 0) {
  ErrorTable::Sample s;
  t.evaluate(std::data(position), s);
  return s.value[column];
}

void expect_same_table(const ErrorTable& a, const ErrorTable& b) {
  ASSERT_EQ(a.grid().size(), b.grid().size());
  for (std::size_t d = 0; d < a.grid().size(); ++d) {
    EXPECT_EQ(a.grid()[d].axis, b.grid()[d].axis);
    EXPECT_EQ(a.grid()[d].nodes, b.grid()[d].nodes) << "variable " << d;
    EXPECT_EQ(a.grid()[d].periodic, b.grid()[d].periodic);
  }
  ASSERT_EQ(a.columns().size(), b.columns().size());
  ASSERT_EQ(a.node_count(), b.node_count());
  for (int n = 0; n < a.node_count(); ++n)
    for (std::size_t c = 0; c < a.columns().size(); ++c)
      EXPECT_EQ(a.value(n, static_cast<int>(c)), b.value(n, static_cast<int>(c))) << "node " << n << " column " << c;
}

// ---- units ----------------------------------------------------------------------------------

TEST_F(LoadTable, ConvertsLengthUnitsToMm) {
  const ErrorTable t = load("len.csv",
                            "x[mm],EXX[um],EYX[nm],EZX[mm]\n"
                            "0,0,0,0\n"
                            "100,2.5,-300,0.004\n");
  EXPECT_DOUBLE_EQ(t.value(1, 0), 2.5e-3);
  EXPECT_DOUBLE_EQ(t.value(1, 1), -300e-6);
  EXPECT_DOUBLE_EQ(t.value(1, 2), 0.004);
  // And the lookup works in mm too.
  EXPECT_DOUBLE_EQ(lookup(t, {50.0}, 0), 1.25e-3);
}

TEST_F(LoadTable, ConvertsAngleUnitsToRad) {
  const ErrorTable t = load("ang.csv",
                            "x[mm],EAX[arcsec],EBX[urad],ECX[mrad]\n"
                            "0,0,0,0\n"
                            "100,3.6,-5,0.002\n");
  EXPECT_DOUBLE_EQ(t.value(1, 0), 3.6 * kArcsec);
  EXPECT_DOUBLE_EQ(t.value(1, 1), -5e-6);
  EXPECT_DOUBLE_EQ(t.value(1, 2), 2e-6);
  const ErrorTable u = load("ang2.csv",
                            "x[mm],EAX[deg],EBX[rad]\n"
                            "0,0,0\n"
                            "100,0.001,-1e-5\n");
  EXPECT_DOUBLE_EQ(u.value(1, 0), 0.001 * kPi / 180.0);
  EXPECT_DOUBLE_EQ(u.value(1, 1), -1e-5);
}

TEST_F(LoadTable, KeepsGridPositionsInTheAxisUnit) {
  // Rotary positions stay in deg (LinuxCNC's unit), linear ones in mm; only values convert.
  const ErrorTable t = load("b.csv",
                            "b[deg],EXB[um],ECB[arcsec]\n"
                            "-120,0,0\n"
                            "-60,1,2\n"
                            "30,0,1\n");
  ASSERT_EQ(t.grid().size(), 1u);
  EXPECT_EQ(t.grid()[0].axis, 'B');
  EXPECT_TRUE(t.grid()[0].rotary);
  EXPECT_FALSE(t.grid()[0].periodic);
  EXPECT_EQ(t.grid()[0].nodes, (std::vector<double>{-120, -60, 30}));
  EXPECT_DOUBLE_EQ(lookup(t, {-90.0}, 0), 0.5e-3);
  EXPECT_DOUBLE_EQ(lookup(t, {-90.0}, 1), 1.0 * kArcsec);
  const ErrorTable x = load("x.csv", "x[mm],EXX[um]\n0,0\n10,1\n");
  EXPECT_FALSE(x.grid()[0].rotary);
}

TEST_F(LoadTable, ReadsTheHeader) {
  const ErrorTable t = load("h.csv",
                            "# a comment line first\n"
                            "z[mm], EXZ[um],EAZ[arcsec]\n"
                            "0,0,0\n"
                            "10,1,1\n");
  EXPECT_EQ(t.path(), (dir_ / "h.csv").string());
  ASSERT_EQ(t.columns().size(), 2u);
  EXPECT_EQ(t.columns()[0].symbol.component, 0);  // X
  EXPECT_EQ(t.columns()[0].symbol.axis, 'Z');
  EXPECT_FALSE(t.columns()[0].symbol.location);
  EXPECT_EQ(t.columns()[1].symbol.component, 3);  // A
  // Where each header cell is, for later messages (machine loader): line 2, columns 1, 8, 16.
  EXPECT_EQ(t.grid()[0].where.line, 2);
  EXPECT_EQ(t.grid()[0].where.column, 1);
  EXPECT_EQ(t.columns()[0].where.line, 2);
  EXPECT_EQ(t.columns()[0].where.column, 8);
  EXPECT_EQ(t.columns()[1].where.column, 16);
  EXPECT_EQ(t.interpolation(), Interpolation::Linear);
}

// ---- grid order -----------------------------------------------------------------------------

TEST_F(LoadTable, IncreasingAndDecreasingGridsGiveTheSameTable) {
  const ErrorTable up = load("up.csv",
                             "x[mm],EXX[um],EYX[um]\n"
                             "-600,3,-1\n"
                             "-550,2,0\n"
                             "-400,4,1\n"
                             "-390,4.5,1.5\n"
                             "0,0,2\n");
  const ErrorTable down = load("down.csv",
                               "x[mm],EXX[um],EYX[um]\n"
                               "0,0,2\n"
                               "-390,4.5,1.5\n"
                               "-400,4,1\n"
                               "-550,2,0\n"
                               "-600,3,-1\n");
  expect_same_table(up, down);
  EXPECT_EQ(down.grid()[0].nodes, (std::vector<double>{-600, -550, -400, -390, 0}));
  for (double x = -650; x <= 50; x += 17.5)
    for (int c : {0, 1}) EXPECT_EQ(lookup(up, {x}, c), lookup(down, {x}, c)) << x;
}

TEST_F(LoadTable, DecreasingVariablesOfATwoDimensionalGridAreReordered) {
  // The same Z-by-Y table four ways: each variable increasing or decreasing.
  auto f = [](double z, double y) { return 1.0 + 0.01 * z - 0.002 * y + 0.0001 * z * y; };  // um
  auto text = [&](bool z_up, bool y_up) {
    std::string s = "z[mm],y[mm],EZZ[um]\n";
    const std::vector<double> zs = z_up ? std::vector<double>{-300, -100, 0} : std::vector<double>{0, -100, -300};
    const std::vector<double> ys = y_up ? std::vector<double>{0, 50, 300} : std::vector<double>{300, 50, 0};
    for (double z : zs)
      for (double y : ys) s += std::to_string(z) + "," + std::to_string(y) + "," + std::to_string(f(z, y)) + "\n";
    return s;
  };
  const ErrorTable ref = load("upup.csv", text(true, true));
  EXPECT_EQ(ref.grid()[0].nodes, (std::vector<double>{-300, -100, 0}));
  EXPECT_EQ(ref.grid()[1].nodes, (std::vector<double>{0, 50, 300}));
  expect_same_table(ref, load("updown.csv", text(true, false)));
  expect_same_table(ref, load("downup.csv", text(false, true)));
  expect_same_table(ref, load("downdown.csv", text(false, false)));
  // Node (z = -100, y = 300) is node 1 * 3 + 2 = 5, first variable slowest.
  EXPECT_DOUBLE_EQ(ref.value(5, 0), f(-100, 300) * 1e-3);
}

// ---- layout ---------------------------------------------------------------------------------

TEST_F(LoadTable, IgnoresCommentsBlankLinesAndSpaces) {
  const ErrorTable clean = load("clean.csv",
                                "x[mm],EXX[um],EAX[arcsec]\n"
                                "0,0,0\n"
                                "25,1.5,-2\n"
                                "50,0.5,1\n");
  const ErrorTable messy = load("messy.csv",
                                "# X axis, measured 2026-11-23\n"
                                "\n"
                                "   # an indented comment\n"
                                "  x[mm] ,\tEXX[um] , EAX[arcsec]  \r\n"
                                "\r\n"
                                "0, 0 ,0\n"
                                "   \t  \n"
                                "# between rows\n"
                                "  25 ,+1.5,  -2\r\n"
                                "50,\t0.5\t,+1");  // no newline at the end
  expect_same_table(clean, messy);
  EXPECT_EQ(messy.columns()[0].where.line, 4);
}

// Excel's "CSV UTF-8" export starts the file with a byte-order mark.
TEST_F(LoadTable, SkipsAUtf8ByteOrderMark) {
  const std::string rows = "x[mm],EXX[um]\n0,0\n25,1.5\n";
  expect_same_table(load("plain.csv", rows), load("bom.csv", "\xEF\xBB\xBF" + rows));
}

TEST_F(LoadTable, ParsesSignsAndExponents) {
  const ErrorTable t = load("signs.csv",
                            "x[mm],EXX[um],EYX[um],EZX[um]\n"
                            "-10,+1.5,-1.5,1.5e+1\n"
                            "+10,.5,-.25,2E-1\n");
  EXPECT_EQ(t.grid()[0].nodes, (std::vector<double>{-10, 10}));
  EXPECT_DOUBLE_EQ(t.value(0, 0), 1.5e-3);
  EXPECT_DOUBLE_EQ(t.value(0, 1), -1.5e-3);
  EXPECT_DOUBLE_EQ(t.value(0, 2), 15e-3);
  EXPECT_DOUBLE_EQ(t.value(1, 0), 0.5e-3);
  EXPECT_DOUBLE_EQ(t.value(1, 1), -0.25e-3);
  EXPECT_DOUBLE_EQ(t.value(1, 2), 0.2e-3);
}

// ---- options --------------------------------------------------------------------------------

TEST_F(LoadTable, ScaleMultipliesOneColumn) {
  const std::string text =
      "c[deg],EXC[um],ECC[arcsec]\n"
      "0,0,0\n"
      "90,2,1\n"
      "180,1,-1\n"
      "270,0,0.5\n"
      "360,0,0\n";
  TableOptions options;
  options.scale["ECC"] = 10.0;
  const ErrorTable plain = load("c.csv", text);
  const ErrorTable scaled = load("c.csv", text, options);
  for (int n = 0; n < plain.node_count(); ++n) {
    EXPECT_EQ(scaled.value(n, 0), plain.value(n, 0)) << n;  // EXC untouched
    EXPECT_DOUBLE_EQ(scaled.value(n, 1), 10.0 * plain.value(n, 1)) << n;
  }
  EXPECT_DOUBLE_EQ(scaled.value(1, 1), 10.0 * kArcsec);
  options.scale = {{"EXC", -1.0}};
  const ErrorTable negated = load("c.csv", text, options);
  EXPECT_DOUBLE_EQ(negated.value(1, 0), -2e-3);
  EXPECT_EQ(negated.value(1, 1), plain.value(1, 1));
}

TEST_F(LoadTable, CubicInterpolationIsPassedToTheTable) {
  TableOptions options;
  options.interpolation = Interpolation::Cubic;
  const ErrorTable t = load("cubic.csv",
                            "x[mm],EXX[um]\n"
                            "0,0\n"
                            "10,1\n"
                            "20,0\n"
                            "30,-1\n",
                            options);
  EXPECT_EQ(t.interpolation(), Interpolation::Cubic);
  EXPECT_NEAR(lookup(t, {10.0}), 1e-3, 1e-15);
  EXPECT_GT(lookup(t, {5.0}), 0.5e-3 + 1e-6);  // above the chord: a curve, not a line
}

TEST_F(LoadTable, SlopeLimitsAreOptions) {
  const std::string steep = "x[mm],EXX[um]\n0,0\n10,150\n";  // 0.015 mm/mm
  EXPECT_THROW(load("steep.csv", steep), LoadError);
  TableOptions options;
  options.limits.translation = 0.02;
  EXPECT_NO_THROW(load("steep.csv", steep, options));
  // At the limit is allowed: 0.01 mm/mm and 1e-4 rad/mm exactly.
  EXPECT_NO_THROW(load("edge.csv", "x[mm],EXX[mm],EAX[rad]\n0,0,0\n10,0.1,0.001\n"));
}

// ---- cross-axis grids -----------------------------------------------------------------------

TEST_F(LoadTable, TwoDimensionalTableInRowOrderLoadsAndEvaluates) {
  // Z positioning that depends on Y; z slowest. Bilinear data, so the lookup is exact.
  auto f = [](double z, double y) { return 2.0 - 0.004 * z + 0.003 * y + 2e-5 * z * y; };  // um
  std::string text = "# EZZ over z and y\nz[mm],y[mm],EZZ[um]\n";
  const std::vector<double> zs{0, -100, -250, -300}, ys{0, 150, 300};
  for (double z : zs)
    for (double y : ys) text += std::to_string(z) + "," + std::to_string(y) + "," + std::to_string(f(z, y)) + "\n";
  const ErrorTable t = load("z_by_y.csv", text);
  ASSERT_EQ(t.grid().size(), 2u);
  EXPECT_EQ(t.grid()[0].axis, 'Z');
  EXPECT_EQ(t.grid()[1].axis, 'Y');
  EXPECT_EQ(t.grid()[0].nodes, (std::vector<double>{-300, -250, -100, 0}));
  EXPECT_EQ(t.grid()[1].nodes, (std::vector<double>{0, 150, 300}));
  EXPECT_EQ(t.node_count(), 12);
  for (double z = -300; z <= 0; z += 37)
    for (double y = 0; y <= 300; y += 41) {
      ErrorTable::Sample s;
      const double p[2] = {z, y};
      t.evaluate(p, s);
      EXPECT_NEAR(s.value[0], f(z, y) * 1e-3, 1e-12) << z << ", " << y;
      EXPECT_NEAR(s.slope[0][0], (-0.004 + 2e-5 * y) * 1e-3, 1e-12);
      EXPECT_NEAR(s.slope[0][1], (0.003 + 2e-5 * z) * 1e-3, 1e-12);
    }
}

TEST_F(LoadTable, ThreeDimensionalTableLoads) {
  std::string text = "x[mm],y[mm],z[mm],EXX[um],EYX[um]\n";
  for (int x : {0, 100})
    for (int y : {0, 50, 100})
      for (int z : {-10, 0})
        text += std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(z) + "," +
                std::to_string(0.01 * x + 0.02 * y + 0.1 * z) + ",1\n";
  const ErrorTable t = load("xyz.csv", text);
  ASSERT_EQ(t.grid().size(), 3u);
  EXPECT_EQ(t.grid()[2].nodes, (std::vector<double>{-10, 0}));
  EXPECT_NEAR(lookup(t, {50.0, 25.0, -5.0}, 0), (0.5 + 0.5 - 0.5) * 1e-3, 1e-15);
  EXPECT_NEAR(lookup(t, {50.0, 25.0, -5.0}, 1), 1e-3, 1e-15);
}

// ---- periodic rotary grids ------------------------------------------------------------------

TEST_F(LoadTable, A360DegRotaryGridIsPeriodic) {
  const ErrorTable c = load("c.csv",
                            "c[deg],ECC[arcsec]\n"
                            "0,0\n"
                            "90,1\n"
                            "180,2\n"
                            "270,1\n"
                            "360,0\n");
  EXPECT_TRUE(c.grid()[0].periodic);
  EXPECT_NEAR(lookup(c, {-45.0}), 0.5 * kArcsec, 1e-18);  // wraps to 315
  EXPECT_NEAR(lookup(c, {405.0}), 0.5 * kArcsec, 1e-18);  // wraps to 45
  // Also from -180 to 180, and listed downwards.
  EXPECT_TRUE(load("c2.csv", "c[deg],ECC[arcsec]\n-180,0\n0,1\n180,0\n").grid()[0].periodic);
  const ErrorTable down = load("c3.csv", "c[deg],ECC[arcsec]\n360,0\n270,1\n180,2\n90,1\n0,0\n");
  EXPECT_TRUE(down.grid()[0].periodic);
  expect_same_table(c, down);
}

TEST_F(LoadTable, OtherGridsAreNotPeriodic) {
  // Less than 360 deg, more than 360 deg, and 360 mm of a linear axis: end values held.
  EXPECT_FALSE(load("a.csv", "c[deg],ECC[arcsec]\n0,0\n350,1\n").grid()[0].periodic);
  EXPECT_FALSE(load("b.csv", "c[deg],ECC[arcsec]\n-10,0\n360,1\n").grid()[0].periodic);
  const ErrorTable x = load("x.csv", "x[mm],EXX[um]\n0,0\n360,1\n");
  EXPECT_FALSE(x.grid()[0].periodic);
  EXPECT_DOUBLE_EQ(lookup(x, {370.0}), 1e-3);
}

TEST_F(LoadTable, PeriodicVariableOfACrossAxisTable) {
  // EXC over C (periodic) and X; the 360 row of each X must equal the 0 row.
  const ErrorTable t = load("c_by_x.csv",
                            "c[deg],x[mm],EXC[um]\n"
                            "0,0,0\n0,100,1\n"
                            "180,0,2\n180,100,3\n"
                            "360,0,0\n360,100,1\n");
  EXPECT_TRUE(t.grid()[0].periodic);
  EXPECT_FALSE(t.grid()[1].periodic);
  EXPECT_NEAR(lookup(t, {-90.0, 50.0}), lookup(t, {270.0, 50.0}), 1e-18);
  EXPECT_NEAR(lookup(t, {270.0, 50.0}), (0.5 * (2 + 0) + 0.5 * (3 + 1)) / 2 * 1e-3, 1e-15);
}

// ---- refusals (details and messages: tests/golden) -----------------------------------------

TEST_F(LoadTable, ErrorsNameLineAndColumn) {
  try {
    load("nan.csv", "x[mm],EXX[um]\n# comment\n0,0\n10, nan\n");
    FAIL() << "accepted a NaN";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where().path, (dir_ / "nan.csv").string());
    EXPECT_EQ(e.where().line, 4);
    EXPECT_EQ(e.where().column, 5);
    EXPECT_EQ(e.message(), "'nan' is not a finite number");
  }
}

TEST_F(LoadTable, AMissingFileIsALoadError) {
  try {
    load_table((dir_ / "absent.csv").string());
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where().path, (dir_ / "absent.csv").string());
    EXPECT_EQ(e.where().line, 0);
  }
}

}  // namespace
}  // namespace vc::tables
