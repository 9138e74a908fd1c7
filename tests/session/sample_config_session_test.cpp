// A LinuxCNC user's own configuration retrofitted with volkins: LinuxCNC's 5-axis samples as
// installed. table-rotary-tilting's xyzbc-trt.ini and xyzac-trt.ini (table-table, switchable
// kinematics, M428/M429, the pivot on the stock module's HAL pins) and bridgemill's 5axis.ini (a
// head-head bridge mill, 5axiskins: X Y Z carry the C-B head, W moves the tool along its own axis,
// two Y joints, the pivot length from a sum2 of the mechanical length and the tool length offset),
// and table-dual-rotary's xyzab-tdr.ini (xyzab_tdr_kins: B carrying the rotary table A, the
// geometry from pyvcp sliders). `volcomp init` writes the machine file and the patch, the patch is
// applied with `patch`, and the configuration's own demo program (demos/xyzbc_switchkins.ngc:
// helices at B 20 C 45 in TCP, moves in identity, 16 switches; the xyzac one at A 20 C 45;
// 5axisgui.ngc, in the test's copy 5axisgui_short.ngc with 32 of its 128 holes drilled with W
// around a sphere, its 8 B steps, C at 90 deg steps, tool 100 with G43; for the tdr sample, whose demo reads stock pins, the test's tdr_switchkins.ngc) runs
// headless (tests/session/headless_sample.py) with the stock module and with volkins. The joints
// of both are checked against an independent transcription of the stock inverse (trtfuncs.c,
// 5axiskins.c, xyzab_tdr_kins.comp) evaluated on the recorded world commands, in each sample's
// kinematics type, through LinuxCNC's joint interpolation: the stock run validates the
// transcription, the volkins run with zero errors must give the same joints to 1e-9 mm / deg. Then
// xyzbc and the bridge mill with errors (a perturbed copy of the machine file): the module against
// the core and the real tool tip against the ideal one, as on the MC-300.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "linuxcnc_run.hpp"
#include "session_checks.hpp"
#include "vc/machine/held_rotary.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/csv.hpp"
#include "vc/trace/session_trace.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
using machine::Joints;

const fs::path kSamples = "/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis/vismach/5axis";

// xyzbc-trt-kins' inverse (LinuxCNC 2.9 trtfuncs.c, xyzbcKinematicsInverse), written out here
// from its equations, for the sample's pivot (its HALCMDs: sets :x-offset -20, sets :z-offset
// -15, rot points 0): TCP world (x y z b c, tool offset on z) to joints.
Joints xyzbc_inverse(const Joints& w, double tool_offset, double) {
  const double dx = -20, dz = -15 + tool_offset;
  const double b = w[3] * M_PI / 180.0, c = w[4] * M_PI / 180.0;
  const double px = -std::cos(b) * dx - std::sin(b) * dz + dx, pz = std::sin(b) * dx - std::cos(b) * dz + dz;
  Joints q = w;
  q[0] = std::cos(c) * std::cos(b) * w[0] - std::sin(c) * std::cos(b) * w[1] + std::sin(b) * w[2] + px;
  q[1] = std::sin(c) * w[0] + std::cos(c) * w[1];
  q[2] = -std::cos(c) * std::sin(b) * w[0] + std::sin(c) * std::sin(b) * w[1] + std::cos(b) * w[2] + pz;
  return q;
}

// xyzac-trt-kins' (xyzacKinematicsInverse), for its sample's pivot (y-offset 20, z-offset 10,
// rot points 0): TCP world (x y z a c) to joints.
Joints xyzac_inverse(const Joints& w, double tool_offset, double) {
  const double dy = 20, dz = 10 + tool_offset;
  const double a = w[3] * M_PI / 180.0, c = w[4] * M_PI / 180.0;
  Joints q = w;
  q[0] = std::cos(c) * w[0] - std::sin(c) * w[1];
  q[1] = std::sin(c) * std::cos(a) * w[0] + std::cos(c) * std::cos(a) * w[1] - std::sin(a) * w[2] - std::cos(a) * dy +
         std::sin(a) * dz + dy;
  q[2] = std::sin(c) * std::sin(a) * w[0] + std::cos(c) * std::sin(a) * w[1] + std::cos(a) * w[2] - std::sin(a) * dy -
         std::cos(a) * dz + dz;
  return q;
}

