// `volcomp init` describes the stock kinematics exactly: the machine files it writes for
// LinuxCNC's xyzbc-trt and xyzac-trt samples (read in place) and for random rotation points
// and offsets give, in volkins' TCP world, the tool tip that LinuxCNC's xyzbc-trt-kins and
// xyzac-trt-kins compute (trtfuncs.c's equations, transcribed below independently of init),
// forward and inverse, to 1e-9 mm over 2000 random poses; the same for LinuxCNC's 5axiskins
// (its bridgemill sample and random pivot lengths, W and the tool length offset included), and
// its pivot lengths init cannot follow refused with their lines. trivkins configurations (a
// gantry with a duplicated letter) keep each axis once; modules the model cannot express are
// refused with the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <regex>

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
    return {
        std::cos(c) * std::cos(t) * u + std::sin(c) * v - std::cos(c) * std::sin(t) * w + std::cos(c) * p.dx + p.xr,
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
  if (!test::samples_installed())
    GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
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
  EXPECT_EQ(g.result.patch.kinematics,
            "volkins machine=" + g.result.machine_path + " coordinates=xyzbc sparm=identityfirst");
  EXPECT_NE(g.result.machine_text.find("x-offset = -20: xyzbc-trt.ini:65 `HALCMD = sets :x-offset     -20`"),
            std::string::npos)
      << g.result.machine_text;
  expect_stock_kinematics(g.model, {true, 0, 0, 0, -20, 0, -15}, 2000, 1);
}

TEST(StockKinematics, XyzacSampleMatchesXyzacTrtKins) {
  if (!test::samples_installed())
    GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
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
  std::string ini = "[EMC]\nMACHINE = random trt\n[KINS]\nKINEMATICS = " + module +
                    "\nJOINTS = 5\n"
                    "[TRAJ]\nCOORDINATES = XYZ" +
                    std::string(1, tilt) +
                    "C\nLINEAR_UNITS = mm\nANGULAR_UNITS = deg\n"
                    "[HAL]\nHALFILE = trt.hal\nHALCMD = net :tool-offset motion.tooloffset.z " +
                    module + ".tool-offset\n";
  const double limits[5][2] = {{-300, 250}, {-200, 220}, {-350, 100}, {-120, 120}, {-36000, 36000}};
  for (int j = 0; j < 5; ++j)
    ini += "[JOINT_" + std::to_string(j) + "]\nTYPE = " + (j < 3 ? "LINEAR" : "ANGULAR") +
           "\nMIN_LIMIT = " + std::to_string(limits[j][0]) + "\nMAX_LIMIT = " + std::to_string(limits[j][1]) + "\n";
  test::write_file(dir / "trt.ini", ini);
  auto number = [](double v) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", v);
    return std::string(text);
  };
  test::write_file(dir / "trt.hal",
                   "loadrt [KINS]KINEMATICS\n"
                   "setp " +
                       module + ".x-rot-point " + number(p.xr) +
                       "\n"
                       "setp " +
                       module + ".y-rot-point " + number(p.yr) +
                       "\n"
                       "net :zr " +
                       module + ".z-rot-point\nsets :zr " + number(p.zr) +
                       "\n"
                       "setp " +
                       module + ".x-offset " + number(p.dx) +
                       "\n"
                       "setp " +
                       module + ".y-offset " + number(p.dy) +
                       "\n"
                       "net :dz => " +
                       module + ".z-offset\nsets :dz " + number(p.dz) + "\n");
  return dir / "trt.ini";
}

TEST(StockKinematics, RandomRotationPointsAndOffsetsMatchTheStockModules) {
  std::mt19937_64 rng(20261128);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  for (bool bc : {true, false}) {
    for (int geometry = 0; geometry < 5; ++geometry) {
      const Trt p{bc,
                  uniform(-200, 200),
                  uniform(-200, 200),
                  uniform(-200, 200),
                  uniform(-100, 100),
                  uniform(-100, 100),
                  uniform(-100, 100)};
      SCOPED_TRACE(std::string(bc ? "xyzbc" : "xyzac") + " geometry " + std::to_string(geometry));
      const std::string name = std::string(bc ? "bc" : "ac") + std::to_string(geometry);
      const Generated g = generate(trt_configuration(name, p), name + "_machine");
      EXPECT_EQ(g.result.machine.world, "tcp");
      EXPECT_NE(g.result.patch.kinematics.find(" world=tcp"), std::string::npos);
      expect_stock_kinematics(g.model, p, 400, 100 + static_cast<unsigned>(geometry));
    }
  }
}

