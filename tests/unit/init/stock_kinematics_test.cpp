// `volcomp init` describes the stock kinematics exactly: the machine files it writes for
// LinuxCNC's xyzbc-trt and xyzac-trt samples (read in place) and for random rotation points
// and offsets give, in volkins' TCP world, the tool tip that LinuxCNC's xyzbc-trt-kins and
// xyzac-trt-kins compute (trtfuncs.c's equations, transcribed below independently of init),
// forward and inverse, to 1e-9 mm over 2000 random poses. trivkins configurations (a gantry
// with a duplicated letter) keep each axis once; modules the model cannot express are refused
// with the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "init_test_files.hpp"
#include "vc/init/init.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::init {
namespace {

namespace fs = std::filesystem;
using machine::Joints;

// LinuxCNC 2.9's trtfuncs.c (commit f1270d6ed7), xyz?cKinematicsForward and -Inverse: xr, yr,
// zr the x/y/z-rot-point pins, dx, dy, dz the x/y/z-offset pins, dt the tool-offset pin. The
// joints and the world are x, y, z, tilt (B or A), c; angles in deg.
struct Trt {
  bool bc = true;  // xyzbc-trt-kins, else xyzac-trt-kins
  double xr = 0, yr = 0, zr = 0, dx = 0, dy = 0, dz = 0;
};

constexpr double kRad = M_PI / 180.0;

Eigen::Vector3d stock_forward(const Trt& p, double dt, const Joints& j) {
  const double t = j[3] * kRad, c = j[4] * kRad, dz = p.dz + dt;
  if (p.bc) {
    const double u = j[0] - p.dx - p.xr, v = j[1] - p.yr, w = j[2] - dz - p.zr;
    return {std::cos(c) * std::cos(t) * u + std::sin(c) * v - std::cos(c) * std::sin(t) * w + std::cos(c) * p.dx + p.xr,
            -std::sin(c) * std::cos(t) * u + std::cos(c) * v + std::sin(c) * std::sin(t) * w - std::sin(c) * p.dx + p.yr,
            std::sin(t) * u + std::cos(t) * w + dz + p.zr};
  }
  const double u = j[0] - p.xr, v = j[1] - p.dy - p.yr, w = j[2] - dz - p.zr;
  return {std::cos(c) * u + std::sin(c) * std::cos(t) * v + std::sin(c) * std::sin(t) * w + std::sin(c) * p.dy + p.xr,
          -std::sin(c) * u + std::cos(c) * std::cos(t) * v + std::cos(c) * std::sin(t) * w + std::cos(c) * p.dy + p.yr,
          -std::sin(t) * v + std::cos(t) * w + dz + p.zr};
}

Eigen::Vector3d stock_inverse(const Trt& p, double dt, const Joints& w) {
  const double t = w[3] * kRad, c = w[4] * kRad, dz = p.dz + dt;
  const double u = w[0] - p.xr, v = w[1] - p.yr, s = w[2] - p.zr;
  if (p.bc) {
    const double dpx = -std::cos(t) * p.dx - std::sin(t) * dz + p.dx;
    const double dpz = std::sin(t) * p.dx - std::cos(t) * dz + dz;
    return {std::cos(c) * std::cos(t) * u - std::sin(c) * std::cos(t) * v + std::sin(t) * s + dpx + p.xr,
            std::sin(c) * u + std::cos(c) * v + p.yr,
            -std::cos(c) * std::sin(t) * u + std::sin(c) * std::sin(t) * v + std::cos(t) * s + dpz + p.zr};
  }
  return {std::cos(c) * u - std::sin(c) * v + p.xr,
          std::sin(c) * std::cos(t) * u + std::cos(c) * std::cos(t) * v - std::sin(t) * s - std::cos(t) * p.dy +
              std::sin(t) * dz + p.dy + p.yr,
          std::sin(c) * std::sin(t) * u + std::cos(c) * std::sin(t) * v + std::cos(t) * s - std::sin(t) * p.dy -
              std::cos(t) * dz + dz + p.zr};
}

struct Generated {
  InitResult result;
  machine::Model model;
};

// init on `ini`, its machine file written beside the scratch folder's and loaded.
Generated generate(const fs::path& ini, const std::string& name) {
  const fs::path dir = test::scratch_folder(name);
  Generated g{run_init({ini.string(), (dir / "machine.toml").string(), "2026-01-01"}), {}};
  test::write_file(dir / "machine.toml", g.result.machine_text);
  g.model = machine::load_machine((dir / "machine.toml").string());
  return g;
}

// volkins' TCP world (the model's tool tip in the part frame, LinuxCNC's Z = tip + the tool
// length offset, as kins/src/volkins.cc's set_world) against the stock module, both ways.
void expect_stock_kinematics(const machine::Model& model, const Trt& p, int poses, unsigned seed) {
  ASSERT_EQ(model.coordinates(), p.bc ? "xyzbc" : "xyzac");
  std::mt19937_64 rng(seed);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  double worst = 0.0;
  for (int i = 0; i < poses; ++i) {
    Joints q(5);
    for (int j = 0; j < 3; ++j) q[j] = uniform(model.axes[j].travel_min, model.axes[j].travel_max);
    q[3] = uniform(-90.0, 90.0);
    q[4] = uniform(model.axes[4].travel_min, model.axes[4].travel_max);
    const double offset = uniform(0.0, 150.0);
    const double L = model.correction_length(offset);

    Joints world = machine::nominal_forward(model, machine::WorldConvention::Tcp, q, L);
    world[2] += offset;
    const Eigen::Vector3d stock = stock_forward(p, offset, q);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(world[k], stock[k], 1e-9) << "forward, pose " << i << " axis " << k;
      worst = std::max(worst, std::abs(world[k] - stock[k]));
    }
    EXPECT_EQ(world[3], q[3]);
    EXPECT_EQ(world[4], q[4]);

    const Eigen::Vector3d stock_joints = stock_inverse(p, offset, world);
    const Joints tip = world - offset * Joints::Unit(world.size(), 2);  // the core's TCP world: without G43's Z
    Joints joints;
    ASSERT_EQ(machine::nominal_inverse(model, machine::WorldConvention::Tcp, tip, L, joints), machine::Status::Ok);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(joints[k], stock_joints[k], 1e-9) << "inverse, pose " << i << " axis " << k;
      EXPECT_NEAR(joints[k], q[k], 1e-9) << "round trip, pose " << i;
      worst = std::max(worst, std::abs(joints[k] - stock_joints[k]));
    }
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", worst);
  ::testing::Test::RecordProperty("largest_difference_mm", text);
}

