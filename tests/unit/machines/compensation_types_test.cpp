// The ISO/TR 16907 Annex A types of a machine file (vc/machine/compensation_types.hpp), against
// listings written here from reading each file (not from the code under test): every shipped
// machine, a machine without errors as `volcomp init` writes it (none), and files with one kind
// of error, made by `volcomp perturb` from it or written here (exactly that type).
#include "vc/machine/compensation_types.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "test_support.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
using machine::CompensationTypes;

// code -> what provides it (basic types) or the parts present (composites); "!" before a
// composite's code: it is partial.
using Listing = std::vector<std::pair<std::string, std::vector<std::string>>>;

Listing listing_of(const CompensationTypes& types) {
  Listing out;
  for (const machine::CompensationType& t : types.types) out.emplace_back((t.complete ? "" : "!") + t.code, t.sources);
  return out;
}

void expect_listing(const CompensationTypes& types, const Listing& expected) {
  const Listing got = listing_of(types);
  EXPECT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < std::max(got.size(), expected.size()); ++i) {
    const std::string want = i < expected.size() ? expected[i].first : "(nothing)";
    const std::string have = i < got.size() ? got[i].first : "(nothing)";
    EXPECT_EQ(have, want) << "type " << i;
    if (i < got.size() && i < expected.size()) {
      EXPECT_EQ(got[i].second, expected[i].second) << want;
    }
  }
}

const std::vector<std::string> kLinearAll = {"L-POS", "L-STR", "L-SQU", "L-ANG"};
const std::vector<std::string> kRotaryAll = {"R-POS", "R-RAX", "R-POR", "R-ANG"};
std::vector<std::string> with_for(std::vector<std::string> parts) {
  parts.push_back("FOR");
  return parts;
}

// Six-column tables of every linear axis (x.csv: EXX..ECX, all non-zero): positioning,
// straightness and angular motions of each.
Listing linear_tables(const std::string& squareness_y, const std::string& squareness_z) {
  return {{"L-POS", {"X: EXX (x.csv)", "Y: EYY (y.csv)", "Z: EZZ (z.csv)"}},
          {"L-STR", {"X: EYX, EZX (x.csv)", "Y: EXY, EZY (y.csv)", "Z: EXZ, EYZ (z.csv)"}},
          {"L-SQU", {squareness_y, squareness_z}},
          {"L-ANG", {"X: EAX, EBX, ECX (x.csv)", "Y: EAY, EBY, ECY (y.csv)", "Z: EAZ, EBZ, ECZ (z.csv)"}},
          {"L-VOL", kLinearAll}};
}

// mc300.toml: tables of X, Y, Z (six columns each), EC0Y, EA0Z and EB0Z; tables of B and C
// (six columns), EA0B, EC0B, EA0C, EC0C; two rotary axes.
Listing mc300_listing() {
  Listing l = linear_tables("Y: EC0Y", "Z: EA0Z, EB0Z");
  l.push_back({"FOR", {"two rotary axes: volkins corrects the tool direction too, faded out near the pole"}});
  l.push_back({"L-VOL+", with_for(kLinearAll)});
  // EC0C, C's zero position, is an angular positioning error (R-POS), not a location (R-POR).
  l.push_back({"R-POS", {"B: EBB (b.csv)", "C: EC0C (zero position)", "C: ECC (c.csv)"}});
  l.push_back({"R-RAX", {"B: EXB, EYB, EZB (b.csv)", "C: EXC, EYC, EZC (c.csv)"}});
  l.push_back({"R-POR", {"B: EA0B, EC0B", "C: EA0C"}});
  l.push_back({"R-ANG", {"B: EAB, ECB (b.csv)", "C: EAC, EBC (c.csv)"}});
  l.push_back({"R-VOL", kRotaryAll});
  l.push_back({"R-VOL+", with_for(kRotaryAll)});
  return l;
}

machine::Model load(const std::string& name) { return machine::load_machine(test::machine_path(name)); }