// LinuxCNC 2.9's 5axiskins.c (commit f1270d6ed7), fiveaxis_KinematicsForward and -Inverse: P
// the pivot-length pin, s2r(r, t, p) spherical to cartesian (t the azimuth, p the polar angle,
// deg). The joints and the world are x, y, z, b, c, w.
using Six = Eigen::Matrix<double, 6, 1>;

Eigen::Vector3d s2r(double r, double t, double p) {
  t *= kRad;
  p *= kRad;
  return {r * std::sin(p) * std::cos(t), r * std::sin(p) * std::sin(t), r * std::cos(p)};
}

Six five_axis_forward(double P, const Six& j) {
  const Eigen::Vector3d r = s2r(P + j[5], j[4], 180.0 - j[3]);
  Six pos;
  pos << j[0] + r.x(), j[1] + r.y(), j[2] + P + r.z(), j[3], j[4], j[5];
  return pos;
}

Six five_axis_inverse(double P, const Six& pos) {
  const Eigen::Vector3d r = s2r(P + pos[5], pos[4], 180.0 - pos[3]);
  Six j;
  j << pos[0] - r.x(), pos[1] - r.y(), pos[2] - P - r.z(), pos[3], pos[4], pos[5];
  return j;
}

// The sum2 that drives pivot-length, as LinuxCNC's sum2.comp: out = in0 * gain0 + in1 * gain1 +
// offset, one input motion.tooloffset.z (gain 1), the other the constant `pivot`.
struct PivotSum {
  double pivot = 250.0, gain = 1.0, offset = 0.0;  // of the constant input
  double out(double tool_offset) const { return pivot * gain + tool_offset * 1.0 + offset; }
};

// volkins' TCP world against 5axiskins, both ways: LinuxCNC's world Z is the core's plus the
// tool length offset (G43), the core's nominal tool is the offset plus W (tool_axis_coordinate).
// Returns the largest difference (mm, deg).
double expect_five_axis_kinematics(const machine::Model& model, const PivotSum& sum, int poses, unsigned seed) {
  EXPECT_EQ(model.coordinates(), "xyzbc");
  EXPECT_EQ(model.tool_axis_coordinate, 'W');
  if (model.coordinates() != "xyzbc") return INFINITY;
  std::mt19937_64 rng(seed);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  double worst = 0.0;
  for (int i = 0; i < poses; ++i) {
    Six j;
    for (int k = 0; k < 5; ++k) j[k] = uniform(model.axes[k].travel_min, model.axes[k].travel_max);
    j[5] = uniform(-100.0, 500.0);
    const double offset = uniform(0.0, 150.0);
    const double P = sum.out(offset);
    const double L = model.correction_length(offset) + j[5];  // the nominal TCP tool: L + w

    const Six stock_world = five_axis_forward(P, j);
    const Joints q = j.head<5>();
    const Joints world = machine::nominal_forward(model, machine::WorldConvention::Tcp, q, L);
    for (int k = 0; k < 3; ++k) {
      const double linuxcnc = world[k] + (k == 2 ? offset : 0.0);
      EXPECT_NEAR(linuxcnc, stock_world[k], 1e-9) << "forward, pose " << i << " axis " << k;
      worst = std::max(worst, std::abs(linuxcnc - stock_world[k]));
    }
    EXPECT_EQ(world[3], j[3]);
    EXPECT_EQ(world[4], j[4]);

    const Six stock_joints = five_axis_inverse(P, stock_world);
    Joints tip = stock_world.head<5>();
    tip[2] -= offset;  // the core's TCP world: without G43's Z
    Joints joints;
    EXPECT_EQ(machine::nominal_inverse(model, machine::WorldConvention::Tcp, tip, L, joints), machine::Status::Ok);
    for (int k = 0; k < 5; ++k) {
      EXPECT_NEAR(joints[k], stock_joints[k], 1e-9) << "inverse, pose " << i << " joint " << k;
      EXPECT_NEAR(joints[k], j[k], 1e-9) << "round trip, pose " << i;
      worst = std::max(worst, std::abs(joints[k] - stock_joints[k]));
    }
  }
  return worst;
}

void record_largest_difference(double worst) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", worst);
  ::testing::Test::RecordProperty("largest_difference_mm", text);
}

