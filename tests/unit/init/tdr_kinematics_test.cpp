// `volcomp init` describes LinuxCNC's xyzab_tdr_kins (a dual rotary table: B on the bed carrying
// the rotary table A) exactly: the machine files it writes for the installed xyzab-tdr sample
// (read in place, its geometry from the pyvcp sliders' start values) and for random rotation
// points and offsets (set by setp and sets) give, in volkins' TCP world, the tool tip that the
// module's kinematicsForward computes and the joints of its kinematicsInverse (type 1, both
// transcribed below from xyzab_tdr_kins.comp, independently of init), to 1e-9 mm over 2000
// random poses each, and its identity type 0 is volkins' default type 0. millturn, whose turning
// type the model cannot express, and parameters xyzab_tdr_kins does not read are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "generated_machine.hpp"
#include "init_test_files.hpp"
#include "vc/init/init.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::init {
namespace {

namespace fs = std::filesystem;
using machine::Joints;
using test::Generated;
using test::generate;

constexpr double kRad = M_PI / 180.0;

// LinuxCNC 2.9's xyzab_tdr_kins.comp (commit b09da1ae11), kinematicsForward and -Inverse of type
// 1 (TCP): xr, yr, zr the x/y/z-rot-point pins, dx, dz the x/z-offset pins, dt the tool-offset-z
// pin. The joints and the world are x, y, z, a, b; angles in deg.
struct Tdr {
  double xr = 0, yr = 0, zr = 0, dx = 0, dz = 0;
};

Eigen::Vector3d tdr_forward(const Tdr& p, double dt, const Joints& j) {
  const double sa = std::sin(j[3] * kRad), ca = std::cos(j[3] * kRad);
  const double sb = std::sin(j[4] * kRad), cb = std::cos(j[4] * kRad);
  const double px = j[0] - p.xr, py = j[1] - p.yr, pz = j[2] - p.zr - dt;
  return {cb * px + sb * pz + p.xr,  //
          sa * sb * px + ca * py - cb * sa * pz + sa * p.dz + p.yr,
          -ca * sb * px + sa * py + ca * cb * pz - ca * p.dz + p.zr + p.dz + dt};
}

Eigen::Vector3d tdr_inverse(const Tdr& p, double dt, const Joints& w) {
  const double sa = std::sin(w[3] * kRad), ca = std::cos(w[3] * kRad);
  const double sb = std::sin(w[4] * kRad), cb = std::cos(w[4] * kRad);
  const double qx = w[0] - p.xr - p.dx, qy = w[1] - p.yr, qz = w[2] - p.zr - p.dz - dt;
  return {cb * qx + sa * sb * qy - ca * sb * qz + cb * p.dx - sb * p.dz + p.xr,  //
          ca * qy + sa * qz + p.yr, sb * qx - sa * cb * qy + ca * cb * qz + sb * p.dx + cb * p.dz + p.zr + dt};
}

// volkins' TCP world (the model's tool tip in the part frame; LinuxCNC's Z is the tip's plus
// G43's offset, as kins/src/volkins.cc's set_world) against xyzab_tdr_kins' type 1, both ways,
// and its identity type 0 against volkins' axes world: joints over their travel, tool offset
// 0..150 mm. Returns the largest difference (mm, deg).
double expect_tdr_kinematics(const machine::Model& model, const Tdr& p, int poses, unsigned seed) {
  EXPECT_EQ(model.coordinates(), "xyzab");
  if (model.coordinates() != "xyzab") return INFINITY;
  std::mt19937_64 rng(seed);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  double worst = 0.0;
  for (int i = 0; i < poses; ++i) {
    Joints q(5);
    for (int k = 0; k < 5; ++k) q[k] = uniform(model.axes[k].travel_min, model.axes[k].travel_max);
    const double offset = uniform(0.0, 150.0);
    const double L = model.correction_length(offset);

    Joints world = machine::nominal_forward(model, machine::WorldConvention::Tcp, q, L);
    world[2] += offset;
    const Eigen::Vector3d stock = tdr_forward(p, offset, q);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(world[k], stock[k], 1e-9) << "forward, pose " << i << " axis " << k;
      worst = std::max(worst, std::abs(world[k] - stock[k]));
    }
    EXPECT_EQ(world[3], q[3]);
    EXPECT_EQ(world[4], q[4]);

    const Eigen::Vector3d stock_joints = tdr_inverse(p, offset, world);
    Joints tip = world;
    tip[2] -= offset;  // the core's TCP world: without G43's Z
    Joints joints;
    EXPECT_EQ(machine::nominal_inverse(model, machine::WorldConvention::Tcp, tip, L, joints), machine::Status::Ok);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(joints[k], stock_joints[k], 1e-9) << "inverse, pose " << i << " axis " << k;
      EXPECT_NEAR(joints[k], q[k], 1e-9) << "round trip, pose " << i;
      worst = std::max(worst, std::abs(joints[k] - stock_joints[k]));
    }
    for (int k = 3; k < 5; ++k) {
      EXPECT_NEAR(joints[k], q[k], 1e-9) << "inverse, pose " << i << " joint " << k;
      worst = std::max(worst, std::abs(joints[k] - q[k]));
    }
    // Type 0, the identity: the world is the joints.
    EXPECT_EQ(machine::nominal_forward(model, machine::WorldConvention::Axes, q, L), q) << "identity, pose " << i;
  }
  return worst;
}