TEST(CompensationTypes, Mc300ProvidesLinearAndRotaryVolumetricWithOrientation) {
  const CompensationTypes t = machine::compensation_types(load("mc300"));
  expect_listing(t, mc300_listing());
  EXPECT_TRUE(t.orientation_possible);
  EXPECT_TRUE(t.has("L-VOL+"));
  EXPECT_TRUE(t.has("R-VOL+"));
  EXPECT_TRUE(t.thermal.empty());
}

// mc300_thermal.toml: the MC-300 with a temperature table beside each linear axis's (EXX over
// x and coolant, EYY over y and coolant, EZZ over z and spindle).
TEST(CompensationTypes, Mc300ThermalAddsItsTemperatureTables) {
  const CompensationTypes t = machine::compensation_types(load("mc300_thermal"));
  Listing l = mc300_listing();
  l[0].second = {"X: EXX (x.csv)",         "X: EXX (x_coolant.csv)", "Y: EYY (y.csv)",
                 "Y: EYY (y_coolant.csv)", "Z: EZZ (z.csv)",         "Z: EZZ (z_spindle.csv)"};
  expect_listing(t, l);
  EXPECT_EQ(t.thermal, (std::vector<std::string>{"coolant: X EXX (x_coolant.csv); Y EYY (y_coolant.csv)",
                                                 "spindle: Z EZZ (z_spindle.csv)"}));
}

// mill3.toml: three linear axes, six-column tables, EC0X, EA0Z and EB0Z, a cross-axis table
// EZZ(z, y) and [stiffness] for X, Y and Z: L-VOL, and L-SPEC for the compliance and the
// cross-axis table; no rotary axis: no FOR.
TEST(CompensationTypes, Mill3ProvidesLinearVolumetricAndItsSpecificTerms) {
  const CompensationTypes t = machine::compensation_types(load("mill3"));
  Listing l = linear_tables("X: EC0X", "Z: EA0Z, EB0Z");
  l[0].second = {"X: EXX (x.csv)", "Y: EYY (y.csv)", "Z: EZZ (z.csv)", "Z: EZZ (z_by_y.csv)"};
  l.push_back({"L-SPEC",
               {"X: cutting-force compliance ([stiffness])", "Y: cutting-force compliance ([stiffness])",
                "Z: cutting-force compliance ([stiffness])", "Z: EZZ over another axis (z_by_y.csv)"}});
  expect_listing(t, l);
  EXPECT_FALSE(t.orientation_possible);
  EXPECT_EQ(t.find("FOR"), nullptr);
  EXPECT_EQ(t.find("L-VOL+"), nullptr);
}

// knee_mill.toml: Z, Y, X on the workpiece chain (listed in joint order, X Y Z), six-column
// tables, EA0Y, EB0X, EC0X.
TEST(CompensationTypes, KneeMillProvidesLinearVolumetric) {
  const CompensationTypes t = machine::compensation_types(load("knee_mill"));
  expect_listing(t, linear_tables("X: EB0X, EC0X", "Y: EA0Y"));
  EXPECT_FALSE(t.orientation_possible);
}

// ac_trunnion.toml: X, Y, Z tables, EC0Y, EA0Z, EB0Z; A and C tables (six columns), EY0A,
// EZ0A, EB0A, EC0A, EX0C, EY0C, EZ0C, EA0C, EB0C; the spindle line's EA0S and EB0S.
TEST(CompensationTypes, AcTrunnionProvidesEverythingAndTheSpindleLine) {
  const CompensationTypes t = machine::compensation_types(load("ac_trunnion"));
  Listing l = linear_tables("Y: EC0Y", "Z: EA0Z, EB0Z");
  l.push_back({"FOR", {"two rotary axes: volkins corrects the tool direction too, faded out near the pole"}});
  l.push_back({"L-VOL+", with_for(kLinearAll)});
  l.push_back({"R-POS", {"A: EAA (a.csv)", "C: ECC (c.csv)"}});
  l.push_back({"R-RAX", {"A: EXA, EYA, EZA (a.csv)", "C: EXC, EYC, EZC (c.csv)"}});
  l.push_back({"R-POR", {"A: EY0A, EZ0A, EB0A, EC0A", "C: EX0C, EY0C, EZ0C, EA0C, EB0C"}});
  l.push_back({"R-ANG", {"A: EBA, ECA (a.csv)", "C: EAC, EBC (c.csv)"}});
  l.push_back({"R-VOL", kRotaryAll});
  l.push_back({"R-VOL+", with_for(kRotaryAll)});
  l.push_back({"L-SPEC", {"spindle: EA0S, EB0S"}});
  expect_listing(t, l);
}