void expect_vector(const Eigen::Vector3d& v, const Eigen::Vector3d& expected, const char* what) {
  EXPECT_LT((v - expected).norm(), 1e-12) << what << ": " << v.transpose() << " instead of " << expected.transpose();
}

TEST(StockKinematics, XyzbcSampleMatchesXyzbcTrtKins) {
  if (!test::samples_installed()) GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
  const Generated g = generate(test::kSampleConfigs / "table-rotary-tilting/xyzbc-trt.ini", "xyzbc_sample");
  // The sample's values: x-offset -20, z-offset -15 (sets on their signals), rot points 0.
  expect_vector(g.model.axes[3].pole_mm, {-20, 0, -15}, "B pole");
  expect_vector(g.model.axes[4].pole_mm, {20, 0, 15}, "C pole");
  expect_vector(g.model.fixture.translation(), {0, 0, 0}, "fixture");
  EXPECT_EQ(g.model.axes[4].travel_min, -36000.0);
  EXPECT_EQ(g.model.axes[3].travel_max, 50.0);
  EXPECT_EQ(g.model.tool_length_mm, 10.0);  // T2 Z10 of xyzbc-trt.tbl
  EXPECT_EQ(g.model.info.name, "sim-xyzbc-trt-kins (switchkins)");
  EXPECT_TRUE(g.result.machine.identity_first);
  EXPECT_EQ(g.result.patch.kinematics, "volkins machine=" + g.result.machine_path + " coordinates=xyzbc sparm=identityfirst");
  EXPECT_NE(g.result.machine_text.find("x-offset = -20: xyzbc-trt.ini:65 `HALCMD = sets :x-offset     -20`"),
            std::string::npos)
      << g.result.machine_text;
  expect_stock_kinematics(g.model, {true, 0, 0, 0, -20, 0, -15}, 2000, 1);
}

TEST(StockKinematics, XyzacSampleMatchesXyzacTrtKins) {
  if (!test::samples_installed()) GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
  const Generated g = generate(test::kSampleConfigs / "table-rotary-tilting/xyzac-trt.ini", "xyzac_sample");
  // y-offset 20, z-offset 10.
  expect_vector(g.model.axes[3].pole_mm, {0, 20, 10}, "A pole");
  expect_vector(g.model.axes[4].pole_mm, {0, -20, -10}, "C pole");
  EXPECT_EQ(g.model.tool_length_mm, 30.0);  // T5..T9 Z30 of xyzac-trt.tbl
  expect_stock_kinematics(g.model, {false, 0, 0, 0, 0, 20, 10}, 2000, 2);
}