// 5axiskins' inverse (LinuxCNC 2.9 5axiskins.c, fiveaxis_KinematicsInverse), written out here
// from its equations, for the bridgemill sample's pivot length: 5axisgui's pivot_len 250 plus
// the tool length offset (its sum2 pivotsum): TCP world (x y z b c, tool offset on z) and the
// W coordinate to the joints x y z b c.
Joints bridgemill_inverse(const Joints& world, double tool_offset, double w) {
  const double pivot = 250 + tool_offset, r = pivot + w;
  const double t = world[4] * M_PI / 180.0, p = (180.0 - world[3]) * M_PI / 180.0;  // s2r(r, c, 180 - b)
  Joints q = world;
  q[0] = world[0] - r * std::sin(p) * std::cos(t);
  q[1] = world[1] - r * std::sin(p) * std::sin(t);
  q[2] = world[2] - pivot - r * std::cos(p);
  return q;
}

// xyzab_tdr_kins' inverse of type 1 (LinuxCNC 2.9 xyzab_tdr_kins.comp, kinematicsInverse),
// written out here from its equations, for the xyzab-tdr sample's geometry (its pyvcp sliders'
// start values: x/y/z-rot-point -50, -50, -100, x-offset -20, z-offset -10): TCP world (x y z a
// b, tool offset on z) to joints.
Joints tdr_inverse(const Joints& w, double tool_offset, double) {
  const double xr = -50, yr = -50, zr = -100, dx = -20, dz = -10, dt = tool_offset;
  const double sa = std::sin(w[3] * M_PI / 180.0), ca = std::cos(w[3] * M_PI / 180.0);
  const double sb = std::sin(w[4] * M_PI / 180.0), cb = std::cos(w[4] * M_PI / 180.0);
  const double qx = w[0] - xr - dx, qy = w[1] - yr, qz = w[2] - zr - dz - dt;
  Joints q = w;
  q[0] = cb * qx + sa * sb * qy - ca * sb * qz + cb * dx - sb * dz + xr;
  q[1] = ca * qy + sa * qz + yr;
  q[2] = sb * qx - sa * cb * qy + ca * cb * qz + sb * dx + cb * dz + zr + dt;
  return q;
}

// trivkins' inverse: the joints are the world.
Joints trivkins_inverse(const Joints& w, double, double) { return w; }

// A sample configuration and its demo program.
struct Sample {
  fs::path folder;
  std::string ini, program, machine;
  Joints (*stock_tcp_inverse)(const Joints& world, double tool_offset, double tool_axis);
  std::string headless_options;  // headless_sample.py's: the TCP kinematics type, values of GUI pins
  std::size_t min_switches;      // kinematics switches the demo makes
  std::size_t min_tcp = 10000;   // samples in the TCP type
  // The test's own program (copied into the run, `program` its name) where the sample's cannot
  // run with volkins, and headless options of the stock run alone (signals its pyvcp sliders drove).
  fs::path own_program;
  std::string stock_options;
  double mm_per_unit = 1.0;  // LinuxCNC's length unit, in mm: the trace is in it
};
const Sample kXyzbc{kSamples / "table-rotary-tilting",
                    "xyzbc-trt.ini",
                    "demos/xyzbc_switchkins.ngc",
                    "xyzbc-trt.toml",
                    xyzbc_inverse,
                    "",
                    8,
                    10000,
                    {},
                    ""};
const Sample kXyzac{kSamples / "table-rotary-tilting",
                    "xyzac-trt.ini",
                    "demos/xyzac_switchkins.ngc",
                    "xyzac-trt.toml",
                    xyzac_inverse,
                    "",
                    8,
                    10000,
                    {},
                    ""};
// Its kinematics type 0 is 5axiskins (no sparm=identityfirst); the vismach model 5axisgui, which
// needs X, gave the pivot's mechanical length (its default pivot_len): the headless copy sets it.
// trivkins samples, with programs of the test's own. ja_tests/xyzb_locking_indexer: inches, B a
// locking indexer without limits (a continuous rotary table; the program moves B alone, as LinuxCNC
// requires of an indexer). wrapped_rotary: A a wrapped rotary table without limits, turned with
// X, Y, Z and across 0/360.
const fs::path kAxisSamples = "/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis";
const Sample kXyzbInch{kAxisSamples / "ja_tests/xyzb_locking_indexer",
                       "xyzb.ini",
                       "xyzb_inch.ngc",
                       "xyzb.toml",
                       trivkins_inverse,
                       " --bit-column b_is_unlocked=B-is-unlocked --bit-column b_held=volkins.joint.3.held",
                       0,
                       0,
                       test::source_path("tests/session/programs/xyzb_inch.ngc"),
                       "",
                       25.4};