// The test machines of tests/unit/machines/data, on the ac_trunnion's linear tables.
machine::Model load_test_machine(const std::string& name) {
  return machine::load_machine(test::source_path("tests/unit/machines/data/" + name + ".toml"));
}

// xyza_table.toml: X, Y, Z as the ac_trunnion; one rotary axis A (a.csv, six columns; EY0A,
// EZ0A, EB0A, EC0A); the spindle's EA0S, EB0S. One rotary axis: R-VOL, but no FOR.
TEST(CompensationTypes, XyzaTableProvidesRotaryVolumetricWithoutOrientation) {
  const CompensationTypes t = machine::compensation_types(load_test_machine("xyza_table"));
  Listing l = linear_tables("Y: EC0Y", "Z: EA0Z, EB0Z");
  l.push_back({"R-POS", {"A: EAA (a.csv)"}});
  l.push_back({"R-RAX", {"A: EXA, EYA, EZA (a.csv)"}});
  l.push_back({"R-POR", {"A: EY0A, EZ0A, EB0A, EC0A"}});
  l.push_back({"R-ANG", {"A: EBA, ECA (a.csv)"}});
  l.push_back({"R-VOL", kRotaryAll});
  l.push_back({"L-SPEC", {"spindle: EA0S, EB0S"}});
  expect_listing(t, l);
  EXPECT_FALSE(t.orientation_possible);
}

// bc_head.toml: B in the tool chain (b_head.csv, six columns; EX0B, EZ0B, EA0B, EC0B), C on
// the table (ac_trunnion's c.csv; EX0C, EY0C, EA0C, EB0C).
TEST(CompensationTypes, BcHeadProvidesEverythingWithOrientation) {
  const CompensationTypes t = machine::compensation_types(load_test_machine("bc_head"));
  Listing l = linear_tables("Y: EC0Y", "Z: EA0Z, EB0Z");
  l.push_back({"FOR", {"two rotary axes: volkins corrects the tool direction too, faded out near the pole"}});
  l.push_back({"L-VOL+", with_for(kLinearAll)});
  l.push_back({"R-POS", {"B: EBB (b_head.csv)", "C: ECC (c.csv)"}});
  l.push_back({"R-RAX", {"B: EXB, EYB, EZB (b_head.csv)", "C: EXC, EYC, EZC (c.csv)"}});
  l.push_back({"R-POR", {"B: EX0B, EZ0B, EA0B, EC0B", "C: EX0C, EY0C, EA0C, EB0C"}});
  l.push_back({"R-ANG", {"B: EAB, ECB (b_head.csv)", "C: EAC, EBC (c.csv)"}});
  l.push_back({"R-VOL", kRotaryAll});
  l.push_back({"R-VOL+", with_for(kRotaryAll)});
  l.push_back({"L-SPEC", {"spindle: EA0S, EB0S"}});
  expect_listing(t, l);
}

TEST(CompensationTypes, EveryShippedMachineIsListedHere) {
  // The tests above cover these; a new machine file needs its listing here.
  EXPECT_EQ(test::shipped_machines(), (std::vector<std::string>{"mc300", "mill3", "ac_trunnion", "knee_mill"}));
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(test::source_path("machines/data")))
    if (e.path().extension() == ".toml") files.push_back(e.path().stem().string());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"ac_trunnion", "knee_mill", "mc300", "mc300_thermal", "mill3"}));
}

// ---- files with no error, or one kind --------------------------------------------------

