// The circular test (ISO 230-4, a ballbar): a circle made by the first-order formula with known
// centre, scales, squareness and a reversal spike is fitted back exactly; a circle simulated on
// the mill3 model with its squareness EC0X alone (through the machine's forward kinematics,
// not the formula) gives EC0X back in the machine file's own terms, and the file written with
// it loads.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_support.hpp"
#include "vc/identify/circular_test.hpp"
#include "vc/machine/deviations.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::identify {
namespace {

namespace fs = std::filesystem;
constexpr double kArcsec = M_PI / 648000.0;

std::string write(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("vc_circle_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << text;
  return p.string();
}

TEST(CircularTest, FitsTheFirstOrderModelBack) {
  const double R = 150, cx = 0.003, cy = -0.002, ex = 5e-6, ey = -3e-6, theta = 10 * kArcsec;
  std::ostringstream csv;
  csv << "# plane: XY\n# radius_mm: 150\nangle[deg],ccw[um],cw[um]\n";
  for (int k = 0; k < 720; ++k) {
    const double deg = 0.5 * k, phi = deg * M_PI / 180;
    const double d = -cx * std::cos(phi) - cy * std::sin(phi) +
                     R * (ex * std::cos(phi) * std::cos(phi) + ey * std::sin(phi) * std::sin(phi)) +
                     R * theta * std::sin(phi) * std::cos(phi);
    const double spike = 0.002 * std::exp(-std::pow((deg - 90) / 1.0, 2));  // 2 um where X reverses (ccw)
    csv << deg << ',' << (d + spike) * 1e3 << ',' << (d + 0.0005) * 1e3 << '\n';
  }
  const CircularTest t = read_circular_test(write("formula.csv", csv.str()));
  const CircularEvaluation e = evaluate_circular_test(t);
  ASSERT_EQ(e.fits.size(), 2u);
  const CircleFit& cw = e.fits[1];
  EXPECT_NEAR(cw.centre_first_mm, cx, 1e-9);
  EXPECT_NEAR(cw.centre_second_mm, cy, 1e-9);
  // (to the CSV's 6 significant digits)
  EXPECT_NEAR(cw.scale_mismatch, ex - ey, 1e-10);
  EXPECT_NEAR(cw.squareness_rad, theta, 1e-10);
  EXPECT_NEAR(cw.mean_scale, (ex + ey) / 2 + 0.0005 / R, 1e-10);
  EXPECT_NEAR(e.hysteresis_mm, 0.0015, 2e-5);  // cw 0.5 um off, ccw's 2 um spike: 1.5 um apart at 90 deg
  const CircleFit& ccw = e.fits[0];
  double at_90 = 0;
  for (const auto& [angle, height] : ccw.spikes)
    if (angle == 90) at_90 = height;
  EXPECT_NEAR(at_90, 0.002, 0.0003);
  EXPECT_NEAR(e.squareness_rad, theta, 2e-7);  // the spike biases the ccw fit a little
}

TEST(CircularTest, SquarenessComesBackInTheMachineFilesTerms) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const machine::Model only = machine::keep_only(model, {"EC0X"});
  const int x = model.joint_of('X'), y = model.joint_of('Y'), z = model.joint_of('Z');
  const double R = 100;
  std::ostringstream csv;
  csv << "# plane: XY\n# radius_mm: 100\nangle[deg],direction,deviation[um]\n";
  for (int k = 0; k < 360; ++k) {
    const double phi = k * M_PI / 180;
    machine::Joints q(3);
    q[x] = (model.axes[x].travel_min + model.axes[x].travel_max) / 2 + R * std::cos(phi);
    q[y] = (model.axes[y].travel_min + model.axes[y].travel_max) / 2 + R * std::sin(phi);
    q[z] = (model.axes[z].travel_min + model.axes[z].travel_max) / 2;
    const Eigen::Vector3d e = machine::tool_pose(only, machine::Machine::Real, q, model.tool_length_mm).tip_mm -
                              machine::tool_pose(only, machine::Machine::Ideal, q, model.tool_length_mm).tip_mm;
    csv << k << ",ccw," << (std::cos(phi) * e.x() + std::sin(phi) * e.y()) * 1e3 << '\n';
  }
  const CircularTest t = read_circular_test(write("mill3.csv", csv.str()));
  const CircularEvaluation e = evaluate_circular_test(t);
  const std::vector<SquarenessTerm> terms = squareness_terms(model, "XY", R, e.squareness_rad);
  // Only EC0X: in mill3's chain Y carries X, so turning Y's line turns X with it (no squareness).
  ASSERT_EQ(terms.size(), 1u);
  const auto ec0x = std::find_if(terms.begin(), terms.end(), [](const auto& s) { return s.symbol == "EC0X"; });
  ASSERT_NE(ec0x, terms.end());
  EXPECT_NEAR(ec0x->value_rad / kArcsec, 8.0, 0.05);  // mill3.toml: EC0X_arcsec = 8.0
  EXPECT_NEAR(ec0x->in_file_rad / kArcsec, 8.0, 1e-9);

  // Through the command line: the file written with it loads and carries it.
  const std::string dir = (fs::temp_directory_path() / ("vc_circle_out_" + std::to_string(::getpid()))).string();
  const auto r = test::run_volcomp("identify circle " + write("mill3.csv", csv.str()) + " --machine " +
                                   test::machine_path("mill3") + " --machine-out " + dir);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("EC0X = 8.0"), std::string::npos) << r.out;
  const machine::Model written = machine::load_machine(dir + "/mill3.toml");
  EXPECT_NEAR(written.axes[x].location_rad[2] / kArcsec, 8.0, 0.05);
  fs::remove_all(dir);
}

TEST(CircularTest, RefusesWhatCannotGiveASquareness) {
  const auto message = [](const std::string& text) -> std::string {
    try {
      evaluate_circular_test(read_circular_test(write("bad.csv", text)));
    } catch (const std::exception& e) {
      return e.what();
    }
    return "not refused";
  };
  std::string half = "# radius_mm: 100\nangle[deg],direction,deviation[um]\n";
  for (int k = 0; k <= 180; k += 5) half += std::to_string(k) + ",ccw,1\n";
  EXPECT_NE(message(half).find("the squareness needs the whole turn"), std::string::npos);
  EXPECT_NE(message("angle[deg],direction,deviation[um]\n0,ccw,1\n").find("radius is not known"), std::string::npos);
  EXPECT_NE(message("angle[deg],direction,deviation[um]\n0,left,1\n").find("bad.csv:2:3: error: direction 'left'"),
            std::string::npos);
}

}  // namespace
}  // namespace vc::identify