const Sample kWrappedRotary{kAxisSamples / "wrapped_rotary",
                            "wrapped_rotary.ini",
                            "xyza_wrapped.ngc",
                            "wrapped_rotary.toml",
                            trivkins_inverse,
                            "",
                            0,
                            0,
                            test::source_path("tests/session/programs/xyza_wrapped.ngc"),
                            ""};
// Its demo program with a quarter of its drillings (the same B steps, C at 90 deg steps).
const Sample kBridgemill{kSamples / "bridgemill",
                         "5axis.ini",
                         "5axisgui_short.ngc",
                         "5axis.toml",
                         bridgemill_inverse,
                         " --tcp-type 0 --sets :gui-pivot-len=250",
                         0,
                         10000,
                         test::source_path("tests/session/programs/5axisgui_short.ngc"),
                         ""};
// xyzab_tdr_kins: type 0 the identity, type 1 TCP. Headless, its pyvcp sliders are gone: the
// stock run gets their start values on their signals (the patched one has no stock pin on them).
const Sample kTdr{kSamples / "table-dual-rotary",
                  "xyzab-tdr.ini",
                  "tdr_switchkins.ngc",
                  "xyzab-tdr.toml",
                  tdr_inverse,
                  "",
                  4,
                  5000,
                  test::source_path("tests/session/programs/tdr_switchkins.ngc"),
                  " --sets :x-rot-point=-50 --sets :y-rot-point=-50 --sets :z-rot-point=-100"
                  " --sets :x-offset=-20 --sets :z-offset=-10"};

struct StockComparison {
  double largest = 0;  // joints against the stock kinematics (mm or deg)
  std::size_t tcp = 0, switches = 0;
};

// The recorded joints against LinuxCNC's interpolation of the stock inverse of the recorded
// commands (identity where the trace's tcp column is 0).
StockComparison compare_with_stock(const Sample& sample, const trace::SessionTrace& t) {
  StockComparison out;
  std::vector<Joints> p(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    const bool tcp = t.convention[k] == machine::WorldConvention::Tcp;
    const double tool_axis = t.tool_axis_mm.empty() ? 0.0 : t.tool_axis_mm[k];
    p[k] = tcp ? sample.stock_tcp_inverse(t.world[k], t.tool_offset_mm[k == 0 ? 0 : k - 1], tool_axis) : t.world[k];
    out.tcp += tcp;
    out.switches += k > 0 && t.convention[k] != t.convention[k - 1];
  }
  for (std::size_t n = 3; n < t.size(); ++n)
    out.largest = std::max(out.largest, (t.joints[n] - trace::interpolated(p, n)).cwiseAbs().maxCoeff());
  return out;
}

// The session ran volkins, with the correction applied in full (the driver waits for its ramp).
void expect_volkins_applied(const trace::SessionTrace& t) {
  ASSERT_GT(t.size(), 10000u);
  EXPECT_EQ(std::count(t.gain.begin(), t.gain.end(), 1.0), static_cast<long>(t.size())) << "volkins.gain is not 1";
}

