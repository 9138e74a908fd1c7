// simsphere (kins/sim) in a real HAL (halrun, a servo thread, no motion): the probe trips where
// the true machine's ball reaches the sphere, stays tripped within its release hysteresis,
// counts its touches, and bad parameters make loadrt fail with the reason.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "linuxcnc_run.hpp"

namespace vc {
namespace {

// The ball 13.5 mm (sphere 25 + ball 2, halved) above the sphere's centre in joint Z touches
// it; the MC-300's Z errors over 13.5 mm are far under the 10 um steps used here.
TEST(Simsphere, TripsWhereTheBallTouchesTheSphere) {
  std::string script =
      "loadrt threads name1=servo-thread period1=1000000\n"
      "loadrt simsphere machine=@SRC@machines/data/mc300.toml centre=-300,-160,-200\n"
      "addf simsphere.update servo-thread\nstart\n"
      "setp simsphere.joint.0 -300\nsetp simsphere.joint.1 -160\n";
  // Above, pressed in, backed off inside the hysteresis, backed off, pressed in again.
  for (const char* z : {"-186.49", "-186.51", "-186.497", "-186.48", "-186.505"})
    script += std::string("setp simsphere.joint.2 ") + z +
              "\nloadusr -w sleep 0.05\ngetp simsphere.probe\ngetp simsphere.gap-um\n";
  script += "getp simsphere.touches\n";
  const test::CommandResult r = test::halrun("simsphere_trips", script);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::vector<std::string> v = test::getp_values(r.out);
  ASSERT_EQ(v.size(), 11u) << r.out;
  const char* probe[] = {"FALSE", "TRUE", "TRUE", "FALSE", "TRUE"};
  const double gap[] = {10, -10, 3, 20, -5};
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(v[2 * k], probe[k]) << "step " << k << "\n" << r.out;
    EXPECT_NEAR(std::stod(v[2 * k + 1]), gap[k], 0.5) << "step " << k;
  }
  EXPECT_EQ(v[10], "2");
}

TEST(Simsphere, BadParametersAreRefusedWithTheReason) {
  for (const auto& [parameters, message] : std::vector<std::pair<std::string, std::string>>{
           {"centre=-300,-160", "simsphere: centre=X,Y,Z (mm)"},
           {"centre=-300,-160,-200 sphere_diameter=big", "simsphere: sphere_diameter=big is not a number"},
           {"centre=-300,-160,-200 noise_um=-1", "simsphere: the diameters must be positive and noise_um not negative"},
           {"centre=-300,-160,-200 coordinates=xyzac", "coordinates=xyzac does not match the machine file"}}) {
    const test::CommandResult r = test::halrun(
        "simsphere_bad", "loadrt simsphere machine=@SRC@machines/data/mc300.toml " + parameters + "\nshow comp\n");
    EXPECT_NE(r.out.find(message), std::string::npos) << parameters << "\n" << r.out;
    EXPECT_EQ(r.out.find("simsphere.probe"), std::string::npos);
    EXPECT_EQ(std::regex_search(r.out, std::regex(R"(RT\s+simsphere)")), false) << r.out;
  }
}

}  // namespace
}  // namespace vc