class CompensationTypesOneKind : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new fs::path(fs::temp_directory_path() / ("vc_comp_types_" + std::to_string(::getpid())));
    fs::remove_all(*folder_);
    fs::create_directories(*folder_);
    const test::CommandResult r = test::run_volcomp(
        "init /usr/share/doc/linuxcnc/examples/sample-configs/sim/axis/vismach/5axis/table-rotary-tilting/"
        "xyzbc-trt.ini -o " +
        (*folder_ / "nominal.toml").string() + " > /dev/null");
    ASSERT_EQ(r.exit_code, 0) << r.out;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*folder_);
    delete folder_;
  }
  // `volcomp perturb` of the nominal machine with `options`; the machine it writes.
  static machine::Model perturbed(const std::string& name, const std::string& options) {
    const fs::path out = *folder_ / name;
    const test::CommandResult r =
        test::run_volcomp("perturb " + (*folder_ / "nominal.toml").string() + " -o " + out.string() + " " + options);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    return machine::load_machine((out / "nominal.toml").string());
  }
  static void write(const std::string& name, const std::string& text) { std::ofstream(*folder_ / name) << text; }
  static fs::path* folder_;
};
fs::path* CompensationTypesOneKind::folder_ = nullptr;

const std::string kFor = "two rotary axes: volkins corrects the tool direction too, faded out near the pole";

TEST_F(CompensationTypesOneKind, NominalMachineFromInitProvidesNone) {
  const CompensationTypes t = machine::compensation_types(machine::load_machine((*folder_ / "nominal.toml").string()));
  EXPECT_TRUE(t.types.empty()) << listing_of(t).front().first;
  EXPECT_TRUE(t.orientation_possible);  // B and C: it could, had the file an orientation error
  EXPECT_TRUE(t.thermal.empty());
}

TEST_F(CompensationTypesOneKind, RotaryPositionLocationIsRPorAlone) {
  // A position error of the C line moves the tool point, not its direction: no FOR.
  expect_listing(machine::compensation_types(perturbed("ex0c", "--location EX0C=15um")),
                 {{"R-POR", {"C: EX0C"}}, {"!R-VOL", {"R-POR"}}});
}

TEST_F(CompensationTypesOneKind, RotaryOrientationLocationIsRPorWithOrientation) {
  expect_listing(machine::compensation_types(perturbed("eb0c", "--location EB0C=-3arcsec")),
                 {{"FOR", {kFor}}, {"R-POR", {"C: EB0C"}}, {"!R-VOL", {"R-POR"}}, {"!R-VOL+", {"R-POR", "FOR"}}});
}

TEST_F(CompensationTypesOneKind, SquarenessIsLSquAlone) {
  expect_listing(machine::compensation_types(perturbed("ea0z", "--location EA0Z=4arcsec")),
                 {{"L-SQU", {"Z: EA0Z"}}, {"!L-VOL", {"L-SQU"}}, {"FOR", {kFor}}, {"!L-VOL+", {"L-SQU", "FOR"}}});
}

TEST_F(CompensationTypesOneKind, PositioningTableIsLPosAlone) {
  write("exx.csv", "x[mm],EXX[um]\n-200,0\n0,3\n200,-2\n");
  expect_listing(machine::compensation_types(perturbed("exx", "--add-table " + (*folder_ / "exx.csv").string())),
                 {{"L-POS", {"X: EXX (exx.csv)"}}, {"!L-VOL", {"L-POS"}}});
}

TEST_F(CompensationTypesOneKind, StraightnessTableIsLStrAlone) {
  write("eyz.csv", "z[mm],EYZ[um],EXZ[um]\n-120,0,0\n0,2,0\n120,-1,0\n");  // EXZ all zero: not provided
  expect_listing(machine::compensation_types(perturbed("eyz", "--add-table " + (*folder_ / "eyz.csv").string())),
                 {{"L-STR", {"Z: EYZ (eyz.csv)"}}, {"!L-VOL", {"L-STR"}}});
}