class SampleConfig : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kSamples)) GTEST_SKIP() << "LinuxCNC's sample configurations are not installed: " << kSamples;
  }

  // A fresh run folder `dir` with a copy of the sample as the user has it (`user`), retrofitted:
  // `volcomp init` on it and its patch applied with patch(1).
  struct Retrofitted {
    fs::path dir, user;
  };
  static Retrofitted retrofitted(const Sample& sample, const std::string& name) {
    const fs::path dir = test::run_folder(name);
    const fs::path user = dir / "user";
    fs::copy(sample.folder, user, fs::copy_options::recursive);
    retrofit(sample, dir, user);
    return {dir, user};
  }

  static void retrofit(const Sample& sample, const fs::path& dir, const fs::path& user) {
    const test::CommandResult init =
        test::run_in(dir, std::string(VC_VOLCOMP) + " init " + (user / sample.ini).string() + " -o " +
                              (user / sample.machine).string() + " --patch " + (dir / "volkins.patch").string());
    ASSERT_EQ(init.exit_code, 0) << init.out;
    const test::CommandResult patch =
        test::run_in(dir, "patch -p1 -d " + user.string() + " -i " + (dir / "volkins.patch").string());
    ASSERT_EQ(patch.exit_code, 0) << patch.out;
    ASSERT_NE(patch.out.find("patching file"), std::string::npos) << patch.out;
  }

  // The configuration made headless in dir/run (the `extra` files copied into it, over its own),
  // run; its trace, read for `model`.
  static trace::SessionTrace run(const Sample& sample, const fs::path& dir, const fs::path& config,
                                 const machine::Model& model, std::vector<fs::path> extra = {},
                                 const std::string& options = "") {
    const fs::path run_dir = dir / "run";
    const test::CommandResult h =
        test::run_in(dir, "python3 " + test::source_path("tests/session/headless_sample.py") + " " + config.string() +
                              " " + sample.ini + " " + run_dir.string() + " --program " + sample.program +
                              sample.headless_options + options);
    EXPECT_EQ(h.exit_code, 0) << h.out;
    if (!sample.own_program.empty()) extra.push_back(sample.own_program);
    for (const fs::path& f : extra) {
      fs::copy_file(f, run_dir / f.filename(), fs::copy_options::overwrite_existing);
      fs::permissions(run_dir / f.filename(), fs::perms::all);
    }
    const test::CommandResult r = test::run_in(run_dir, "linuxcnc " + sample.ini, 900);
    std::ifstream result(run_dir / "result.txt");
    std::string first;
    std::getline(result, first);
    EXPECT_EQ(first.rfind("ok", 0), 0u) << "session: " << first << "\n" << r.out;
    if (first.rfind("ok", 0) != 0) throw std::runtime_error("the session did not run cleanly");
    // An inch configuration's trace is in inches: the reader takes it to mm, as `volcomp trace --ini` does.
    const trace::TraceLayout layout = sample.mm_per_unit != 1.0
                                          ? trace::trace_layout(model, model.coordinates(), sample.mm_per_unit)
                                          : trace::TraceLayout{};
    return trace::read_session_trace((run_dir / "trace.csv").string(), model, layout);
  }

  // The stock module's session: the transcription must be its inverse. The trace is read for
  // init's machine file (the sample's axes).
  static void expect_stock_transcribed(const Sample& sample, const std::string& name) {
    const auto [dir, user] = retrofitted(sample, name);
    const machine::Model model = machine::load_machine((user / sample.machine).string());
    const trace::SessionTrace t = run(sample, dir, sample.folder, model, {}, sample.stock_options);
    const StockComparison c = compare_with_stock(sample, t);
    // The same equations; the compilers may round a product differently (fused multiply-add).
    EXPECT_LT(c.largest, 1e-12) << "the transcription is not LinuxCNC's " << sample.ini;
    EXPECT_EQ(std::count(t.gain.begin(), t.gain.end(), 0.0), static_cast<long>(t.size())) << "volkins was loaded";
    EXPECT_GE(c.switches, sample.min_switches);
    EXPECT_GE(c.tcp, sample.min_tcp);
    std::cout << sample.ini << " stock: " << t.size() << " samples, " << c.tcp << " in TCP, " << c.switches
              << " switches; joints against the transcription: " << c.largest << "\n";
  }

  // Retrofitted, zero errors: the stock module's joints.
  static trace::SessionTrace expect_stock_joints(const Sample& sample, const std::string& name) {
    const auto [dir, user] = retrofitted(sample, name);
    const machine::Model model = machine::load_machine((user / sample.machine).string());
    const trace::SessionTrace t = run(sample, dir, user, model);
    expect_volkins_applied(t);
    const StockComparison c = compare_with_stock(sample, t);
    EXPECT_LT(c.largest, 1e-9) << "volkins' joints differ from the stock module's";
    EXPECT_GE(c.switches, sample.min_switches);
    EXPECT_GE(c.tcp, sample.min_tcp);
    const trace::TraceSummary s = trace::check_trace(model, machine::WorldConvention::Axes, t);
    EXPECT_LT(test::extremes(s).mismatch, 1e-9);
    std::cout << sample.ini << " volkins, zero errors: " << t.size() << " samples, " << c.tcp << " in TCP, "
              << c.switches << " switches; joints against the stock module: max " << c.largest << "\n";
    return t;
  }

  // Retrofitted, then the machine file perturbed (volcomp perturb with `locations` and a table on
  // X): the tool is corrected along the demo program as on the MC-300.
  static trace::SessionTrace expect_corrected(const Sample& sample, const std::string& name,
                                              const std::string& locations) {
    const auto [model, t] = run_perturbed(sample, name, locations);
    const trace::TraceSummary s = trace::check_trace(model, machine::WorldConvention::Axes, t);
    int rotaries = 0;
    for (const machine::Axis& axis : model.axes) rotaries += axis.type == machine::AxisType::Rotary;
    test::expect_compensated(s, rotaries, "sample " + sample.ini + " with errors");
    expect_uncorrected_error(model, t);
    return t;
  }

  // What the correction removed: the model's error along the path (no tool length offset).
  static void expect_uncorrected_error(const machine::Model& model, const trace::SessionTrace& t) {
    double uncorrected = 0.0;
    for (const Joints& q : t.joints)
      uncorrected = std::max(uncorrected, machine::volumetric_error(model, q, 0.0).position_mm.norm());
    EXPECT_GT(uncorrected, 0.005);
    std::cout << "the same path uncompensated: tool tip error up to " << uncorrected * 1e3 << " um\n";
  }

  // Retrofitted, the machine file perturbed (volcomp perturb with `locations` and a table on X),
  // run: the perturbed file and the trace.
  struct PerturbedRun {
    machine::Model model;
    trace::SessionTrace trace;
  };
  static PerturbedRun run_perturbed(const Sample& sample, const std::string& name, const std::string& locations) {
    const auto [dir, user] = retrofitted(sample, name);
    std::ofstream table(dir / "x_errors.csv");
    table
        << "x[mm],EXX[um],EYX[um],EZX[um],EAX[arcsec],EBX[arcsec],ECX[arcsec]\n"
           "-200,-6,2,-1,1.5,-2,1\n-100,-2,3,0,2,-1,0.5\n0,0,2,1,1,0,0\n100,3,0,1,-0.5,1.5,-0.5\n200,8,-2,0,-2,2.5,-1\n";
    table.close();
    const test::CommandResult perturb = test::run_in(
        dir, std::string(VC_VOLCOMP) + " perturb " + (user / sample.machine).string() + " -o " +
                 (dir / "measured").string() + " " + locations + " --add-table " + (dir / "x_errors.csv").string());
    EXPECT_EQ(perturb.exit_code, 0) << perturb.out;
    const fs::path measured = dir / "measured" / sample.machine;
    const machine::Model model = machine::load_machine(measured.string());
    trace::SessionTrace t = run(sample, dir, user, model, {measured, dir / "measured/x_errors.csv"});
    expect_volkins_applied(t);
    return {model, std::move(t)};
  }

  // The bridge mill's joints beyond the model's (x y z b c): joint 5 is W's (volkins passes the
  // world's W through, LinuxCNC interpolates it), joint 6 the gantry's second Y (joint 1's command).
  static void expect_tool_axis_and_gantry_joints(const trace::SessionTrace& t) {
    const std::vector<tables::CsvRow> rows = tables::read_csv_rows(t.path, "session trace");
    const auto column = [&](const std::string& name) {
      const auto& h = rows.front().cells;
      const auto it = std::find_if(h.begin(), h.end(), [&](const tables::CsvCell& c) { return c.text == name; });
      EXPECT_NE(it, h.end()) << name;
      std::vector<double> v;
      for (std::size_t r = 1; r < rows.size(); ++r) v.push_back(std::stod(rows[r].cells[it - h.begin()].text));
      return v;
    };
    const std::vector<double> w = column("w"), j1 = column("j1"), j5 = column("j5"), j6 = column("j6");
    double tool_axis = 0, gantry = 0, drilled = 0;
    for (std::size_t n = 3; n < w.size(); ++n) {
      tool_axis = std::max(tool_axis, std::abs(j5[n] - (w[n - 3] + 4 * w[n - 2] + w[n - 1]) / 6));
      gantry = std::max(gantry, std::abs(j6[n] - j1[n]));
      drilled = std::min(drilled, w[n]);
    }
    EXPECT_LT(tool_axis, 1e-12) << "joint 5 is not the W coordinate";
    EXPECT_EQ(gantry, 0.0) << "the two Y joints differ";
    EXPECT_LT(drilled, -9.0) << "the demo did not drill with W";
    std::cout << "W joint against the W coordinate: " << tool_axis << "; the two Y joints differ by " << gantry
              << "; W down to " << drilled << " mm\n";
  }
};

