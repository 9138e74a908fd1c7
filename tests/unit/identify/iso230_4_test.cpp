// The circular test (ISO 230-4, a ballbar): a circle made by the first-order formula with known
// centre, scales, squareness and a reversal spike is fitted back exactly; a circle simulated on
// a true mill3 (through the machine's forward kinematics, not the formula, every error of the
// machine) gives its EC0X back in the machine file's own terms, the file's other errors
// included, and the file written with it loads.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_support.hpp"
#include "vc/identify/iso230_4.hpp"
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

// The circle of a model, simulated through its forward kinematics (the tip error's radial part
// at 360 points about the middle of the travel), as a run file.
// Elsewhere than the middle, or with a ball `tool_length_mm` from the gauge point: about
// `centre` (x, y, z), said in the file's metadata when `declared`.
std::string circle_of(const machine::Model& model, double radius_mm, const Eigen::Vector3d* centre = nullptr,
                      double tool_length_mm = std::nan(""), bool declared = false) {
  const int x = model.joint_of('X'), y = model.joint_of('Y'), z = model.joint_of('Z');
  const double L = std::isnan(tool_length_mm) ? model.tool_length_mm : tool_length_mm;
  const auto middle = [&](int j) { return (model.axes[j].travel_min + model.axes[j].travel_max) / 2; };
  const Eigen::Vector3d c = centre ? *centre : Eigen::Vector3d(middle(x), middle(y), middle(z));
  std::ostringstream csv;
  csv << "# plane: XY\n# radius_mm: " << radius_mm << "\n";
  if (declared) csv << "# tool_length_mm: " << L << "\n# centre: x=" << c.x() << ", y=" << c.y() << ", z=" << c.z() << "\n";
  csv << "angle[deg],direction,deviation[um]\n";
  for (int k = 0; k < 360; ++k) {
    const double phi = k * M_PI / 180;
    machine::Joints q = machine::Joints::Zero(model.joint_count());
    q[x] = c.x() + radius_mm * std::cos(phi);
    q[y] = c.y() + radius_mm * std::sin(phi);
    q[z] = c.z();
    const Eigen::Vector3d e = machine::tool_pose(model, machine::Machine::Real, q, L).tip_mm -
                              machine::tool_pose(model, machine::Machine::Ideal, q, L).tip_mm;
    csv << k << ",ccw," << (std::cos(phi) * e.x() + std::sin(phi) * e.y()) * 1e3 << '\n';
  }
  return csv.str();
}

// One squareness in the file (issue 48): the circle of a true mill3 whose EC0X is 12 arcsec
// (the file: 8), simulated with every error of the machine (its tables' slopes make a
// squareness too), gives EC0X = 12 back with the file's other errors as they are, not the
// measured squareness written on top of what the tables already carry; the circle of the file
// itself gives its own 8 back.
TEST(CircularTest, SquarenessComesBackInTheMachineFilesTerms) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const int x = model.joint_of('X');
  machine::Model truth = model;
  truth.axes[x].location_rad[2] = 12 * kArcsec;
  truth.axes[x].real_base =
      machine::line_placement(truth.axes[x].pole_mm, truth.axes[x].location_mm, truth.axes[x].location_rad);
  const double R = 100;
  const std::string run = write("mill3.csv", circle_of(truth, R));
  const CircularEvaluation e = evaluate_circular_test(read_circular_test(run));
  const std::vector<SquarenessTerm> terms = squareness_terms(model, "XY", R, e.squareness_rad, default_circle_setup(model));
  // Only EC0X: in mill3's chain Y carries X, so turning Y's line turns X with it (no squareness).
  ASSERT_EQ(terms.size(), 1u);
  EXPECT_EQ(terms[0].symbol, "EC0X");
  EXPECT_NEAR(terms[0].value_rad / kArcsec, 12.0, 0.05);
  EXPECT_NEAR(terms[0].in_file_rad / kArcsec, 8.0, 1e-9);
  EXPECT_GT(std::abs(e.squareness_rad - terms[0].value_rad) / kArcsec, 0.3);  // the tables carry a squareness too
  const CircularEvaluation own =
      evaluate_circular_test(read_circular_test(write("mill3_own.csv", circle_of(model, R))));
  EXPECT_NEAR(squareness_terms(model, "XY", R, own.squareness_rad, default_circle_setup(model))[0].value_rad / kArcsec, 8.0, 0.05);

  // Through the command line: the file written with it loads, carries it and shows the measured squareness.
  const std::string dir = (fs::temp_directory_path() / ("vc_circle_out_" + std::to_string(::getpid()))).string();
  const auto r = test::run_volcomp("identify circle " + run + " --machine " + test::machine_path("mill3") +
                                   " --machine-out " + dir);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("EC0X = 12.0"), std::string::npos) << r.out;
  const machine::Model written = machine::load_machine(dir + "/mill3.toml");
  EXPECT_NEAR(written.axes[x].location_rad[2] / kArcsec, 12.0, 0.05);
  fs::remove_all(dir);
}