TEST_F(CompensationTypesOneKind, RotaryTablesSortIntoPositioningRunOutAndTilt) {
  write("ecc.csv", "c[deg],ECC[arcsec]\n0,0\n180,4\n360,0\n");
  expect_listing(
      machine::compensation_types(perturbed("ecc", "--add-table " + (*folder_ / "ecc.csv").string())),
      {{"FOR", {kFor}}, {"R-POS", {"C: ECC (ecc.csv)"}}, {"!R-VOL", {"R-POS"}}, {"!R-VOL+", {"R-POS", "FOR"}}});
  write("ezb.csv", "b[deg],EZB[um]\n-100,1\n0,0\n50,2\n");  // axial run-out of B: a position error, no FOR
  expect_listing(machine::compensation_types(perturbed("ezb", "--add-table " + (*folder_ / "ezb.csv").string())),
                 {{"R-RAX", {"B: EZB (ezb.csv)"}}, {"!R-VOL", {"R-RAX"}}});
  write("eab.csv", "b[deg],EAB[arcsec]\n-100,1\n0,0\n50,2\n");
  expect_listing(
      machine::compensation_types(perturbed("eab", "--add-table " + (*folder_ / "eab.csv").string())),
      {{"FOR", {kFor}}, {"R-ANG", {"B: EAB (eab.csv)"}}, {"!R-VOL", {"R-ANG"}}, {"!R-VOL+", {"R-ANG", "FOR"}}});
}

// A three-axis machine written here: one kind of error at a time, no FOR possible.
std::string three_axes(const std::string& x_extra, const std::string& tail = "") {
  return "[machine]\nname = \"three\"\n[spindle]\ngauge_point_mm = [0, 0, 0]\ntool_length_mm = 100\n"
         "[fixture]\norigin_mm = [0, 0, 0]\nrotation_deg = [0, 0, 0]\n"
         "[[tool_chain]]\naxis = \"X\"\ntype = \"linear\"\ndirection = [1, 0, 0]\npole_mm = [0, 0, 0]\n"
         "travel_mm = [0, 300]\n" +
         x_extra +
         "[[tool_chain]]\naxis = \"Y\"\ntype = \"linear\"\ndirection = [0, 1, 0]\npole_mm = [0, 0, 0]\n"
         "travel_mm = [0, 300]\n"
         "[[tool_chain]]\naxis = \"Z\"\ntype = \"linear\"\ndirection = [0, 0, 1]\npole_mm = [0, 0, 0]\n"
         "travel_mm = [-300, 0]\n" +
         tail;
}

TEST_F(CompensationTypesOneKind, ThreeAxesAngularTableIsLAngWithoutOrientation) {
  write("ecx.csv", "x[mm],ECX[arcsec]\n0,0\n300,3\n");
  write("three_ang.toml", three_axes("[[tool_chain.tables]]\nfile = \"ecx.csv\"\n"));
  const CompensationTypes t =
      machine::compensation_types(machine::load_machine((*folder_ / "three_ang.toml").string()));
  expect_listing(t, {{"L-ANG", {"X: ECX (ecx.csv)"}}, {"!L-VOL", {"L-ANG"}}});
  EXPECT_FALSE(t.orientation_possible);
}

TEST_F(CompensationTypesOneKind, OffsetRollAndComplianceAreLSpec) {
  write("three_spec.toml", three_axes("[tool_chain.location]\nEY0X_um = 5.0\nEA0X_arcsec = 2.0\n",
                                      "[stiffness]\nZ = { compliance_um_per_N = 0.03 }\n"));
  expect_listing(machine::compensation_types(machine::load_machine((*folder_ / "three_spec.toml").string())),
                 {{"L-SPEC",
                   {"X: EY0X (offset of the axis line), EA0X (roll of the axis line)",
                    "Z: cutting-force compliance ([stiffness])"}}});
}

TEST_F(CompensationTypesOneKind, TemperatureTableIsThermalAndItsColumnsType) {
  write("exx_t.csv", "x[mm],air[degC],EXX[um]\n0,15,0\n0,25,0\n300,15,-2\n300,25,3\n");
  write("three_thermal.toml", "[temperatures]\nair = { reference_degC = 20.0, min_degC = 15.0, max_degC = 25.0 }\n" +
                                  three_axes("[[tool_chain.tables]]\nfile = \"exx_t.csv\"\n"));
  const CompensationTypes t =
      machine::compensation_types(machine::load_machine((*folder_ / "three_thermal.toml").string()));
  expect_listing(t, {{"L-POS", {"X: EXX (exx_t.csv)"}}, {"!L-VOL", {"L-POS"}}});
  EXPECT_EQ(t.thermal, (std::vector<std::string>{"air: X EXX (exx_t.csv)"}));
}

}  // namespace
}  // namespace vc