// A trt configuration of our own: the pins set in a HAL file (setp, and sets on a signal),
// the tool offset netted to motion.tooloffset.z, no sparm (type 0 is TCP: world=tcp).
fs::path trt_configuration(const std::string& name, const Trt& p) {
  const std::string module = p.bc ? "xyzbc-trt-kins" : "xyzac-trt-kins";
  const char tilt = p.bc ? 'B' : 'A';
  const fs::path dir = test::scratch_folder(name);
  std::string ini = "[EMC]\nMACHINE = random trt\n[KINS]\nKINEMATICS = " + module + "\nJOINTS = 5\n"
                    "[TRAJ]\nCOORDINATES = XYZ" + std::string(1, tilt) + "C\nLINEAR_UNITS = mm\nANGULAR_UNITS = deg\n"
                    "[HAL]\nHALFILE = trt.hal\nHALCMD = net :tool-offset motion.tooloffset.z " + module + ".tool-offset\n";
  const double limits[5][2] = {{-300, 250}, {-200, 220}, {-350, 100}, {-120, 120}, {-36000, 36000}};
  for (int j = 0; j < 5; ++j)
    ini += "[JOINT_" + std::to_string(j) + "]\nTYPE = " + (j < 3 ? "LINEAR" : "ANGULAR") + "\nMIN_LIMIT = " +
           std::to_string(limits[j][0]) + "\nMAX_LIMIT = " + std::to_string(limits[j][1]) + "\n";
  test::write_file(dir / "trt.ini", ini);
  auto number = [](double v) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", v);
    return std::string(text);
  };
  test::write_file(dir / "trt.hal", "loadrt [KINS]KINEMATICS\n"
                                    "setp " + module + ".x-rot-point " + number(p.xr) + "\n"
                                    "setp " + module + ".y-rot-point " + number(p.yr) + "\n"
                                    "net :zr " + module + ".z-rot-point\nsets :zr " + number(p.zr) + "\n"
                                    "setp " + module + ".x-offset " + number(p.dx) + "\n"
                                    "setp " + module + ".y-offset " + number(p.dy) + "\n"
                                    "net :dz => " + module + ".z-offset\nsets :dz " + number(p.dz) + "\n");
  return dir / "trt.ini";
}

TEST(StockKinematics, RandomRotationPointsAndOffsetsMatchTheStockModules) {
  std::mt19937_64 rng(20261128);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  for (bool bc : {true, false}) {
    for (int geometry = 0; geometry < 5; ++geometry) {
      const Trt p{bc, uniform(-200, 200), uniform(-200, 200), uniform(-200, 200), uniform(-100, 100),
                  uniform(-100, 100), uniform(-100, 100)};
      SCOPED_TRACE(std::string(bc ? "xyzbc" : "xyzac") + " geometry " + std::to_string(geometry));
      const std::string name = std::string(bc ? "bc" : "ac") + std::to_string(geometry);
      const Generated g = generate(trt_configuration(name, p), name + "_machine");
      EXPECT_EQ(g.result.machine.world, "tcp");
      EXPECT_NE(g.result.patch.kinematics.find(" world=tcp"), std::string::npos);
      expect_stock_kinematics(g.model, p, 400, 100 + static_cast<unsigned>(geometry));
    }
  }
}

// The refusal init gives for a configuration: its location and message.
LoadError refusal(const fs::path& ini) {
  try {
    run_init({ini.string(), (fs::temp_directory_path() / "never_written.toml").string(), "2026-01-01"});
  } catch (const LoadError& e) {
    return e;
  }
  ADD_FAILURE() << ini << " was accepted";
  return LoadError({}, "");
}

TEST(StockKinematics, RefusesTheSamplesTheModelCannotExpress) {
  if (!test::samples_installed()) GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
  const LoadError bridgemill = refusal(test::kSampleConfigs / "bridgemill/5axis.ini");
  EXPECT_EQ(bridgemill.where().line, 98);
  EXPECT_NE(bridgemill.message().find("5axiskins is refused: its W joint moves the tool along the tool's own axis: a "
                                      "fourth linear axis; the model has three"),
            std::string::npos)
      << bridgemill.what();
  const LoadError max5 = refusal(test::kSampleConfigs / "max5/max5kins.ini");
  EXPECT_EQ(max5.where().line, 4);
  EXPECT_NE(max5.message().find("maxkins is refused: it maps joints by number"), std::string::npos) << max5.what();
  // max5triv: trivkins coordinates=xyzabc, but [TRAJ]COORDINATES = X Y Z B C (joint 3, A, is
  // a dummy joint looped back in its HAL file): not an axis of the machine.
  const LoadError triv = refusal(test::kSampleConfigs / "max5/max5triv.ini");
  EXPECT_EQ(triv.where().path, (test::kSampleConfigs / "max5/max5_base.inc").string());
  EXPECT_NE(triv.message().find("[TRAJ]COORDINATES = X Y Z B C and trivkins coordinates=xyzabc (max5triv.ini:4 "),
            std::string::npos)
      << triv.what();
  EXPECT_NE(triv.message().find("joint 3 the axis A, which the trajectory planner does not have"), std::string::npos)
      << triv.what();
}

