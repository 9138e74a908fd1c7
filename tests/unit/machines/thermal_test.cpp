// Thermal expansion of a linear axis (issue 21, the linear case of the source's chapter VI):
// mill3 with a ball-screw temperature input on X. The X axis that has grown by
// alpha (T - T_ref) (x - x_ref) puts the tool that much further along its travel on the part
// (+X moves the tool +x on the part): checked from that definition, not from the model's
// composition; at the reference temperature nothing changes; and what the file may not say
// is refused with its place.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_support.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::machine {
namespace {

// mill3.toml with [temperatures] and a thermal line on X (`thermal`: what to put there).
std::string thermal_mill3(const std::string& name, const std::string& thermal,
                          const std::string& temperatures =
                              "[temperatures]\nx_screw = { reference_degC = 20.0, "
                              "min_degC = 15.0, max_degC = 45.0 }\n") {
  std::ifstream in(test::machine_path("mill3"));
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const std::string tables = test::source_path("tables/data/mill3/");
  for (std::size_t at; (at = s.find("../../tables/data/mill3/")) != std::string::npos;)
    s.replace(at, std::string("../../tables/data/mill3/").size(), tables);
  const std::size_t x = s.find("travel_mm = [0, 500]");
  s.insert(x + std::string("travel_mm = [0, 500]").size(), "\n" + thermal);
  s = temperatures + s;
  const auto path = std::filesystem::temp_directory_path() / ("vc_thermal_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << s;
  return path.string();
}

TEST(Thermal, AScrewThatGrowsCarriesTheToolFurtherAlongIt) {
  const Model model = load_machine(
      thermal_mill3("m.toml", "thermal = { input = \"x_screw\", expansion_um_per_m_K = 11.5, reference_mm = 50 }"));
  const Model plain = load_machine(test::machine_path("mill3"));
  ASSERT_EQ(model.temperatures.size(), 1u);
  Joints q(3);
  q << 420.0, 150.0, -80.0;  // joint order x y z
  const Eigen::Vector3d cold = tool_pose(model, Machine::Real, q, 100).tip_mm;
  EXPECT_LT((cold - tool_pose(plain, Machine::Real, q, 100).tip_mm).norm(), 1e-12);  // at 20 degC: as without
  Conditions at = model.reference_conditions();
  model.set_temperature(at, "x_screw", 30.0);
  const Eigen::Vector3d warm = tool_pose(model, at, Machine::Real, q, 100).tip_mm;
  const double growth = 11.5e-6 * 10.0 * (420.0 - 50.0);  // 42.55 um
  EXPECT_NEAR(warm.x() - cold.x(), growth, 1e-5);         // (the axis's own small tilts turn it by < 1e-4)
  EXPECT_NEAR(warm.y() - cold.y(), 0.0, 1e-5);
  EXPECT_NEAR(warm.z() - cold.z(), 0.0, 1e-5);
  EXPECT_THROW(model.set_temperature(at, "x_screw", 50.0), std::invalid_argument);  // beyond max_degC
  EXPECT_THROW(model.set_temperature(at, "spindle", 25.0), std::invalid_argument);
  EXPECT_EQ(tool_pose(model, Machine::Real, q, 100).tip_mm, cold) << "the model itself never changes";
}

// predistort --temperature: the program is made for the warm machine, its X words short by the
// growth there; an unknown input or a value outside the range is refused.
TEST(Thermal, PredistortMakesTheProgramForTheGivenTemperature) {
  const std::string machine =
      thermal_mill3("p.toml", "thermal = { input = \"x_screw\", expansion_um_per_m_K = 11.5, reference_mm = 50 }");
  const auto dir = std::filesystem::temp_directory_path() / ("vc_thermal_run_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "zero.var") << "5220\t1.000000\n5221\t0.000000\n5222\t0.000000\n5223\t0.000000\n";
  std::ofstream(dir / "p.ngc") << "G21 G90 G54\nG0 X0 Y100 Z-50\nG1 X450 F500\nM2\n";
  const auto x_of_the_cut = [&](const std::string& extra) {
    const auto r =
        test::run_volcomp("predistort " + machine + " " + (dir / "p.ngc").string() + " -o " + (dir / "o.ngc").string() +
                          " --var " + (dir / "zero.var").string() + " -q " + extra);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    std::ifstream out(dir / "o.ngc");
    double x = 0;
    for (std::string line; std::getline(out, line);)  // the cut's last piece: "G1 X..." or "X..."
      if (line.rfind("G1 X", 0) == 0 || line.rfind("X", 0) == 0) x = std::stod(line.substr(line.find('X') + 1));
    return x;
  };
  const double cold = x_of_the_cut(""), warm = x_of_the_cut("--temperature x_screw=30");
  EXPECT_NEAR(warm - cold, -11.5e-6 * 10 * (450 - 50), 0.0005);  // -46 um, to the tolerance
  auto r = test::run_volcomp("predistort " + machine + " " + (dir / "p.ngc").string() + " -o " +
                             (dir / "o.ngc").string() + " --temperature x_screw=60");
  EXPECT_NE(r.out.find("outside the range the model holds for"), std::string::npos) << r.out;
  r = test::run_volcomp("predistort " + machine + " " + (dir / "p.ngc").string() + " -o " + (dir / "o.ngc").string() +
                        " --temperature spindle=25");
  EXPECT_NE(r.out.find("no temperature input 'spindle'"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

TEST(Thermal, WhatTheFileMayNotSayIsRefusedWithItsPlace) {
  const auto refused = [](const std::string& path) -> std::string {
    try {
      load_machine(path);
    } catch (const LoadError& e) {
      return e.what();
    }
    return "not refused";
  };
  EXPECT_NE(refused(thermal_mill3("a.toml", "thermal = { input = \"y_screw\", expansion_um_per_m_K = 11.5 }"))
                .find("no temperature input 'y_screw' in [temperatures]"),
            std::string::npos);
  EXPECT_NE(refused(thermal_mill3("b.toml", "thermal = { input = \"x_screw\", expansion_um_per_m_K = 115 }"))
                .find("expansion_um_per_m_K must be within +-50"),
            std::string::npos);
  EXPECT_NE(refused(thermal_mill3("c.toml", "thermal = { input = \"x_screw\", expansion_um_per_m_K = 11.5 }",
                                  "[temperatures]\nx_screw = { reference_degC = 60.0, max_degC = 45.0 }\n"))
                .find("needs -50 <= min_degC <= reference_degC <= max_degC <= 150"),
            std::string::npos);
  EXPECT_NE(refused(thermal_mill3("d.toml", "thermal = { input = \"x_screw\", expansion = 11.5 }"))
                .find("unknown key 'expansion'"),
            std::string::npos);
  // Conditions hold eight inputs (fixed size: the servo thread sets them without allocating).
  std::string nine = "[temperatures]\nx_screw = { reference_degC = 20.0, min_degC = 15.0, max_degC = 45.0 }\n";
  for (int i = 1; i < 9; ++i) nine += "t" + std::to_string(i) + " = { reference_degC = 20.0 }\n";
  EXPECT_NE(refused(thermal_mill3("e.toml", "thermal = { input = \"x_screw\", expansion_um_per_m_K = 11.5 }", nine))
                .find("more than 8 temperature inputs"),
            std::string::npos);
}

}  // namespace
}  // namespace vc::machine