TEST_F(SampleConfig, XyzbcStockKinematicsAreTheTranscribedOnes) {
  expect_stock_transcribed(kXyzbc, "sample_xyzbc_stock");
}

TEST_F(SampleConfig, XyzbcRetrofittedWithZeroErrorsVolkinsGivesTheStockJoints) {
  expect_stock_joints(kXyzbc, "sample_xyzbc_volkins");
}

TEST_F(SampleConfig, XyzacStockKinematicsAreTheTranscribedOnes) {
  expect_stock_transcribed(kXyzac, "sample_xyzac_stock");
}

TEST_F(SampleConfig, XyzacRetrofittedWithZeroErrorsVolkinsGivesTheStockJoints) {
  expect_stock_joints(kXyzac, "sample_xyzac_volkins");
}

TEST_F(SampleConfig, XyzbcRetrofittedWithErrorsVolkinsPutsTheRealToolOnTheCommandedPose) {
  // The true machine: location errors of every kind and a table on X.
  expect_corrected(kXyzbc, "sample_xyzbc_errors",
                   "--location EX0C=15um --location EY0C=-10um --location EA0C=-6arcsec --location EC0B=8arcsec"
                   " --location EC0Y=-5arcsec --location EB0Z=5arcsec");
}

TEST_F(SampleConfig, TdrStockKinematicsAreTheTranscribedOnes) { expect_stock_transcribed(kTdr, "sample_tdr_stock"); }

