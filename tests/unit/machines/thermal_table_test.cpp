// Tables whose grid variables include a temperature (issue 21, the source's chapter VI): a
// positioning table over an axis position and a temperature input, an offset over a temperature
// only. Every expected value here is interpolated by hand from the CSV numbers written in the
// test (not through ErrorTable), on a machine whose only errors are those tables, so the tool
// tip error is the tables' values themselves; then the shipped MC-300 example against mc300.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_support.hpp"
#include "vc/machine/correct.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/load_table.hpp"

namespace vc::machine {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("vc_thermal_table_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

// X positioning over x and the screw temperature; a spindle offset along Z over its temperature.
constexpr const char* kXScrew =
    "# test table\n"
    "x[mm],x_screw[degC],EXX[um]\n"
    "0,15,0\n0,20,0\n0,45,0\n"
    "500,15,-28.75\n500,20,0\n500,45,143.75\n";
constexpr const char* kSpindle =
    "spindle[degC],EZZ[um]\n"
    "10,4\n20,0\n30,-20\n40,-50\n";

// Three error-free linear axes in the tool chain (u = +x, +y, +z, poles at the origin): the tool
// tip error in the part frame is exactly (EXX, 0, EZZ).
std::string plain_machine() {
  std::ofstream(scratch("x_screw.csv")) << kXScrew;
  std::ofstream(scratch("spindle.csv")) << kSpindle;
  const fs::path path = scratch("plain.toml");
  std::ofstream(path) << R"([temperatures]
x_screw = { reference_degC = 20.0, min_degC = 15.0, max_degC = 45.0 }
spindle = { reference_degC = 20.0, min_degC = 10.0, max_degC = 40.0 }
[machine]
name = "plain"
[spindle]
[[tool_chain]]
axis = "X"
type = "linear"
direction = [1, 0, 0]
pole_mm = [0, 0, 0]
travel_mm = [0, 500]
[[tool_chain.tables]]
file = "x_screw.csv"
[[tool_chain]]
axis = "Y"
type = "linear"
direction = [0, 1, 0]
pole_mm = [0, 0, 0]
travel_mm = [0, 400]
[[tool_chain]]
axis = "Z"
type = "linear"
direction = [0, 0, 1]
pole_mm = [0, 0, 0]
travel_mm = [-300, 0]
[[tool_chain.tables]]
file = "spindle.csv"
)";
  return path.string();
}

// By hand from kXScrew: bilinear in (x, T) on the cells 15..20 and 20..45 degC, mm.
double exx_by_hand(double x, double t) {
  const double at_500 = t <= 20 ? -28.75 * (20 - t) / 5 : 143.75 * (t - 20) / 25;
  return 1e-3 * at_500 * x / 500;
}
// By hand from kSpindle: piecewise linear, mm.
double ezz_by_hand(double t) {
  if (t <= 20) return 1e-3 * 4 * (20 - t) / 10;
  if (t <= 30) return 1e-3 * -20 * (t - 20) / 10;
  return 1e-3 * (-20 - 30 * (t - 30) / 10);
}

TEST(TemperatureTable, LoadsATemperatureAsAGridVariable) {
  std::ofstream(scratch("t.csv")) << kXScrew;
  const tables::ErrorTable t = tables::load_table(scratch("t.csv").string());
  ASSERT_EQ(t.grid().size(), 2u);
  EXPECT_FALSE(t.grid()[0].is_temperature());
  EXPECT_TRUE(t.grid()[1].is_temperature());
  EXPECT_EQ(t.grid()[1].name(), "x_screw");
  EXPECT_EQ(t.grid()[1].unit(), "degC");
  EXPECT_EQ(t.grid()[1].nodes, (std::vector<double>{15, 20, 45}));
  EXPECT_EQ(t.grid()[1].where.line, 2);
  EXPECT_EQ(t.grid()[1].where.column, 7);
  for (const auto& [x, temp] : {std::pair{0.0, 20.0}, {125.0, 17.5}, {400.0, 32.25}, {500.0, 45.0}, {333.0, 15.0}}) {
    const double at[2] = {x, temp};
    tables::ErrorTable::Sample s;
    t.evaluate(at, s);
    EXPECT_NEAR(s.value[0], exx_by_hand(x, temp), 1e-15) << x << ", " << temp;
  }
  // A temperature grid has no slope limit: 5.75 um/K is far above 0.01 mm per unit.
  std::ofstream(scratch("steep.csv")) << "spindle[degC],EZZ[um]\n20,0\n21,500\n";
  EXPECT_NO_THROW(tables::load_table(scratch("steep.csv").string()));
}

TEST(TemperatureTable, TheToolTipMovesByTheTablesAtTheCurrentTemperatures) {
  const Model model = load_machine(plain_machine());
  Conditions at = model.reference_conditions();
  ASSERT_EQ(model.tables.size(), 2u);
  EXPECT_EQ(model.tables[0].joint[1], -1);
  EXPECT_EQ(model.tables[0].input[1], model.temperature_of("x_screw"));
  EXPECT_EQ(model.axes[0].moved_by, 1u) << "a temperature moves no joint";
  for (const double x_screw : {20.0, 15.0, 18.3, 27.0, 45.0})
    for (const double spindle : {20.0, 10.0, 26.5, 33.0, 40.0}) {
      model.set_temperature(at, "x_screw", x_screw);
      model.set_temperature(at, "spindle", spindle);
      for (const double x : {0.0, 80.0, 499.0}) {
        Joints q(3);
        q << x, 120.0, -150.0;
        const VolumetricError e = volumetric_error(model, at, q, 100.0);
        // (to the rounding of tips some 500 mm from the origin: an ulp there is 1.1e-13 mm)
        EXPECT_NEAR(e.position_mm.x(), exx_by_hand(x, x_screw), 1e-12);
        EXPECT_NEAR(e.position_mm.y(), 0.0, 1e-12);
        EXPECT_NEAR(e.position_mm.z(), ezz_by_hand(spindle), 1e-12);
        // The correction puts the real tool on the nominal point at this temperature.
        const Correction c = correct(model, at, q, 100.0);
        ASSERT_EQ(c.status, Status::Ok);
        EXPECT_LT(c.residual_mm, 1e-9);
        EXPECT_NEAR(c.joints[2] - q[2], -ezz_by_hand(spindle), 1e-12);
      }
    }
}

// The linear case on an axis without any table (Y of the plain machine): the expansion alone
// is its component error.
TEST(TemperatureTable, AThermalExpansionNeedsNoTable) {
  std::string text;
  {
    std::ifstream in(plain_machine());
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  const std::string y = "travel_mm = [0, 400]";
  text.insert(text.find(y) + y.size(),
              "\nthermal = { input = \"x_screw\", expansion_um_per_m_K = 11.5, reference_mm = 100 }");
  std::ofstream(scratch("y_thermal.toml")) << text;
  const Model model = load_machine(scratch("y_thermal.toml").string());
  ASSERT_TRUE(model.axes[1].tables.empty());
  Conditions at = model.reference_conditions();
  model.set_temperature(at, "x_screw", 30.0);
  Joints q(3);
  q << 0.0, 350.0, -100.0;
  const VolumetricError e = volumetric_error(model, at, q, 100.0);
  EXPECT_NEAR(e.position_mm.y(), 11.5e-6 * 10 * (350 - 100), 1e-12);  // 28.75 um
  EXPECT_NEAR(e.position_mm.x(), exx_by_hand(0.0, 30.0), 1e-12);
  const Correction c = correct(model, at, q, 100.0);
  EXPECT_LT(c.residual_mm, 1e-9) << "the correction sees the expansion's slope too";
}

// The shipped example: mc300.toml plus example thermal tables (tables/data/mc300/thermal).
TEST(TemperatureTable, TheMc300ExampleIsMc300AtItsReferenceAndMovesByItsTablesWhenWarm) {
  const Model warm = load_machine(test::machine_path("mc300_thermal"));
  const Model mc300 = load_machine(test::machine_path("mc300"));
  ASSERT_EQ(warm.temperatures.size(), 2u);
  const std::vector<std::array<double, 5>> poses{
      {-450, -200, -150, 0, 0}, {-20, -300, -10, -60, 135}, {-590, -5, -300, 25, 300}, {-300, -160, -200, -90, 45}};
  for (const auto& p : poses) {
    const Joints q = Eigen::Map<const Eigen::Matrix<double, 5, 1>>(p.data());
    const ToolPose a = tool_pose(warm, Machine::Real, q, 100.0), b = tool_pose(mc300, Machine::Real, q, 100.0);
    EXPECT_EQ((a.tip_mm - b.tip_mm).norm(), 0.0) << "at the reference temperatures";
    EXPECT_EQ((a.direction - b.direction).norm(), 0.0);
  }
  Conditions at = warm.reference_conditions();
  warm.set_temperature(at, "coolant", 25.0);
  warm.set_temperature(at, "spindle", 27.0);
  // At B = C = 0 the part frame is the bed's: the tables' translations show as they are, up to
  // the machine's own angles, which turn them (the Z line's squareness 5" + 5", X's and Y's
  // angular errors: up to ~1e-4 rad on the 0.054 mm of Z, 5e-6 mm).
  Joints q(5);
  q << -450, -200, -150, 0, 0;
  const Eigen::Vector3d change =
      volumetric_error(warm, at, q, 100.0).position_mm - volumetric_error(mc300, q, 100.0).position_mm;
  // By hand from the CSV files: x_coolant.csv at x = -450 (3/4 of the way to -600) and 25 degC:
  // -2.5 um x 0.75; y_coolant.csv at y = -200 (200/320) and 25 degC: -2.1 um x 0.625;
  // z_spindle.csv at 27 degC, between 19 (0) and 28 (-60.3): -60.3 x 8/9.
  EXPECT_NEAR(change.x(), -1.875e-3, 1e-5);
  EXPECT_NEAR(change.y(), -1.3125e-3, 1e-5);
  EXPECT_NEAR(change.z(), -53.6e-3, 1e-5);
  EXPECT_THROW(warm.set_temperature(at, "coolant", 26.5), std::invalid_argument);  // beyond its range
  // volcomp check: usable, and it lists the inputs and the temperature grids.
  const auto r = test::run_volcomp("check " + test::machine_path("mc300_thermal"));
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(
      r.out.find("temperature inputs (degC; surveyed at the reference): coolant 19 (18 .. 26) spindle 19 (18 .. 28)"),
      std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("grid spindle: 3 nodes 18 .. 28 degC"), std::string::npos) << r.out;
}

// predistort --temperature on a temperature table: the program is made for the warm spindle,
// its Z words higher by the spindle's growth there (the correction moves Z up by -EZZ).
TEST(TemperatureTable, PredistortMakesTheProgramForTheGivenTemperature) {
  const fs::path dir = scratch("run");
  fs::create_directories(dir);
  std::ofstream(dir / "zero.var") << "5220\t1.000000\n5221\t0.000000\n5222\t0.000000\n5223\t0.000000\n";
  std::ofstream(dir / "p.ngc") << "G21 G90 G54\nG0 X-300 Y-100 Z-100 B0 C0\nG1 Z-120 F500\nM2\n";
  const auto z_of_the_cut = [&](const std::string& extra) {
    const auto r =
        test::run_volcomp("predistort " + test::machine_path("mc300_thermal") + " " + (dir / "p.ngc").string() +
                          " -o " + (dir / "o.ngc").string() + " --var " + (dir / "zero.var").string() + " -q " + extra);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    std::ifstream out(dir / "o.ngc");
    double z = 0;
    for (std::string line; std::getline(out, line);)
      if (const auto at = line.find('Z'); at != std::string::npos && line.find('(') == std::string::npos)
        z = std::stod(line.substr(at + 1));
    return z;
  };
  const double cold = z_of_the_cut(""), warm = z_of_the_cut("--temperature spindle=27 --temperature coolant=25");
  EXPECT_NEAR(warm - cold, 0.0536, 0.0005);  // +53.6 um, to predistort's tolerance
}

}  // namespace
}  // namespace vc::machine