void record_largest_difference(double worst) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", worst);
  ::testing::Test::RecordProperty("largest_difference_mm", text);
  std::printf("largest difference to xyzab_tdr_kins: %s mm / deg\n", text);
}

void expect_vector(const Eigen::Vector3d& v, const Eigen::Vector3d& expected, const char* what) {
  EXPECT_LT((v - expected).norm(), 1e-12) << what << ": " << v.transpose() << " instead of " << expected.transpose();
}

TEST(StockKinematics, TdrSampleMatchesXyzabTdrKins) {
  if (!test::samples_installed())
    GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
  const Generated g = generate(test::kSampleConfigs / "table-dual-rotary/xyzab-tdr.ini", "tdr_sample");
  // Its geometry: the pyvcp sliders' start values in xyzab-tdr.xml (the HALCMD's sets on
  // :x-offset and :z-offset are overwritten by them; the rot points have no sets).
  expect_vector(g.model.axes[4].pole_mm, {-50, -50, -100}, "B pole");
  expect_vector(g.model.axes[3].pole_mm, {0, 0, -10}, "A pole");
  expect_vector(g.model.axes[4].direction, {0, -1, 0}, "B direction");
  expect_vector(g.model.axes[3].direction, {-1, 0, 0}, "A direction");
  expect_vector(g.model.fixture.translation(), {50, 50, 110}, "fixture");
  EXPECT_EQ(g.model.workpiece_chain, (std::vector<int>{4, 3}));  // B on the bed carries A
  EXPECT_EQ(g.model.tool_chain, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(g.model.axes[3].travel_min, -3600.0);
  EXPECT_EQ(g.model.axes[4].travel_max, 180.0);
  EXPECT_EQ(g.model.tool_length_mm, 50.0);  // T4 Z50 of xyzab-tdr.tbl
  EXPECT_EQ(g.model.tool_length_reference_mm, 0.0);
  // Type 0 the identity, type 1 TCP, as volkins' default.
  EXPECT_EQ(g.result.machine.world, "");
  EXPECT_FALSE(g.result.machine.identity_first);
  EXPECT_EQ(g.result.patch.kinematics, "volkins machine=" + g.result.machine_path + " coordinates=xyzab");
  for (const char* origin :
       {"x-rot-point = -50: the pyvcp slider x-rot-point's start, xyzab-tdr.xml:256 `<initval>-50</initval>` "
        "(pyvcp.x-rot-point-f drives :x-rot-point, xyzab-tdr-postgui.hal:20 ",
        "z-offset = -10: the pyvcp slider z-offset's start, xyzab-tdr.xml:177 `<initval>-10</initval>`",
        "moving a slider no longer changes the kinematics", "xyzab_tdr_kins's x-offset cancels out of its equations"})
    EXPECT_NE(g.result.machine_text.find(origin), std::string::npos) << origin << "\n" << g.result.machine_text;
  record_largest_difference(expect_tdr_kinematics(g.model, {-50, -50, -100, -20, -10}, 2000, 5));
}

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// An xyzab_tdr_kins configuration of our own: the pins set in a HAL file (setp, and sets on a
// signal), the tool offset netted to motion.tooloffset.z.
fs::path tdr_configuration(const std::string& name, const Tdr& p, const std::string& kinematics = "xyzab_tdr_kins") {
  const fs::path dir = test::scratch_folder(name);
  std::string ini = "[EMC]\nMACHINE = random tdr\n[KINS]\nKINEMATICS = " + kinematics +
                    "\nJOINTS = 5\n[TRAJ]\nCOORDINATES = XYZAB\nLINEAR_UNITS = mm\nANGULAR_UNITS = deg\n"
                    "[HAL]\nHALFILE = tdr.hal\n";
  const double limits[5][2] = {{-300, 250}, {-200, 220}, {-350, 100}, {-720, 720}, {-120, 110}};
  for (int j = 0; j < 5; ++j)
    ini += "[JOINT_" + std::to_string(j) + "]\nTYPE = " + (j < 3 ? "LINEAR" : "ANGULAR") +
           "\nMIN_LIMIT = " + std::to_string(limits[j][0]) + "\nMAX_LIMIT = " + std::to_string(limits[j][1]) + "\n";
  test::write_file(dir / "tdr.ini", ini);
  test::write_file(dir / "tdr.hal",
                   "loadrt [KINS]KINEMATICS\n"
                   "net :tool-offset motion.tooloffset.z => xyzab_tdr_kins.tool-offset-z\n"
                   "setp xyzab_tdr_kins.x-rot-point " +
                       number(p.xr) + "\nnet :yr => xyzab_tdr_kins.y-rot-point\nsets :yr " + number(p.yr) +
                       "\nsetp xyzab_tdr_kins.z-rot-point " + number(p.zr) + "\nsetp xyzab_tdr_kins.x-offset " +
                       number(p.dx) + "\nnet :dz xyzab_tdr_kins.z-offset\nsets :dz " + number(p.dz) + "\n");
  return dir / "tdr.ini";
}

TEST(StockKinematics, RandomTdrGeometriesMatchXyzabTdrKins) {
  std::mt19937_64 rng(20261202);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  double worst = 0.0;
  for (int geometry = 0; geometry < 5; ++geometry) {
    const Tdr p{uniform(-200, 200), uniform(-200, 200), uniform(-200, 200), uniform(-100, 100), uniform(-100, 100)};
    SCOPED_TRACE("xyzab_tdr_kins geometry " + std::to_string(geometry));
    const std::string name = "tdr" + std::to_string(geometry);
    const Generated g = generate(tdr_configuration(name, p), name + "_machine");
    expect_vector(g.model.axes[4].pole_mm, {p.xr, p.yr, p.zr}, "B pole");
    expect_vector(g.model.axes[3].pole_mm, {0, 0, p.dz}, "A pole");
    EXPECT_EQ(g.result.patch.kinematics, "volkins machine=" + g.result.machine_path + " coordinates=xyzab");
    // The tool offset pin's net goes to volkins; every other stock pin's line goes.
    EXPECT_NE(g.result.patch.diff.find("+net :tool-offset motion.tooloffset.z => volkins.tool-offset\n"),
              std::string::npos)
        << g.result.patch.diff;
    worst = std::max(worst, expect_tdr_kinematics(g.model, p, 2000, 300 + static_cast<unsigned>(geometry)));
  }
  record_largest_difference(worst);
}

// An inch configuration: the pins in inches, the machine file in mm (x 25.4, cited), the stock
// equations in inches scaled to mm.
TEST(StockKinematics, InchTdrPinsAreConvertedToMm) {
  const Tdr inch{2, -3, 4.5, 1, -0.75};
  const fs::path ini = tdr_configuration("tdr_inch", inch);
  std::string text = test::file_text(ini);
  text.replace(text.find("LINEAR_UNITS = mm"), 17, "LINEAR_UNITS = inch");
  test::write_file(ini, text);
  const Generated g = generate(ini, "tdr_inch_machine");
  expect_vector(g.model.axes[4].pole_mm, {50.8, -76.2, 114.3}, "B pole");
  expect_vector(g.model.axes[3].pole_mm, {0, 0, -0.75 * 25.4}, "A pole");
  EXPECT_NE(g.result.machine_text.find("z-offset = -0.75 inch (-19.0"), std::string::npos)
      << g.result.machine_text;
  const Tdr mm{50.8, -76.2, 114.3, 25.4, -19.05};
  record_largest_difference(expect_tdr_kinematics(g.model, mm, 400, 7));
}

// A pyvcp slider of the configuration's own panel: its start held within min_ .. max_ as pyvcp
// holds it; one whose value comes from outside the panel (param_pin) and one whose start is off
// its resolution refused.
TEST(StockKinematics, TdrGeometryFromAPyvcpSlider) {
  const Tdr p{10, 20, 30, 0, 5};
  const fs::path ini = tdr_configuration("tdr_slider", p);
  std::string text = test::file_text(ini);
  text.insert(text.find("[KINS]"), "[DISPLAY]\nPYVCP = panel.xml\n");
  test::write_file(ini, text);
  test::write_file(ini.parent_path() / "post.hal", "net :dz <= pyvcp.dz-f\n");
  text.insert(text.find("HALFILE = tdr.hal\n") + 18, "POSTGUI_HALFILE = post.hal\n");
  test::write_file(ini, text);
  const std::string panel =
      "<pyvcp>\n<!-- <scale><halpin>\"dz\"</halpin><initval>99</initval></scale> -->\n"
      "<scale>\n  <halpin>\"dz\"</halpin>\n  <resolution>0.5</resolution>\n  <min_>-40</min_>\n  <max_>-7.5</max_>\n"
      "  <initval>12</initval>\n</scale>\n</pyvcp>\n";
  test::write_file(ini.parent_path() / "panel.xml", panel);
  const Generated g = generate(ini, "tdr_slider_machine");
  expect_vector(g.model.axes[3].pole_mm, {0, 0, -7.5}, "A pole");  // 12 held at max_ -7.5, not sets :dz 5
  EXPECT_NE(g.result.machine_text.find("z-offset = -7.5: the pyvcp slider dz's start, panel.xml:8 "
                                       "`<initval>12</initval>`, held at panel.xml:7 `<max_>-7.5</max_>`"),
            std::string::npos)
      << g.result.machine_text;
  record_largest_difference(expect_tdr_kinematics(g.model, {10, 20, 30, 0, -7.5}, 200, 6));

  std::string refused = panel;
  refused.replace(refused.find("  <initval>"), 0, "  <param_pin>1</param_pin>\n");
  test::write_file(ini.parent_path() / "panel.xml", refused);
  try {
    run_init({ini.string(), (ini.parent_path() / "never.toml").string(), "2026-01-01"});
    ADD_FAILURE() << "a slider with a param_pin was accepted";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where().line, 3);
    EXPECT_NE(e.message().find("the pyvcp slider dz has a <param_pin>: its value is set from outside the panel"),
              std::string::npos)
        << e.what();
  }
  // A start off the slider's resolution (Tk would round it).
  std::string off = panel;
  off.replace(off.find("<initval>12</initval>"), 21, "<initval>-10.3</initval>");
  test::write_file(ini.parent_path() / "panel.xml", off);
  try {
    run_init({ini.string(), (ini.parent_path() / "never.toml").string(), "2026-01-01"});
    ADD_FAILURE() << "a start off the resolution was accepted";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where().line, 3);
    EXPECT_NE(e.message().find("the pyvcp slider dz starts at -10.3, not a multiple of its resolution 0.5"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(ini.parent_path() / "never.toml"));
}

LoadError refusal(const fs::path& ini) {
  try {
    run_init({ini.string(), (fs::temp_directory_path() / "never_written.toml").string(), "2026-01-01"});
  } catch (const LoadError& e) {
    return e;
  }
  ADD_FAILURE() << ini << " was accepted";
  return LoadError({}, "");
}

TEST(StockKinematics, RefusesMillturnAndTdrParameters) {
  // halcompile's count= (rtapi_app takes it; it makes dummy instances, which volkins has not).
  const LoadError count = refusal(tdr_configuration("tdr_count", {}, "xyzab_tdr_kins count=2"));
  EXPECT_EQ(count.where().line, 4);
  EXPECT_EQ(count.message().rfind("`count=2`: xyzab_tdr_kins has no parameter of its own", 0), 0u) << count.what();
  if (!test::samples_installed())
    GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
  const LoadError millturn = refusal(test::kSampleConfigs.parent_path() / "millturn/millturn.ini");
  EXPECT_EQ(millturn.where().line, 10);
  EXPECT_NE(millturn.message().find("millturn is refused: its kinematics type 1 (turning, millturn.comp) turns the "
                                    "world against the joints (x = the Z joint, y = minus the Y joint, z = the X "
                                    "joint) and passes A through as the work spindle"),
            std::string::npos)
      << millturn.what();
}

}  // namespace
}  // namespace vc::init
