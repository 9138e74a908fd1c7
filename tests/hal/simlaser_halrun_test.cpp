// simlaser (kins/sim) in a real HAL (halrun, a servo thread, no motion): each laser reads the true
// machine's optic along its beam (the ideal machine's line between its start and end joints) as
// the test computes it from the true file's forward (tool_pose), independently of the module's
// arithmetic: two lines at once, mill3 with its errors and the MC-300 with its rotary axes at 0;
// bad parameters make loadrt fail with the reason.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "linuxcnc_run.hpp"
#include "test_support.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc {
namespace {

std::string set_joints(const machine::Joints& q, int lines) {
  std::string s;
  for (int j = 0; j < q.size(); ++j) s += "setp simlaser.joint." + std::to_string(j) + " " + std::to_string(q[j]) + "\n";
  s += "loadusr -w sleep 0.05\n";
  for (int i = 0; i < lines; ++i) s += "getp simlaser." + std::to_string(i) + ".position-mm\n";
  return s;
}

// The reading the module should give: the true optic along the ideal line from its start.
double expected_mm(const machine::Model& m, const machine::Joints& start, const machine::Joints& end,
                   const machine::Joints& q) {
  const double L = m.tool_length_mm;
  const Eigen::Vector3d s = machine::tool_pose(m, machine::Machine::Ideal, start, L).tip_mm;
  const Eigen::Vector3d u = (machine::tool_pose(m, machine::Machine::Ideal, end, L).tip_mm - s).normalized();
  return (machine::tool_pose(m, machine::Machine::Real, q, L).tip_mm - s).dot(u);
}

machine::Joints joints(const machine::Model& m, double x, double y, double z) {
  machine::Joints q = machine::Joints::Zero(m.joint_count());
  q[m.joint_of('X')] = x, q[m.joint_of('Y')] = y, q[m.joint_of('Z')] = z;
  return q;
}

TEST(Simlaser, ReadsTheTrueOpticAlongEachIdealLine) {
  for (const std::string name : {"mill3", "mc300"}) {
    const machine::Model model = machine::load_machine(test::machine_path(name));
    // A body diagonal and a face diagonal of a volume inside both machines' travel.
    const machine::Joints s0 = joints(model, 100, 50, -250), e0 = joints(model, 300, 200, -100);
    const machine::Joints s1 = joints(model, 100, 200, -175), e1 = joints(model, 300, 50, -175);
    // Each line's start, a point 0.5 mm off it and its end: halcmd prints 7 significant digits,
    // so the readings near the start check the module to 1e-7 mm, those at the end to 1e-4 mm.
    const std::vector<machine::Joints> poses = {s0, joints(model, 100.3, 49.8, -249.6), e0,
                                                s1, joints(model, 100.2, 200.4, -175.3), e1};
    std::string script = "loadrt threads name1=servo-thread period1=1000000\n"
                         "loadrt simlaser machine=@SRC@machines/data/" + name + ".toml"
                         " lines=100,50,-250,300,200,-100/100,200,-175,300,50,-175\n"
                         "addf simlaser.update servo-thread\nstart\n";
    for (const machine::Joints& q : poses) script += set_joints(q, 2);
    const test::CommandResult r = test::halrun("simlaser_reads_" + name, script);
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const std::vector<std::string> v = test::getp_values(r.out);
    ASSERT_EQ(v.size(), 2 * poses.size()) << r.out;
    for (std::size_t k = 0; k < poses.size(); ++k)
      for (int line = 0; line < 2; ++line) {
        const double expected = line == 0 ? expected_mm(model, s0, e0, poses[k]) : expected_mm(model, s1, e1, poses[k]);
        EXPECT_NEAR(std::stod(v[2 * k + line]), expected, 1e-7 + 6e-7 * std::abs(expected))
            << name << " line " << line << ", pose " << k;
      }
    // At its own start a laser reads the true machine's error along the line there, and at its
    // end the length plus the error: micrometres (the file's errors), not zero, not millimetres.
    const double start_error = std::abs(std::stod(v[0])), end_error = std::abs(std::stod(v[4]) - (e0 - s0).norm());
    for (double error : {start_error, end_error}) {
      EXPECT_GT(error, 2e-4) << name;
      EXPECT_LT(error, 0.1) << name;
    }
  }
}

TEST(Simlaser, NoiseHasItsStandardDeviation) {
  // 1 um of noise, 400 readings of a still machine, one sample per servo period of 1 ms.
  const test::CommandResult r = test::halrun(
      "simlaser_noise", "loadrt threads name1=servo-thread period1=1000000\n"
                        "loadrt simlaser machine=@SRC@machines/data/mill3.toml lines=0,0,-100,100,0,-100 noise_um=1 seed=3\n"
                        "loadrt sampler depth=1000 cfg=f\nnet reading simlaser.0.position-mm => sampler.0.pin.0\n"
                        "addf simlaser.update servo-thread\naddf sampler.0 servo-thread\nstart\n"
                        "loadusr -w sleep 0.6\nloadusr -w halsampler -n 400\n");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::vector<double> x;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_match(line, m, std::regex(R"(\s*(-?[0-9.]+(e-?[0-9]+)?)\s*)"))) x.push_back(std::stod(m[1]));
  }
  ASSERT_EQ(x.size(), 400u) << r.out;
  double mean = 0, sq = 0;
  for (double v : x) mean += v / 400.0;
  for (double v : x) sq += (v - mean) * (v - mean) / 399.0;
  EXPECT_NEAR(std::sqrt(sq) * 1e3, 1.0, 0.1) << "um";
}

TEST(Simlaser, BadParametersAreRefusedWithTheReason) {
  for (const auto& [parameters, message] : std::vector<std::pair<std::string, std::string>>{
           {"lines=0,0,0,100,0", "simlaser: lines=SX,SY,SZ,EX,EY,EZ[/SX,...] (mm): each line's start and end joints X, Y, Z: cannot read '0,0,0,100,0'"},
           {"lines=0,0,0,0,0,0", "simlaser: '0,0,0,0,0,0': its start and end are the same point"},
           {"lines=0,0,0,100,0,0 noise_um=loud", "simlaser: noise_um=loud is not a number"},
           {"lines=0,0,0,100,0,0 noise_um=-1", "simlaser: noise_um must not be negative"}}) {
    const test::CommandResult r = test::halrun(
        "simlaser_bad", "loadrt simlaser machine=@SRC@machines/data/mill3.toml " + parameters + "\nshow comp\n");
    EXPECT_NE(r.out.find(message), std::string::npos) << parameters << "\n" << r.out;
    EXPECT_EQ(std::regex_search(r.out, std::regex(R"(RT\s+simlaser)")), false) << r.out;
  }
}

}  // namespace
}  // namespace vc