TEST_F(SampleConfig, TdrRetrofittedWithZeroErrorsVolkinsGivesTheStockJoints) {
  expect_stock_joints(kTdr, "sample_tdr_volkins");
}

TEST_F(SampleConfig, BridgemillStockKinematicsAreTheTranscribedOnes) {
  expect_stock_transcribed(kBridgemill, "sample_bridgemill_stock");
}

TEST_F(SampleConfig, BridgemillRetrofittedWithZeroErrorsVolkinsGivesTheStockJoints) {
  const trace::SessionTrace t = expect_stock_joints(kBridgemill, "sample_bridgemill_volkins");
  expect_tool_axis_and_gantry_joints(t);
}

TEST_F(SampleConfig, BridgemillRetrofittedWithErrorsVolkinsPutsTheRealToolOnTheCommandedPose) {
  // The head's errors: the C line's position and tilt (in Z's frame), the B line's (in C's),
  // two squarenesses, and the table on X.
  const trace::SessionTrace t =
      expect_corrected(kBridgemill, "sample_bridgemill_errors",
                       "--location EX0C=12um --location EY0C=-8um --location EA0C=5arcsec --location EB0C=-4arcsec"
                       " --location EX0B=10um --location EZ0B=-6um --location EA0B=6arcsec --location EC0B=-5arcsec"
                       " --location EC0Y=-5arcsec"
                       " --location EB0Z=5arcsec");
  expect_tool_axis_and_gantry_joints(t);
}

// An inch configuration: volkins with units=inch gives trivkins' joints (in inches) with zero
// errors, and with errors puts the real tool on the commanded point (the trace taken to mm).
TEST_F(SampleConfig, InchXyzbRetrofittedWithZeroErrorsVolkinsGivesTheStockJoints) {
  expect_stock_joints(kXyzbInch, "sample_xyzb_inch_volkins");
}