// The ball's offset declared (ISO/TR 16907 L548, L919): mill3's pitch and roll tables move the
// ball by their Abbe arm, so the squareness a circle shows grows with the ball's offset from the
// gauge point. A true mill3 (EC0X 12 arcsec, the file 8) circled high above the table with a long
// ball offset gives EC0X = 12 back where the run declares its offset and centre (metadata or
// options); taken at the file's tool length in the middle of the travel, it would not.
TEST(CircularTest, TheSquarenessIsTakenAtTheBallsOffsetAndCentre) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const int x = model.joint_of('X');
  machine::Model truth = model;
  truth.axes[x].location_rad[2] = 12 * kArcsec;
  truth.axes[x].real_base =
      machine::line_placement(truth.axes[x].pole_mm, truth.axes[x].location_mm, truth.axes[x].location_rad);
  const double R = 100, L = 250;
  const Eigen::Vector3d centre(-60, 40, -20);
  const std::string run = write("mill3_ball.csv", circle_of(truth, R, &centre, L, true));
  const CircularTest t = read_circular_test(run);
  const CircularEvaluation e = evaluate_circular_test(t);
  CircleSetup setup = default_circle_setup(model);
  setup.centre[model.joint_of('X')] = centre.x();
  setup.centre[model.joint_of('Y')] = centre.y();
  setup.centre[model.joint_of('Z')] = centre.z();
  setup.tool_length_mm = L;
  EXPECT_NEAR(squareness_terms(model, "XY", R, e.squareness_rad, setup)[0].value_rad / kArcsec, 12.0, 0.05);
  const double undeclared =
      squareness_terms(model, "XY", R, e.squareness_rad, default_circle_setup(model))[0].value_rad / kArcsec;
  EXPECT_GT(std::abs(undeclared - 12.0), 0.3) << "the ball's offset would not matter on mill3";
  std::cout << "EC0X at the declared offset and centre: 12; at the file's tool length in the middle: " << undeclared
            << " arcsec\n";

  // Through the command line: the metadata, or the options over a run without it.
  const auto declared = test::run_volcomp("identify circle " + run + " --machine " + test::machine_path("mill3"));
  ASSERT_EQ(declared.exit_code, 0) << declared.out;
  EXPECT_NE(declared.out.find("EC0X = 12.0"), std::string::npos) << declared.out;
  EXPECT_NE(declared.out.find("(the run's '# tool_length_mm:')"), std::string::npos) << declared.out;
  const std::string bare = write("mill3_ball_bare.csv", circle_of(truth, R, &centre, L, false));
  const auto options = test::run_volcomp("identify circle " + bare + " --machine " + test::machine_path("mill3") +
                                         " --tool-length 250 --centre 'x=-60, y=40, z=-20'");
  ASSERT_EQ(options.exit_code, 0) << options.out;
  EXPECT_NE(options.out.find("EC0X = 12.0"), std::string::npos) << options.out;
  const auto guessed = test::run_volcomp("identify circle " + bare + " --machine " + test::machine_path("mill3"));
  ASSERT_EQ(guessed.exit_code, 0) << guessed.out;
  EXPECT_NE(guessed.out.find("note: declare the tool-side ball's offset"), std::string::npos) << guessed.out;
  const auto bad = test::run_volcomp("identify circle " + bare + " --machine " + test::machine_path("mill3") +
                                     " --centre 'x=-60, y=40'");
  EXPECT_EQ(bad.exit_code, 2) << bad.out;
  EXPECT_NE(bad.out.find("--centre"), std::string::npos) << bad.out;
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
