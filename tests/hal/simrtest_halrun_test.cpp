// simrtest (kins/sim) in a real HAL (halrun, a servo thread, no motion): the sensors read the
// sphere's centre against the nest's in the spindle frame, as the true machine's forward (its
// tool_pose, another code path than the module's 4x4 chain) puts them: 0 at the joints that
// define the sphere, the offset's length and its part along the tool direction at a tilted
// pose; clipped to their range (in-range FALSE); bad parameters make loadrt fail with the reason.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "linuxcnc_run.hpp"
#include "test_support.hpp"
#include "tip_on_point.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc {
namespace {

std::string set_joints(const machine::Joints& q) {
  std::string s;
  for (int j = 0; j < q.size(); ++j) s += "setp simrtest.joint." + std::to_string(j) + " " + std::to_string(q[j]) + "\n";
  return s + "loadusr -w sleep 0.05\ngetp simrtest.dx-um\ngetp simrtest.dy-um\ngetp simrtest.dz-um\ngetp simrtest.in-range\n";
}

TEST(Simrtest, ReadsTheSphereInTheSpindleFrameAsTheTrueMachinePutsIt) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  machine::Joints at_sphere = machine::Joints::Zero(5), turned(5);
  at_sphere << -300, -160, -200, 0, 0;
  const double L = model.tool_length_mm;
  const Eigen::Vector3d sphere = machine::tool_pose(model, machine::Machine::Real, at_sphere, L).tip_mm;
  turned << 0, 0, 0, -30, 45;  // B and C turned, the nest 3-4 mm off the sphere
  const machine::Joints tilted = test::tip_on_point(model, machine::Machine::Real, turned, sphere + Eigen::Vector3d(3, -2, 1.5), L);
  machine::Joints far = at_sphere;
  far[0] += 2.0;  // beyond the 1 mm range
  const std::string script = "loadrt threads name1=servo-thread period1=1000000\n"
                             "loadrt simrtest machine=@SRC@machines/data/mc300.toml centre=-300,-160,-200 range_um=10000\n"
                             "addf simrtest.update servo-thread\nstart\n" +
                             set_joints(at_sphere) + set_joints(tilted);
  const test::CommandResult r = test::halrun("simrtest_reads", script);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::vector<std::string> v = test::getp_values(r.out);
  ASSERT_EQ(v.size(), 8u) << r.out;
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(std::stod(v[d]), 0.0, 1e-3) << r.out;
  EXPECT_EQ(v[3], "TRUE");
  const machine::ToolPose nest = machine::tool_pose(model, machine::Machine::Real, tilted, L);
  const Eigen::Vector3d reading(std::stod(v[4]), std::stod(v[5]), std::stod(v[6]));
  EXPECT_NEAR(reading.norm() * 1e-3, (sphere - nest.tip_mm).norm(), 1e-6);
  EXPECT_NEAR(reading.z() * 1e-3, (sphere - nest.tip_mm).dot(nest.direction), 1e-6);
  EXPECT_GT(reading.norm(), 3000.0);
  EXPECT_EQ(v[7], "TRUE");

  const test::CommandResult clipped = test::halrun(
      "simrtest_clipped", "loadrt threads name1=servo-thread period1=1000000\n"
                          "loadrt simrtest machine=@SRC@machines/data/mc300.toml centre=-300,-160,-200\n"
                          "addf simrtest.update servo-thread\nstart\n" +
                              set_joints(far));
  ASSERT_EQ(clipped.exit_code, 0) << clipped.out;
  const std::vector<std::string> c = test::getp_values(clipped.out);
  ASSERT_EQ(c.size(), 4u) << clipped.out;
  // The MC-300's X joint moves the table: +2 mm puts the sphere 2 mm to +x of the nest.
  const double beyond = (sphere - machine::tool_pose(model, machine::Machine::Real, far, L).tip_mm).x();
  EXPECT_GT(beyond, 1.9);
  EXPECT_NEAR(std::stod(c[0]), 1000.0, 1e-6) << "the sensor at the end of its range";
  EXPECT_EQ(c[3], "FALSE");
}

TEST(Simrtest, BadParametersAreRefusedWithTheReason) {
  for (const auto& [parameters, message] : std::vector<std::pair<std::string, std::string>>{
           {"centre=-300,-160", "simrtest: centre=X,Y,Z (mm)"},
           {"centre=-300,-160,-200 range_um=wide", "simrtest: range_um=wide is not a number"},
           {"centre=-300,-160,-200 noise_um=-1", "simrtest: range_um must be positive and noise_um not negative"}}) {
    const test::CommandResult r = test::halrun(
        "simrtest_bad", "loadrt simrtest machine=@SRC@machines/data/mc300.toml " + parameters + "\nshow comp\n");
    EXPECT_NE(r.out.find(message), std::string::npos) << parameters << "\n" << r.out;
    EXPECT_EQ(std::regex_search(r.out, std::regex(R"(RT\s+simrtest)")), false) << r.out;
  }
}

}  // namespace
}  // namespace vc