TEST(StockKinematics, GantryKeepsEachAxisOnceWithItsFirstJointsTravel) {
  const fs::path dir = test::scratch_folder("gantry");
  std::string ini = "[KINS]\nKINEMATICS = trivkins coordinates=XYYZ kinstype=BOTH\nJOINTS = 4\n"
                    "[TRAJ]\nCOORDINATES = X Y Y Z\nLINEAR_UNITS = mm\n[HAL]\nHALFILE = g.hal\n";
  const double limits[4][2] = {{0, 400}, {0, 2000}, {-5, 2005}, {-100, 0}};
  for (int j = 0; j < 4; ++j)
    ini += "[JOINT_" + std::to_string(j) + "]\nTYPE = LINEAR\nMIN_LIMIT = " + std::to_string(limits[j][0]) +
           "\nMAX_LIMIT = " + std::to_string(limits[j][1]) + "\n";
  test::write_file(dir / "gantry.ini", ini);
  test::write_file(dir / "g.hal", "loadrt [KINS]KINEMATICS\nnet tool-length motion.tooloffset.z => gui.length\n");
  const Generated g = generate(dir / "gantry.ini", "gantry_machine");
  ASSERT_EQ(g.model.coordinates(), "xyz");
  EXPECT_EQ(g.model.axes[1].travel_min, 0.0);
  EXPECT_EQ(g.model.axes[1].travel_max, 2000.0);  // joint 1, the first Y
  EXPECT_EQ(g.model.axes[2].travel_min, -100.0);  // joint 3
  EXPECT_EQ(g.model.tool_chain, (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(g.model.workpiece_chain.empty());
  EXPECT_EQ(g.result.machine.name, "gantry");  // no [EMC]MACHINE: the file's name
  EXPECT_EQ(g.result.patch.kinematics, "volkins machine=" + g.result.machine_path + " coordinates=XYYZ");
  // motion.tooloffset.z is on tool-length already: volkins joins that signal.
  EXPECT_NE(g.result.patch.diff.find("+HALCMD = net tool-length volkins.tool-length\n"), std::string::npos)
      << g.result.patch.diff;
  // The world is the joints: identity.
  Joints q(3);
  q << 12, 345, -67;
  EXPECT_EQ(machine::nominal_forward(g.model, machine::WorldConvention::Axes, q, 0.0), q);
}

TEST(StockKinematics, TrivkinsRotaryAxesAreCarriedByTheTableWithAPlaceholderPole) {
  const fs::path dir = test::scratch_folder("xyzac_triv");
  std::string ini = "[KINS]\nKINEMATICS = trivkins coordinates=xyzac\nJOINTS = 5\n"
                    "[TRAJ]\nCOORDINATES = XYZAC\nLINEAR_UNITS = mm\nANGULAR_UNITS = degree\n[HAL]\nHALCMD = loadrt trivkins coordinates=xyzac\n";
  const double limits[5][2] = {{0, 400}, {0, 300}, {-200, 0}, {-100, 30}, {-720, 720}};
  for (int j = 0; j < 5; ++j)
    ini += "[JOINT_" + std::to_string(j) + "]\nTYPE = " + (j < 3 ? "LINEAR" : "ANGULAR") + "\nMIN_LIMIT = " +
           std::to_string(limits[j][0]) + "\nMAX_LIMIT = " + std::to_string(limits[j][1]) + "\n";
  test::write_file(dir / "m.ini", ini);
  const Generated g = generate(dir / "m.ini", "xyzac_triv_machine");
  ASSERT_EQ(g.model.coordinates(), "xyzac");
  EXPECT_EQ(g.model.workpiece_chain, (std::vector<int>{3, 4}));  // A carries C
  expect_vector(g.model.axes[3].direction, {1, 0, 0}, "A direction");
  expect_vector(g.model.axes[4].direction, {0, 0, 1}, "C direction");
  EXPECT_NE(g.result.machine_text.find("A PLACEHOLDER: trivkins does not know where the rotary axes are"),
            std::string::npos);
  ASSERT_EQ(g.result.machine.remarks.size(), 1u);
  EXPECT_NE(g.result.machine.remarks[0].find("A and C are: their pole_mm are placeholders; measure them (volcomp identify sphere)"), std::string::npos);
  // The HALCMD loading trivkins itself becomes volkins' line, written out (a HALCMD has no
  // INI references).
  EXPECT_NE(g.result.patch.diff.find("+HALCMD = loadrt volkins machine="), std::string::npos) << g.result.patch.diff;
}

}  // namespace
}  // namespace vc::init