TEST(StockKinematics, BridgemillSampleMatches5axiskins) {
  if (!test::samples_installed())
    GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
  const Generated g = generate(test::kSampleConfigs / "bridgemill/5axis.ini", "bridgemill_sample");
  // pivot-length = pivotsum.out = 5axisgui.pivot_len (250, its default) + motion.tooloffset.z.
  expect_vector(g.model.axes[4].pole_mm, {0, 0, 250}, "C pole");
  expect_vector(g.model.axes[3].pole_mm, {0, 0, 0}, "B pole");
  expect_vector(g.model.axes[3].direction, {0, -1, 0}, "B direction");
  expect_vector(g.model.axes[4].direction, {0, 0, 1}, "C direction");
  expect_vector(g.model.spindle.gauge_point_mm, {0, 0, -250}, "gauge point");
  EXPECT_EQ(g.model.tool_chain, (std::vector<int>{0, 1, 2, 4, 3}));  // X Y Z C B
  EXPECT_TRUE(g.model.workpiece_chain.empty());
  EXPECT_EQ(g.model.tool_length_reference_mm, 0.0);
  EXPECT_EQ(g.model.axes[3].travel_min, -120.0);  // [JOINT_3]
  EXPECT_EQ(g.model.axes[1].travel_max, 500.0);   // [JOINT_1], the first Y
  EXPECT_EQ(g.result.machine.coordinates, "xyzbcwy");
  EXPECT_EQ(g.result.patch.kinematics, "volkins machine=" + g.result.machine_path + " coordinates=xyzbcwy world=tcp");
  for (const char* origin :
       {"5axisgui.hal:29 `net :pivot-len => 5axiskins.pivot-length`",
        "5axisgui.hal:28 `net :pivot-len <= pivotsum.out`", "5axisgui.hal:18 `loadrt sum2 names=pivotsum`",
        "5axisgui.hal:25 `net :tool-len => pivotsum.in1`",
        "in0 = 250: 5axisgui.pivot_len (5axisgui.hal:22 `net :gui-pivot-len => pivotsum.in0`), "
        "5axisgui's pivot_len: 5axisgui.hal:1 `loadusr -W 5axisgui`, no pivot_len=: 5axisgui's "
        "default 250",
        "tool_axis_coordinate = \"W\"        # joint 5 of 5axiskins coordinates=xyzbcwy (5axis.ini:98 "})
    EXPECT_NE(g.result.machine_text.find(origin), std::string::npos) << origin << "\n" << g.result.machine_text;
  record_largest_difference(expect_five_axis_kinematics(g.model, {}, 2000, 3));
}

// A 5axiskins configuration of our own: the pivot a sum2 of motion.tooloffset.z (input `tool`)
// and a constant (the other input, by setp or sets), with a gain and an offset.
struct FiveAxisGeometry {
  PivotSum sum;
  int tool = 1;       // the input on motion.tooloffset.z
  bool names = true;  // loadrt sum2 names=..., else count=2 (sum2.1)
  bool sets = false;  // the constant by sets on its signal, else setp
  bool identity_first = false;
};

fs::path five_axis_configuration(const std::string& name, const FiveAxisGeometry& p,
                                 const std::string& extra_hal = "") {
  const fs::path dir = test::scratch_folder(name);
  std::string ini = std::string("[EMC]\nMACHINE = random 5axis\n[KINS]\nKINEMATICS = 5axiskins") +
                    (p.identity_first ? " sparm=identityfirst" : "") +
                    "\nJOINTS = 6\n[TRAJ]\nCOORDINATES = XYZBCW\nLINEAR_UNITS = mm\nANGULAR_UNITS = deg\n"
                    "[HAL]\nHALFILE = fiveaxis.hal\n";
  const double limits[6][2] = {{-400, 300}, {-250, 350}, {-450, 80}, {-110, 95}, {-36000, 36000}, {-100, 500}};
  for (int j = 0; j < 6; ++j)
    ini += "[JOINT_" + std::to_string(j) + "]\nTYPE = " + (j < 3 || j == 5 ? "LINEAR" : "ANGULAR") +
           "\nMIN_LIMIT = " + std::to_string(limits[j][0]) + "\nMAX_LIMIT = " + std::to_string(limits[j][1]) + "\n";
  test::write_file(dir / "fiveaxis.ini", ini);
  auto number = [](double v) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", v);
    return std::string(text);
  };
  const std::string s = p.names ? "pivot" : "sum2.1";
  const std::string tool = s + ".in" + std::to_string(p.tool), constant = s + ".in" + std::to_string(1 - p.tool);
  std::string hal =
      "loadrt [KINS]KINEMATICS\n" + std::string(p.names ? "loadrt sum2 names=other,pivot\n" : "loadrt sum2 count=2\n") +
      "addf " + s +
      " servo-thread\n"
      "net :tool-length motion.tooloffset.z => " +
      tool + "\n" +
      (p.sets ? "net :mechanical-pivot => " + constant + "\nsets :mechanical-pivot " + number(p.sum.pivot) + "\n"
              : "setp " + constant + " " + number(p.sum.pivot) + "\n") +
      "setp " + s + ".gain" + std::to_string(1 - p.tool) + " " + number(p.sum.gain) +
      "\n"
      "setp " +
      s + ".offset " + number(p.sum.offset) +
      "\n"
      "net :pivot-length " +
      s + ".out => 5axiskins.pivot-length\n" + extra_hal;
  test::write_file(dir / "fiveaxis.hal", hal);
  return dir / "fiveaxis.ini";
}

