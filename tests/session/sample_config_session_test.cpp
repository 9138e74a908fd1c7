// A LinuxCNC user's own configuration retrofitted with volkins: LinuxCNC's samples
// table-rotary-tilting/xyzbc-trt.ini and xyzac-trt.ini (switchable kinematics, M428/M429, the
// pivot on the stock module's HAL pins), as installed. `volcomp init` writes the machine file
// and the patch, the patch is applied with `patch`, and the configuration's own demo program
// (demos/xyzbc_switchkins.ngc: helices at B 20 C 45 in TCP, moves in identity, 16 switches; the
// xyzac one at A 20 C 45) runs headless (tests/session/headless_sample.py) with the stock module
// and with volkins. The joints of both are checked against an independent transcription of the
// stock inverse (trtfuncs.c) evaluated on the recorded world commands, in each sample's
// kinematics type, through LinuxCNC's joint interpolation: the stock run validates the
// transcription, the volkins run with zero errors must give the same joints to 1e-9 mm / deg.
// Then xyzbc with errors (a perturbed copy of the machine file): the module against the core
// and the real tool tip against the ideal one, as on the MC-300.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "linuxcnc_run.hpp"
#include "session_checks.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/trace/session_trace.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
using machine::Joints;

const fs::path kSample = "/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis/vismach/5axis/table-rotary-tilting";