// The sample's B is a locking indexer, and init netted volkins to its clamp (B-unlock,
// B-is-unlocked): while clamped, B keeps its correction and X, Y, Z put the tip on the point for
// it; released, B follows its free correction again. The table on X tilts B's axis (EBX) along X,
// so the free correction of B changes as X moves: a clamped B that followed it would move.
TEST_F(SampleConfig, InchXyzbRetrofittedWithErrorsHoldsTheClampedIndexerAndPutsTheRealToolOnThePoint) {
  const auto [model, t] = run_perturbed(kXyzbInch, "sample_xyzb_inch_errors",
                                        "--location EC0Y=-8arcsec --location EB0Z=6arcsec --location EA0Z=-5arcsec");
  const int b = model.joint_of('B');
  const std::vector<double> unlocked = test::trace_column(t.path, "b_is_unlocked");
  const std::vector<double> held = test::trace_column(t.path, "b_held");
  ASSERT_EQ(unlocked.size(), t.size());
  // The last five samples clamped (or, for `free`, B's correction not held) and the commanded B
  // still as long.
  const auto steady = [&](std::size_t n, const std::vector<double>& flag, double value, bool b_still) {
    if (n < 4) return false;
    for (std::size_t k = n - 4; k <= n; ++k)
      if (flag[k] != value || (b_still && t.world[k][b] != t.world[n][b])) return false;
    return true;
  };
  std::size_t releases = 0, clamped = 0, free = 0;
  double moved = 0, mismatch_free = 0, tip = 0, held_joints = 0, direction = 0;
  for (std::size_t n = 1; n < t.size(); ++n) releases += unlocked[n] == 1.0 && unlocked[n - 1] == 0.0;
  const trace::TraceSummary s = trace::check_trace(model, machine::WorldConvention::Axes, t);
  for (const trace::SampleCheck& check : s.samples) {
    const std::size_t n = check.sample;
    tip = std::max(tip, check.tip_error_mm.norm());
    if (steady(n, held, 0.0, false)) {  // free: the module is the core's free correction
      ++free;
      mismatch_free = std::max(mismatch_free, check.module_mismatch);
    }
    if (!steady(n, unlocked, 0.0, true)) continue;
    ++clamped;
    moved = std::max(moved, std::abs(t.joints[n][b] - t.joints[n - 1][b]));
    direction = std::max(direction, check.direction_error_rad);
    // At rest (the command still for five cycles), the joints are the core's for the held B.
    bool rest = true;
    for (std::size_t k = n - 4; k < n; ++k) rest &= t.world[k] == t.world[n];
    if (!rest) continue;
    machine::HeldRotary holding;
    holding.offset_deg[static_cast<std::size_t>(b)] = t.joints[n][b] - t.world[n][b];
    holding.release[static_cast<std::size_t>(b)] = 0.0;
    const machine::Correction core = machine::correct_held(model, model.reference_conditions(), t.world[n],
                                                           t.correction_length_mm[n], 1.0, holding, t.joints[n]);
    ASSERT_EQ(core.status, machine::Status::Ok) << n;
    held_joints = std::max(held_joints, (core.joints - t.joints[n]).cwiseAbs().maxCoeff());
  }
  EXPECT_GE(releases, 3u) << "the program's three indexing moves";
  EXPECT_GT(clamped, t.size() / 2);
  EXPECT_GT(free, 1000u);
  EXPECT_EQ(moved, 0.0) << "the clamped indexer's joint moved";
  EXPECT_LT(held_joints, 1e-9) << "the joints at rest against the core's for the held B";
  EXPECT_LT(mismatch_free, 1e-9) << "the joints against the core's free correction where B is not held";
  EXPECT_LT(tip, 1e-4) << "the tool tip after LinuxCNC's interpolation";
  EXPECT_GT(direction, 1e-7) << "a held B leaves the tilt of its axis along X";
  std::cout << "xyzb, B a locking indexer: " << releases << " releases, " << clamped << " clamped samples (B moved "
            << moved << " deg), " << free << " free; joints at rest against the held core " << held_joints
            << ", free against the core " << mismatch_free << "; tool tip max " << tip * 1e3
            << " um; direction error left while clamped up to " << direction * 1e6 << " urad\n";
  expect_uncorrected_error(model, t);
}

// A rotary table without stops: its travel one turn in the machine file, the joint past 360.
TEST_F(SampleConfig, ContinuousRotaryRetrofittedWithZeroErrorsVolkinsGivesTheStockJoints) {
  expect_stock_joints(kWrappedRotary, "sample_wrapped_rotary_volkins");
}

TEST_F(SampleConfig, ContinuousRotaryRetrofittedWithErrorsVolkinsPutsTheRealToolOnTheCommandedPoint) {
  expect_corrected(kWrappedRotary, "sample_wrapped_rotary_errors",
                   "--location EC0Y=-8arcsec --location EB0Z=6arcsec --location EY0A=20um --location EB0A=7arcsec");
}

}  // namespace
}  // namespace vc