TEST(StockKinematics, RandomPivotLengthsMatch5axiskins) {
  std::mt19937_64 rng(20261129);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  double worst = 0.0;
  for (int geometry = 0; geometry < 5; ++geometry) {
    FiveAxisGeometry p;
    p.sum = {uniform(50, 400), uniform(0.5, 2.0), uniform(-50, 50)};
    p.tool = geometry % 2;
    p.names = geometry % 2 == 0;
    p.sets = geometry >= 2;
    p.identity_first = geometry == 4;
    SCOPED_TRACE("5axiskins geometry " + std::to_string(geometry));
    const std::string name = "fiveaxis" + std::to_string(geometry);
    const Generated g = generate(five_axis_configuration(name, p), name + "_machine");
    const double pm = p.sum.pivot * p.sum.gain + p.sum.offset;
    EXPECT_NEAR(g.model.axes[4].pole_mm.z(), pm, 1e-12);
    EXPECT_NEAR(g.model.spindle.gauge_point_mm.z(), -pm, 1e-12);
    EXPECT_EQ(g.result.machine.world, p.identity_first ? "" : "tcp");
    EXPECT_EQ(g.result.patch.kinematics, "volkins machine=" + g.result.machine_path + " coordinates=xyzbcw" +
                                             (p.identity_first ? " sparm=identityfirst" : " world=tcp"));
    worst = std::max(worst, expect_five_axis_kinematics(g.model, p.sum, 2000, 200 + static_cast<unsigned>(geometry)));
  }
  record_largest_difference(worst);
}