// xyzbc-trt-kins' inverse (LinuxCNC 2.9 trtfuncs.c, xyzbcKinematicsInverse), written out here
// from its equations, for the sample's pivot (its HALCMDs: sets :x-offset -20, sets :z-offset
// -15, rot points 0): TCP world (x y z b c, tool offset on z) to joints.
Joints xyzbc_inverse(const Joints& w, double tool_offset) {
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
Joints xyzac_inverse(const Joints& w, double tool_offset) {
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

// One of the folder's two configurations and its demo program.
struct Sample {
  std::string ini, program, machine;
  Joints (*stock_tcp_inverse)(const Joints&, double);
};
const Sample kXyzbc{"xyzbc-trt.ini", "demos/xyzbc_switchkins.ngc", "xyzbc-trt.toml", xyzbc_inverse};
const Sample kXyzac{"xyzac-trt.ini", "demos/xyzac_switchkins.ngc", "xyzac-trt.toml", xyzac_inverse};

struct StockComparison {
  double largest = 0;      // joints against the stock kinematics (mm or deg)
  std::size_t tcp = 0, switches = 0;
};

// The recorded joints against LinuxCNC's interpolation of the stock inverse of the recorded
// commands (identity where the trace's tcp column is 0).
StockComparison compare_with_stock(const Sample& sample, const trace::SessionTrace& t) {
  StockComparison out;
  std::vector<Joints> p(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    const bool tcp = t.convention[k] == machine::WorldConvention::Tcp;
    p[k] = tcp ? sample.stock_tcp_inverse(t.world[k], t.tool_length_mm[k == 0 ? 0 : k - 1]) : t.world[k];
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

class SampleTrt : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kSample)) GTEST_SKIP() << "LinuxCNC's sample configurations are not installed: " << kSample;
  }

  // A fresh run folder `dir` with a copy of the sample as the user has it (`user`), retrofitted:
  // `volcomp init` on it and its patch applied with patch(1).
  struct Retrofitted {
    fs::path dir, user;
  };
  static Retrofitted retrofitted(const Sample& sample, const std::string& name) {
    const fs::path dir = test::run_folder(name);
    const fs::path user = dir / "user";
    fs::copy(kSample, user, fs::copy_options::recursive);
    retrofit(sample, dir, user);
    return {dir, user};
  }

  static void retrofit(const Sample& sample, const fs::path& dir, const fs::path& user) {
    const test::CommandResult init = test::run_in(
        dir, std::string(VC_VOLCOMP) + " init " + (user / sample.ini).string() + " -o " +
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
                                 const machine::Model& model, const std::vector<fs::path>& extra = {}) {
    const fs::path run_dir = dir / "run";
    const test::CommandResult h =
        test::run_in(dir, "python3 " + test::source_path("tests/session/headless_sample.py") + " " + config.string() +
                              " " + sample.ini + " " + run_dir.string() + " --program " + sample.program);
    EXPECT_EQ(h.exit_code, 0) << h.out;
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
    return trace::read_session_trace((run_dir / "trace.csv").string(), model);
  }

  // The stock module's session: the transcription must be its inverse. The trace is read for
  // init's machine file (the sample's axes).
  static void expect_stock_transcribed(const Sample& sample, const std::string& name) {
    const auto [dir, user] = retrofitted(sample, name);
    const machine::Model model = machine::load_machine((user / sample.machine).string());
    const trace::SessionTrace t = run(sample, dir, kSample, model);
    const StockComparison c = compare_with_stock(sample, t);
    // The same equations; the compilers may round a product differently (fused multiply-add).
    EXPECT_LT(c.largest, 1e-12) << "the transcription is not LinuxCNC's " << sample.ini;
    EXPECT_EQ(std::count(t.gain.begin(), t.gain.end(), 0.0), static_cast<long>(t.size())) << "volkins was loaded";
    EXPECT_GE(c.switches, 8u);
    EXPECT_GT(c.tcp, 10000u);
    std::cout << sample.ini << " stock: " << t.size() << " samples, " << c.tcp << " in TCP, " << c.switches
              << " switches; joints against the transcription: " << c.largest << "\n";
  }

  // Retrofitted, zero errors: the stock module's joints.
  static void expect_stock_joints(const Sample& sample, const std::string& name) {
    const auto [dir, user] = retrofitted(sample, name);
    const machine::Model model = machine::load_machine((user / sample.machine).string());
    const trace::SessionTrace t = run(sample, dir, user, model);
    expect_volkins_applied(t);
    const StockComparison c = compare_with_stock(sample, t);
    EXPECT_LT(c.largest, 1e-9) << "volkins' joints differ from the stock module's";
    EXPECT_GE(c.switches, 8u);
    EXPECT_GT(c.tcp, 10000u);
    const trace::TraceSummary s = trace::check_trace(model, machine::WorldConvention::Axes, t);
    EXPECT_LT(test::extremes(s).mismatch, 1e-9);
    std::cout << sample.ini << " volkins, zero errors: " << t.size() << " samples, " << c.tcp << " in TCP, "
              << c.switches << " switches; joints against the stock module: max " << c.largest << "\n";
  }
};

TEST_F(SampleTrt, XyzbcStockKinematicsAreTheTranscribedOnes) { expect_stock_transcribed(kXyzbc, "sample_xyzbc_stock"); }

TEST_F(SampleTrt, XyzbcRetrofittedWithZeroErrorsVolkinsGivesTheStockJoints) {
  expect_stock_joints(kXyzbc, "sample_xyzbc_volkins");
}

TEST_F(SampleTrt, XyzacStockKinematicsAreTheTranscribedOnes) { expect_stock_transcribed(kXyzac, "sample_xyzac_stock"); }

TEST_F(SampleTrt, XyzacRetrofittedWithZeroErrorsVolkinsGivesTheStockJoints) {
  expect_stock_joints(kXyzac, "sample_xyzac_volkins");
}

TEST_F(SampleTrt, XyzbcRetrofittedWithErrorsVolkinsPutsTheRealToolOnTheCommandedPose) {
  const auto [dir, user] = retrofitted(kXyzbc, "sample_xyzbc_errors");
  // The true machine: location errors of every kind and a table on X.
  std::ofstream table(dir / "x_errors.csv");
  table << "x[mm],EXX[um],EYX[um],EZX[um],EAX[arcsec],EBX[arcsec],ECX[arcsec]\n"
           "-200,-6,2,-1,1.5,-2,1\n-100,-2,3,0,2,-1,0.5\n0,0,2,1,1,0,0\n100,3,0,1,-0.5,1.5,-0.5\n200,8,-2,0,-2,2.5,-1\n";
  table.close();
  const test::CommandResult perturb = test::run_in(
      dir, std::string(VC_VOLCOMP) + " perturb " + (user / "xyzbc-trt.toml").string() + " -o " +
               (dir / "measured").string() +
               " --location EX0C=15um --location EY0C=-10um --location EA0C=-6arcsec --location EC0B=8arcsec"
               " --location EC0Y=-5arcsec --location EB0Z=5arcsec --add-table " + (dir / "x_errors.csv").string());
  ASSERT_EQ(perturb.exit_code, 0) << perturb.out;
  const fs::path measured = dir / "measured/xyzbc-trt.toml";
  const machine::Model model = machine::load_machine(measured.string());
  const trace::SessionTrace t = run(kXyzbc, dir, user, model, {measured, dir / "measured/x_errors.csv"});
  expect_volkins_applied(t);
  const trace::TraceSummary s = trace::check_trace(model, machine::WorldConvention::Axes, t);
  test::expect_compensated(s, 2, "sample xyzbc-trt with errors");
  // What the correction removed: the model's error along the path (no tool length offset).
  double uncorrected = 0.0;
  for (const Joints& q : t.joints)
    uncorrected = std::max(uncorrected, machine::volumetric_error(model, q, 0.0).position_mm.norm());
  EXPECT_GT(uncorrected, 0.005);
  std::cout << "the same path uncompensated: tool tip error up to " << uncorrected * 1e3 << " um\n";
}

}  // namespace
}  // namespace vc