TEST(StockKinematics, TakesThePivotFrom5axisguisArgument) {
  // The bridgemill way, with pivot_len= on the loadusr line (-Wn: halcmd's option with a name).
  const fs::path ini = five_axis_configuration("fiveaxis_gui", {});
  test::write_file(
      ini.parent_path() / "fiveaxis.hal",
      "loadrt [KINS]KINEMATICS\nloadusr -Wn 5axisgui 5axisgui pivot_len=312.5\nloadrt sum2\n"
      "net :gui-pivot-len <= 5axisgui.pivot_len\nnet :gui-pivot-len => sum2.0.in0\nsetp sum2.0.gain0 2\n"
      "net :tool-len <= motion.tooloffset.z => sum2.0.in1\nnet :pivot-len sum2.0.out 5axiskins.pivot-length\n");
  const Generated g = generate(ini, "fiveaxis_gui_machine");
  expect_vector(g.model.axes[4].pole_mm, {0, 0, 625}, "C pole");  // 2 x 312.5
  EXPECT_NE(g.result.machine_text.find(
                "in0 = 312.5: 5axisgui.pivot_len (fiveaxis.hal:5 `net :gui-pivot-len => sum2.0.in0`), "
                "5axisgui's pivot_len: fiveaxis.hal:2 `loadusr -Wn 5axisgui 5axisgui pivot_len=312.5`"),
            std::string::npos)
      << g.result.machine_text;
  record_largest_difference(expect_five_axis_kinematics(g.model, {312.5, 2.0, 0.0}, 200, 4));
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
  if (!test::samples_installed())
    GTEST_SKIP() << "LinuxCNC's sample configurations are not installed (" << test::kSampleConfigs << ")";
  // (bridgemill, 5axiskins, is accepted: BridgemillSampleMatches5axiskins.)
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

// The pivot lengths init cannot follow, and the coordinates volkins cannot pass through.
TEST(StockKinematics, Refuses5axiskinsPivotLengthsThatDoNotFollowTheToolOffset) {
  const std::string why =
      "with a pivot length that does not follow motion.tooloffset.z, G43 moves world Z only, which "
      "volkins' TCP world does not express";
  const fs::path ini = five_axis_configuration("fiveaxis_refused", {});
  const fs::path hal = ini.parent_path() / "fiveaxis.hal";
  struct Case {
    std::string hal;
    int line;  // in the HAL file; negative: in the INI (KINEMATICS)
    std::string message;
  };
  const std::string head = "loadrt [KINS]KINEMATICS\nloadrt sum2 names=pivot\n";  // lines 1, 2
  const std::vector<Case> cases{
      {head + "setp 5axiskins.pivot-length 300\n", 3, "5axiskins.pivot-length is the constant 300: " + why},
      {head + "net :p => 5axiskins.pivot-length\nsets :p 300\n", 4,
       "5axiskins.pivot-length is the constant 300 (sets on its signal :p): " + why},
      {head, -4,
       "5axiskins.pivot-length is netted nowhere in the HAL files read: it keeps 5axiskins' default 250, a "
       "constant: " +
           why},
      {head + "net :p other.out => 5axiskins.pivot-length\n", 3,
       "5axiskins.pivot-length follows other.out at run time (signal :p), which is not the out of a sum2 loaded in the "
       "HAL files read"},
      // The constant part live from another pin than 5axisgui's pivot_len.
      {head + "net :t motion.tooloffset.z => pivot.in1\nnet :c gui.pivot => pivot.in0\nnet :p pivot.out => "
              "5axiskins.pivot-length\n",
       4,
       "pivot.in0 follows gui.pivot at run time (both are on signal :c, which no sets gives a value): the pivot "
       "length's other part must be a constant"},
      // The tool offset with another gain.
      {head + "net :t motion.tooloffset.z => pivot.in1\nsetp pivot.in0 250\nsetp pivot.gain1 2\nnet :p pivot.out => "
              "5axiskins.pivot-length\n",
       5, "pivot.gain1 = 2: pivot.in1 (the tool offset) must enter the pivot length with gain 1; " + why},
      // No input on the tool offset.
      {head + "setp pivot.in0 250\nnet :p pivot.out => 5axiskins.pivot-length\n", 4,
       "5axiskins.pivot-length follows pivot.out, but neither pivot.in0 nor pivot.in1 is on the signal "
       "motion.tooloffset.z drives (it is netted nowhere); " +
           why},
      // Both.
      {head + "net :t motion.tooloffset.z => pivot.in1 pivot.in0\nnet :p pivot.out => 5axiskins.pivot-length\n", 4,
       "5axiskins.pivot-length follows pivot.out, but both pivot.in0 and pivot.in1 are on :t: the pivot length would grow "
       "by twice the tool offset"},
      // 5axisgui's pin without its loadusr.
      {head + "net :t motion.tooloffset.z => pivot.in1\nnet :g 5axisgui.pivot_len => pivot.in0\nnet :p pivot.out => "
              "5axiskins.pivot-length\n",
       4, "pivot.in0 follows 5axisgui.pivot_len, but no `loadusr 5axisgui` is in the HAL files read"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.hal);
    test::write_file(hal, c.hal);
    const LoadError e = refusal(ini);
    EXPECT_EQ(e.where().path, c.line < 0 ? ini.string() : hal.string());
    EXPECT_EQ(e.where().line, std::abs(c.line));
    EXPECT_EQ(e.message().rfind(c.message, 0), 0u) << e.what();
  }
  // A, U and V: 5axiskins passes them through one-to-one, volkins does not.
  std::string text = test::file_text(ini);
  text.replace(text.find("KINEMATICS = 5axiskins"), 22, "KINEMATICS = 5axiskins coordinates=xyzbcwu");
  text.replace(text.find("JOINTS = 6"), 10, "JOINTS = 7");
  test::write_file(ini, text);
  const LoadError u = refusal(ini);
  EXPECT_EQ(u.where().line, 4);
  EXPECT_EQ(u.message(),
            "5axiskins coordinates=xyzbcwu (fiveaxis.ini:4 `KINEMATICS = 5axiskins coordinates=xyzbcwu`) has "
            "U, which 5axiskins passes through to its joint one-to-one: volkins does not pass it through "
            "(its joints are the machine file's axes X Y Z B C and the tool-axis coordinate W); remove the "
            "joint");
  // W is required, as by 5axiskins.
  text.replace(text.find("coordinates=xyzbcwu"), 19, "coordinates=xyzbc");
  test::write_file(ini, text);
  EXPECT_NE(refusal(ini).message().find("coordinates=xyzbc lacks W, which 5axiskins requires (it needs xyzbcw)"),
            std::string::npos);
}

TEST(StockKinematics, GantryKeepsEachAxisOnceWithItsFirstJointsTravel) {
  const fs::path dir = test::scratch_folder("gantry");
  std::string ini =
      "[KINS]\nKINEMATICS = trivkins coordinates=XYYZ kinstype=BOTH\nJOINTS = 4\n"
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
  // kinstype=BOTH is volkins' own type: dropped, and said so.
  ASSERT_EQ(g.result.machine.remarks.size(), 1u);
  EXPECT_TRUE(
      std::regex_search(g.result.machine.remarks[0],
                        std::regex("^the kinematics type stays KINEMATICS_BOTH \\(.*gantry.ini:2: kinstype=BOTH\\)")))
      << g.result.machine.remarks[0];
  // motion.tooloffset.z is on tool-length already: volkins joins that signal.
  EXPECT_NE(g.result.patch.diff.find("+HALCMD = net tool-length volkins.tool-offset\n"), std::string::npos)
      << g.result.patch.diff;
  // The world is the joints: identity.
  Joints q(3);
  q << 12, 345, -67;
  EXPECT_EQ(machine::nominal_forward(g.model, machine::WorldConvention::Axes, q, 0.0), q);
}

TEST(StockKinematics, TrivkinsRotaryAxesAreCarriedByTheTableWithAPlaceholderPole) {
  const fs::path dir = test::scratch_folder("xyzac_triv");
  std::string ini =
      "[KINS]\nKINEMATICS = trivkins coordinates=xyzac\nJOINTS = 5\n"
      "[TRAJ]\nCOORDINATES = XYZAC\nLINEAR_UNITS = mm\nANGULAR_UNITS = degree\n[HAL]\nHALCMD = loadrt trivkins coordinates=xyzac\n";
  const double limits[5][2] = {{0, 400}, {0, 300}, {-200, 0}, {-100, 30}, {-720, 720}};
  for (int j = 0; j < 5; ++j)
    ini += "[JOINT_" + std::to_string(j) + "]\nTYPE = " + (j < 3 ? "LINEAR" : "ANGULAR") +
           "\nMIN_LIMIT = " + std::to_string(limits[j][0]) + "\nMAX_LIMIT = " + std::to_string(limits[j][1]) + "\n";
  test::write_file(dir / "m.ini", ini);
  const Generated g = generate(dir / "m.ini", "xyzac_triv_machine");
  ASSERT_EQ(g.model.coordinates(), "xyzac");
  EXPECT_EQ(g.model.workpiece_chain, (std::vector<int>{3, 4}));  // A carries C
  expect_vector(g.model.axes[3].direction, {1, 0, 0}, "A direction");
  expect_vector(g.model.axes[4].direction, {0, 0, 1}, "C direction");
  EXPECT_NE(g.result.machine_text.find("A PLACEHOLDER: trivkins does not know where the rotary axes are"),
            std::string::npos);
  ASSERT_EQ(g.result.machine.remarks.size(), 2u);
  EXPECT_NE(g.result.machine.remarks[0].find(
                "A and C are: their pole_mm are placeholders; measure them (volcomp identify sphere)"),
            std::string::npos);
  // trivkins without kinstype= is KINEMATICS_IDENTITY; volkins is KINEMATICS_BOTH: said, with what changes.
  EXPECT_NE(g.result.machine.remarks[1].find("the kinematics type changes from KINEMATICS_IDENTITY (no kinstype=: "
                                             "trivkins' default) to volkins' KINEMATICS_BOTH. The planned path stays "
                                             "the same"),
            std::string::npos)
      << g.result.machine.remarks[1];
  EXPECT_NE(g.result.machine_text.find("KINEMATICS_IDENTITY"), std::string::npos);
  // The HALCMD loading trivkins itself becomes volkins' line, written out (a HALCMD has no
  // INI references).
  EXPECT_NE(g.result.patch.diff.find("+HALCMD = loadrt volkins machine="), std::string::npos) << g.result.patch.diff;
}

}  // namespace
}  // namespace vc::init
