// The pre-distorter end to end, judged by independent readings: LinuxCNC's own interpreter
// (`rs274 -g`) reads the input and the output programs, the machine model turns the moves
// into tool-tip paths, and the tests measure how far the real machine running the output
// strays from the ideal machine running the input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>

#include "program_reader.hpp"
#include "rs274.hpp"
#include "test_support.hpp"
#include "vc/machine/kinematics.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/predistort/predistort.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;
using Point = std::array<double, 6>;

std::string program(const std::string& name) { return test::source_path("tests/programs/" + name); }

machine::Joints joints_of(const machine::Model& model, const Point& world) {
  machine::Joints q(model.joint_count());
  for (int j = 0; j < model.joint_count(); ++j)
    q[j] = world[std::string_view("XYZABC").find(model.axes[static_cast<std::size_t>(j)].letter)];
  return q;
}

using Polyline = std::vector<Eigen::Vector3d>;

// Tool-tip paths (part frame) of a machine running canonical moves, one polyline per move
// (empty for rapids: they are corrected at their ends only), sampled every `step_mm`.
std::vector<Polyline> tip_paths(const machine::Model& model, machine::Machine which,
                                const std::vector<test::CanonMove>& moves, double step_mm) {
  std::vector<Polyline> paths;
  Point at = moves.empty() ? Point{} : moves.front().end;
  for (const test::CanonMove& m : moves) {
    Polyline path;
    if (m.kind != test::CanonMove::Traverse) {
      auto tip = [&](const Point& w) {
        return machine::tool_pose(model, which, joints_of(model, w), m.tool_length_mm).tip_mm;
      };
      path.push_back(tip(at));
      for (const Point& w : test::sample(m, at, step_mm)) path.push_back(tip(w));
    }
    paths.push_back(std::move(path));
    at = m.end;
  }
  return paths;
}

// Which input move each output move belongs to: the pieces of a move end, in order, with
// the one that ends within `radius` of the input move's end (world coordinates). Pieces
// shorter than that (the short moves to a corrected start) never end a move: a full circle
// ends where it starts.
std::vector<std::size_t> owners(const std::vector<test::CanonMove>& input, const std::vector<Point>& output_ends,
                                double radius) {
  std::vector<std::size_t> owner;
  std::size_t k = 0;  // the input move being built
  Point previous = output_ends.empty() ? Point{} : output_ends.front();
  for (const Point& end : output_ends) {
    std::size_t mine = std::min(k, input.size() - 1);
    double length = 0;
    for (int i = 0; i < 6; ++i) length = std::max(length, std::abs(end[i] - previous[i]));
    previous = end;
    if (length < radius) {
      owner.push_back(mine);
      continue;
    }
    // An input move may have no output (a rapid written as it is): look a few moves ahead.
    for (std::size_t j = k; j < std::min(input.size(), k + 3); ++j) {
      double d = 0;
      for (int i = 0; i < 6; ++i) d = std::max(d, std::abs(end[i] - input[j].end[i]));
      if (d < radius) {
        mine = j;
        k = j + 1;
        break;
      }
    }
    owner.push_back(mine);
  }
  return owner;
}

double distance_to(const Eigen::Vector3d& p, const Polyline& line) {
  double best = 1e9;
  for (std::size_t k = 1; k < line.size(); ++k) {
    const Eigen::Vector3d ab = line[k] - line[k - 1];
    const double t = ab.squaredNorm() > 0 ? std::clamp((p - line[k - 1]).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (line[k - 1] + t * ab - p).norm());
  }
  return line.size() == 1 ? (line[0] - p).norm() : best;
}

// Largest distance from the actual tool tip to the nominal path of the same program move;
// `checked` counts the samples compared (so that a test cannot pass on none).
double largest_deviation(const std::vector<Polyline>& actual, const std::vector<std::size_t>& owner,
                         const std::vector<Polyline>& nominal, std::size_t& checked) {
  double worst = 0;
  checked = 0;
  for (std::size_t m = 0; m < actual.size(); ++m)
    for (const Eigen::Vector3d& p : actual[m])
      if (!nominal[owner[m]].empty()) {
        worst = std::max(worst, distance_to(p, nominal[owner[m]]));
        ++checked;
      }
  return worst;
}

std::vector<Point> ends_of(const std::vector<test::CanonMove>& moves) {
  std::vector<Point> ends;
  for (const auto& m : moves) ends.push_back(m.end);
  return ends;
}

// The unmodified program on the real machine against the ideal machine, sample by sample.
double raw_error(const std::vector<Polyline>& real, const std::vector<Polyline>& ideal) {
  double worst = 0;
  for (std::size_t m = 0; m < real.size(); ++m)
    for (std::size_t k = 0; k < real[m].size(); ++k) worst = std::max(worst, (real[m][k] - ideal[m][k]).norm());
  return worst;
}

struct Case {
  std::string machine, program, tools, var;
};

class Predistorted : public ::testing::Test {
 protected:
  static std::string run(const Case& c, const std::string& out, const std::string& extra = "") {
    const auto r =
        test::run_volcomp("predistort " + test::machine_path(c.machine) + " " + program(c.program) + " -o " + out +
                          " --tool-table " + program(c.tools) + " --var " + program(c.var) + " " + extra);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    return r.out;
  }
};

const Case kPocket{"mill3", "mill3_pocket.ngc", "mill3.tbl", "mill3.var"};
const Case kSwarf{"mc300", "mc300_swarf.ngc", "mc300.tbl", "mc300.var"};
const Case kInch{"mill3", "mill3_inch.ngc", "mill3.tbl", "mill3.var"};

// The output read by the project's interpreter at full precision, as canonical moves.
std::vector<test::CanonMove> read_output(const machine::Model& model, const Case& c, const std::string& path) {
  static std::map<std::string, interpreter::ToolTable> tools;
  static std::map<std::string, gcode::Parameters> parameters;
  tools[c.tools] = interpreter::read_tool_table(program(c.tools));
  interpreter::read_var_file(program(c.var), parameters[c.var]);
  interpreter::Setup setup;
  setup.machine_axes = predistort::program_axes(model);
  setup.tools = &tools[c.tools];
  setup.var_file = &parameters[c.var];
  std::vector<test::CanonMove> moves;
  for (const interpreter::Move& m : test::read_moves(path, setup)) {
    test::CanonMove cm;
    cm.kind = m.kind == interpreter::MoveKind::Rapid  ? test::CanonMove::Traverse
              : m.kind == interpreter::MoveKind::Line ? test::CanonMove::Feed
                                                      : test::CanonMove::Arc;
    cm.end = m.frame.world(m.end);
    cm.tool_length_mm = m.tool_offset_mm;
    if (m.kind == interpreter::MoveKind::Arc) {
      cm.first = m.arc.first;
      cm.second = m.arc.second;
      cm.normal = m.arc.normal;
      interpreter::Position center = m.end;
      center[static_cast<std::size_t>(m.arc.first)] = m.arc.center_first;
      center[static_cast<std::size_t>(m.arc.second)] = m.arc.center_second;
      const interpreter::Position world_center = m.frame.world(center);
      cm.center_first = world_center[static_cast<std::size_t>(m.arc.first)];
      cm.center_second = world_center[static_cast<std::size_t>(m.arc.second)];
      cm.rotation = (m.arc.clockwise ? -1 : 1) * m.arc.turns;
    }
    moves.push_back(cm);
  }
  return moves;
}

// LinuxCNC reads the output as the project's interpreter does: the same moves, ends and
// arc centers, to rs274's 4 printed decimals (`resolution`). rs274 also lists the rapids the
// pre-distorter wrote as they were (the interpreter reports only the moves it corrects).
void expect_same_moves(const std::vector<test::CanonMove>& rs274, const std::vector<test::CanonMove>& ours,
                       double resolution) {
  auto same_end = [&](const test::CanonMove& a, const test::CanonMove& b) {
    for (int i = 0; i < 6; ++i)
      if (std::abs(a.end[i] - b.end[i]) > resolution) return false;
    return true;
  };
  std::size_t k = 0, skipped = 0;
  for (std::size_t m = 0; m < ours.size(); ++m, ++k) {
    while (k < rs274.size() && rs274[k].kind == test::CanonMove::Traverse && !same_end(rs274[k], ours[m])) {
      ++k;
      ++skipped;
    }
    ASSERT_LT(k, rs274.size()) << "our move " << m << " is not in rs274's reading";
    ASSERT_EQ(rs274[k].kind, ours[m].kind) << "move " << m;
    ASSERT_TRUE(same_end(rs274[k], ours[m])) << "move " << m;
    if (ours[m].kind == test::CanonMove::Arc) {
      EXPECT_NEAR(rs274[k].center_first, ours[m].center_first, resolution) << "move " << m;
      EXPECT_NEAR(rs274[k].center_second, ours[m].center_second, resolution) << "move " << m;
      EXPECT_EQ(rs274[k].rotation, ours[m].rotation) << "move " << m;
    }
  }
  EXPECT_LE(skipped + (rs274.size() - k), 3u);  // the first rapid to Z, G28's two
}

// 3 axes, read back by LinuxCNC's interpreter (4 decimals: 0.05 um rounding per axis).
TEST_F(Predistorted, PocketFollowsTheNominalPathWithinTheTolerance) {
  if (!test::rs274_available()) GTEST_SKIP() << "rs274 not installed";
  const fs::path dir = test::run_folder("predistort_pocket");
  const std::string out = (dir / "pocket_predistorted.ngc").string();
  std::cout << run(kPocket, out);
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const auto input =
      test::rs274_moves("rs274_pocket_in", program(kPocket.program), program(kPocket.tools), program(kPocket.var));
  const auto output = test::rs274_moves("rs274_pocket_out", out, program(kPocket.tools), program(kPocket.var));
  const auto nominal = tip_paths(model, machine::Machine::Ideal, input, 0.05);
  const double raw = raw_error(tip_paths(model, machine::Machine::Real, input, 0.05), nominal);
  std::size_t samples = 0;
  const double deviation = largest_deviation(tip_paths(model, machine::Machine::Real, output, 0.05),
                                             owners(input, ends_of(output), 0.1), nominal, samples);
  EXPECT_GT(samples, 20000u);
  std::cout << "mill3 pocket: " << samples << " samples; raw error max " << raw * 1e3
            << " um; pre-distorted max deviation " << deviation * 1e3 << " um\n";
  EXPECT_GT(raw, 0.010);                // the unmodified program shows the machine's error
  EXPECT_LT(deviation, 0.0005 + 1e-4);  // tolerance + rs274's rounding of the output
}

// 5 axes: the output read at full precision by the project's interpreter (rs274 rounds
// degrees to 1e-4, 0.5 um at the MC-300's lever arms); rs274 checks that reading below.
TEST_F(Predistorted, SwarfFollowsTheNominalPathWithinTheTolerance) {
  if (!test::rs274_available()) GTEST_SKIP() << "rs274 not installed";
  const fs::path dir = test::run_folder("predistort_swarf");
  const std::string out = (dir / "swarf_predistorted.ngc").string();
  std::cout << run(kSwarf, out);
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const auto input =
      test::rs274_moves("rs274_swarf_in", program(kSwarf.program), program(kSwarf.tools), program(kSwarf.var));
  const std::vector<test::CanonMove> output = read_output(model, kSwarf, out);
  for (const auto& m : output) ASSERT_NE(m.kind, test::CanonMove::Arc);
  expect_same_moves(test::rs274_moves("rs274_swarf_out", out, program(kSwarf.tools), program(kSwarf.var)), output,
                    6e-5);

  const auto nominal = tip_paths(model, machine::Machine::Ideal, input, 0.05);
  const double raw = raw_error(tip_paths(model, machine::Machine::Real, input, 0.05), nominal);
  std::size_t samples = 0;
  const double deviation = largest_deviation(tip_paths(model, machine::Machine::Real, output, 0.05),
                                             owners(input, ends_of(output), 0.1), nominal, samples);
  EXPECT_GT(samples, 10000u);
  std::cout << "MC-300 swarf: " << samples << " samples; raw error max " << raw * 1e3
            << " um; pre-distorted max deviation " << deviation * 1e3 << " um\n";
  EXPECT_GT(raw, 0.020);
  EXPECT_LT(deviation, 0.0005);
}

// At every program point the output sends the machine exactly where the kinematics module
// would (the core's joints_from_world, which volkins calls), to the written decimals.
TEST_F(Predistorted, ProgramPointsAgreeWithTheModuleCorrection) {
  if (!test::rs274_available()) GTEST_SKIP() << "rs274 not installed";
  for (const Case& c : {kPocket, kSwarf, kInch}) {
    const std::string name = c.program.substr(0, c.program.find('.'));
    const fs::path dir = test::run_folder("predistort_points_" + name);
    const std::string out = (dir / "out.ngc").string();
    run(c, out);
    const machine::Model model = machine::load_machine(test::machine_path(c.machine));
    const auto input =
        test::rs274_moves("rs274_points_in_" + name, program(c.program), program(c.tools), program(c.var));
    const double resolution = 6e-5 * (c.program.find("inch") != std::string::npos ? 25.4 : 1.0);
    expect_same_moves(test::rs274_moves("rs274_points_out_" + name, out, program(c.tools), program(c.var)),
                      read_output(model, c, out), resolution);
    const interpreter::ToolTable tools = interpreter::read_tool_table(program(c.tools));
    gcode::Parameters parameters;
    interpreter::read_var_file(program(c.var), parameters);
    interpreter::Setup setup;
    setup.machine_axes = predistort::program_axes(model);
    setup.tools = &tools;
    setup.var_file = &parameters;
    const std::vector<interpreter::Move> output = test::read_moves(out, setup);
    std::size_t next = 0, matched = 0, unmatched_feeds = 0;
    double worst = 0;
    for (const test::CanonMove& m : input) {
      machine::Joints corrected;
      ASSERT_EQ(machine::joints_from_world(model, machine::WorldConvention::Axes, joints_of(model, m.end),
                                           m.tool_length_mm, corrected),
                machine::Status::Ok);
      bool found = false;
      for (std::size_t k = next; k < output.size() && k < next + 5000; ++k) {
        const machine::Joints written = joints_of(model, output[k].frame.world(output[k].end));
        const double d = (written - corrected).cwiseAbs().maxCoeff();
        if (d < 2e-6) {
          worst = std::max(worst, d);
          next = k + 1;
          found = true;
          break;
        }
      }
      matched += found;
      if (!found && m.kind != test::CanonMove::Traverse) ++unmatched_feeds;
    }
    std::cout << c.program << ": " << matched << " of " << input.size()
              << " program points found corrected in the output, largest difference " << worst << "\n";
    EXPECT_EQ(unmatched_feeds, 0u);
    EXPECT_GE(matched + 3, input.size());  // rapids written as they are: first Z, G28
  }
}

// The TCP world convention (kinematics with tool-centre-point control, volkins world=tcp):
// program X Y Z are the tool tip in the part frame and LinuxCNC's tool length offset is not
// part of the kinematics' world. At every program point the output is the world position
// whose nominal kinematics give the joints the module's correction gives.
TEST_F(Predistorted, TcpProgramPointsAgreeWithTheModuleCorrection) {
  const fs::path dir = test::run_folder("predistort_tcp");
  const std::string out = (dir / "out.ngc").string();
  run(kSwarf, out, "--world tcp");
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const interpreter::ToolTable tools = interpreter::read_tool_table(program(kSwarf.tools));
  gcode::Parameters parameters;
  interpreter::read_var_file(program(kSwarf.var), parameters);
  interpreter::Setup setup;
  setup.machine_axes = predistort::program_axes(model);
  setup.tools = &tools;
  setup.var_file = &parameters;
  setup.tool_length_in_world = false;
  const auto input = test::read_moves(program(kSwarf.program), setup);
  const auto output = test::read_moves(out, setup);
  ASSERT_GT(input.size(), 300u);
  std::size_t next = 0, matched = 0;
  double worst = 0;
  for (const interpreter::Move& m : input) {
    machine::Joints joints;
    ASSERT_EQ(machine::joints_from_world(model, machine::WorldConvention::Tcp, joints_of(model, m.frame.world(m.end)),
                                         m.tool_offset_mm, joints),
              machine::Status::Ok);
    const machine::Joints expected =
        machine::nominal_forward(model, machine::WorldConvention::Tcp, joints, m.tool_offset_mm);
    for (std::size_t k = next; k < output.size(); ++k) {
      const double d = (joints_of(model, output[k].frame.world(output[k].end)) - expected).cwiseAbs().maxCoeff();
      if (d < 2e-6) {
        worst = std::max(worst, d);
        next = k + 1;
        ++matched;
        break;
      }
    }
  }
  std::cout << "MC-300 swarf, TCP: " << matched << " of " << input.size()
            << " program points found corrected in the output, largest difference " << worst << "\n";
  EXPECT_EQ(matched, input.size());
}

// Cutting-force deflection: the machine under the cutting load of mill3_process.toml,
// simulated here from the force model's formulas (Kienzle's kc, mean force from cutting
// power) and the machine file's compliance, follows the nominal path only if the
// pre-distorter took the deflection off.
TEST_F(Predistorted, CuttingForceDeflectionIsTakenOff) {
  if (!test::rs274_available()) GTEST_SKIP() << "rs274 not installed";
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const interpreter::ToolTable tools = interpreter::read_tool_table(program(kPocket.tools));
  const predistort::CuttingProcess process = predistort::load_process(program("mill3_process.toml"), &tools);
  gcode::Parameters parameters;
  interpreter::read_var_file(program(kPocket.var), parameters);
  interpreter::Setup setup;
  setup.machine_axes = predistort::program_axes(model);
  setup.tools = &tools;
  setup.var_file = &parameters;
  const auto input =
      test::rs274_moves("rs274_force_in", program(kPocket.program), program(kPocket.tools), program(kPocket.var));
  const auto nominal = tip_paths(model, machine::Machine::Ideal, input, 0.05);

  // The tool tip under load: real machine plus compliance x force.
  auto loaded_path = [&](const std::string& path) {
    std::vector<Polyline> tips;
    std::vector<Point> ends;
    double largest = 0;
    for (const interpreter::Move& m : test::read_moves(path, setup)) {
      ends.push_back(m.frame.world(m.end));
      tips.emplace_back();
      if (m.kind == interpreter::MoveKind::Rapid) continue;
      const bool cutting = m.kind != interpreter::MoveKind::Rapid && process.tools.count(m.tool) && m.spindle_on;
      std::vector<Eigen::Vector3d> tip;
      std::vector<machine::Joints> joints;
      const int n = 200;
      for (int k = 0; k <= n; ++k) {
        joints.push_back(joints_of(model, m.frame.world(interpreter::point_at(m, static_cast<double>(k) / n))));
        tip.push_back(machine::tool_pose(model, machine::Machine::Real, joints.back(), m.tool_offset_mm).tip_mm);
      }
      const double length = (tip.back() - tip.front()).norm();
      for (int k = 0; k <= n; ++k) {
        Eigen::Vector3d deflection = Eigen::Vector3d::Zero();
        const Eigen::Vector3d step =
            tip[static_cast<std::size_t>(std::min(k + 1, n))] - tip[static_cast<std::size_t>(std::max(k - 1, 0))];
        if (cutting && length > 0.1 && std::hypot(step.x(), step.y()) > 1e-9) {
          const predistort::ToolProcess& p = process.tools.at(m.tool);
          const Eigen::Vector3d t = Eigen::Vector3d(step.x(), step.y(), 0).normalized();
          const double vf = m.feed * std::hypot(step.x(), step.y()) / step.norm();
          const double hm = vf / (p.teeth * m.spindle_rpm) * std::sqrt(p.width_of_cut_mm / p.diameter_mm);
          const double kc = p.specific_force_N_per_mm2 / std::pow(hm, p.chip_exponent);
          const double fc = kc * p.depth_of_cut_mm * p.width_of_cut_mm * vf / (M_PI * p.diameter_mm * m.spindle_rpm);
          const Eigen::Vector3d left(-t.y(), t.x(), 0);  // tool axis +z on this 3-axis mill
          const Eigen::Vector3d force = -fc * t - p.material_side * p.radial_ratio * fc * left;
          for (int j = 0; j < 3; ++j) {
            const Eigen::Vector3d axis = Eigen::Vector3d::Unit(j);  // mill3: +X, +Y, +Z move the tip +x, +y, +z
            deflection += model.compliance[static_cast<std::size_t>(j)].at(joints[static_cast<std::size_t>(k)][j]) *
                          force.dot(axis) * axis;
          }
        } else if (cutting && length <= 0.1) {
          continue;  // corner transition pieces: the force there is between two directions
        }
        largest = std::max(largest, deflection.norm());
        tips.back().push_back(tip[static_cast<std::size_t>(k)] + deflection);
      }
    }
    return std::tuple{tips, owners(input, ends, 0.1), largest};
  };

  const fs::path dir = test::run_folder("predistort_force");
  const std::string with = (dir / "with_force.ngc").string(), without = (dir / "without_force.ngc").string();
  std::cout << run(kPocket, with, "--process " + program("mill3_process.toml"));
  run(kPocket, without);
  const auto [loaded_with, owner_with, deflection] = loaded_path(with);
  const auto [loaded_without, owner_without, unused] = loaded_path(without);
  std::size_t samples_with = 0, samples_without = 0;
  const double with_force = largest_deviation(loaded_with, owner_with, nominal, samples_with);
  const double without_force = largest_deviation(loaded_without, owner_without, nominal, samples_without);
  EXPECT_GT(samples_with, 5000u);
  EXPECT_GT(samples_without, 5000u);
  std::cout << "mill3 pocket under load: largest deflection " << deflection * 1e3 << " um; deviation "
            << without_force * 1e3 << " um with geometric pre-distortion only, " << with_force * 1e3
            << " um with the deflection taken off\n";
  EXPECT_GT(without_force, 0.003);
  EXPECT_LT(with_force, 0.0005 + 1e-4);
}

TEST(PredistortCli, BadInputNamesLineAndColumnAndLeavesTheOutputAlone) {
  const fs::path dir = test::run_folder("predistort_bad");
  const fs::path out = dir / "out.ngc";
  std::ofstream(out) << "OLD\n";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"G21 G90\nG0 X0 Y0 Z0\nG1 X1 E5\n", "bad.ngc:3:7: error: E word without G70 or G76"},
      {"G21\nG0 X0 Y0 Z0\nG43 H9\n", "bad.ngc:3:5: error: tool 9 is not in the tool table"},
      {"G21\nG0 X0 Y0 Z0\nG1 X1 (unclosed\n", "bad.ngc:3:7"},
      {"G21\nG0 X0 Y0 Z0\nG41 D1 G1 X4 F100\n",  // tool 1: 10 mm
       "bad.ngc:3:11: error: length of cutter compensation entry move is not greater than the tool radius"},
  };
  for (const auto& [text, expected] : cases) {
    std::ofstream(dir / "bad.ngc") << text;
    const auto r =
        test::run_volcomp("predistort " + test::machine_path("mill3") + " " + (dir / "bad.ngc").string() + " -o " +
                          out.string() + " --var " + program("mill3.var") + " --tool-table " + program("mill3.tbl"));
    EXPECT_NE(r.exit_code, 0) << text;
    EXPECT_NE(r.out.find(expected), std::string::npos) << r.out;
    std::ifstream kept(out);
    std::string content((std::istreambuf_iterator<char>(kept)), std::istreambuf_iterator<char>());
    EXPECT_EQ(content, "OLD\n");  // untouched, and no temporary file left beside it
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
  }
}

// A canned cycle is written out as the moves LinuxCNC makes of it (each point corrected), in
// exact path mode as LinuxCNC runs them; one it does not translate is refused with the reason.
// (That the moves are LinuxCNC's is checked against rs274 in tests/acceptance.)
TEST(PredistortCli, CannedCyclesAreWrittenOutOrRefusedWithTheReason) {
  const auto r = test::run_volcomp("predistort " + test::machine_path("mill3") + " " + program("drilling_cycle.ngc") +
                                   " -o - -q --var " + program("mill3.var") + " --tool-table " + program("mill3.tbl"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out.find("\nG81"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("G61 G0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("G64 P0.0005 Q0\nG61 X20"), std::string::npos) << r.out;  // the mode again, the next hole
  const fs::path dir = test::run_folder("predistort_g84");
  const auto run = [&](const std::string& text) {
    std::ofstream(dir / "tap.ngc") << text;
    return test::run_volcomp("predistort " + test::machine_path("mill3") + " " + (dir / "tap.ngc").string() +
                             " -o - -q --var " + program("mill3.var"));
  };
  // Tapping: overrides off, feed in, spindle reversed, dwell, feed out, spindle forward, overrides on.
  const auto tap = run("G21 G90 G54\nG0 X0 Y0 Z50\nS500 M3\nG84 X10 Y10 Z-5 R2 F600 P0.2\nM2\n");
  ASSERT_EQ(tap.exit_code, 0) << tap.out;
  const std::size_t in = tap.out.find("M50 P0\nM51 P0\nG1 ");
  const std::size_t reverse = tap.out.find("M5\nM4\nG4 P0.2\n");
  const std::size_t forward = tap.out.find("M5\nM3\nM50 P1\nM51 P1\n");
  EXPECT_TRUE(in != std::string::npos && reverse > in && forward != std::string::npos && forward > reverse) << tap.out;
  const auto stopped = run("G21 G90 G54\nG0 X0 Y0 Z50\nG84 X10 Y10 Z-5 R2 F600\nM2\n");
  EXPECT_NE(stopped.out.find("tap.ngc:3:1: error: G84: LinuxCNC refuses a tapping cycle with the spindle not turning"),
            std::string::npos)
      << stopped.out;
  const auto back_bore = run("G21 G90 G54\nG0 X0 Y0 Z50\nS500 M3\nG87 X10 Y10 Z-5 R2 I1 J1 K-2 F600\nM2\n");
  EXPECT_NE(back_bore.out.find("tap.ngc:4:1: error: G87: the back boring cycle G87 is not translated"),
            std::string::npos)
      << back_bore.out;
}

TEST(PredistortCli, AMachineWithAUVOrWAxisIsRefusedAtStart) {
  // LinuxCNC's W axis as the third linear axis: a valid machine file (the module can load
  // it), but the pre-distorter writes X Y Z A B C only.
  const fs::path dir = test::run_folder("predistort_uvw");
  std::ofstream(dir / "xyw.toml") << R"([machine]
name = "xyw"
[spindle]
gauge_point_mm = [0, 0, 0]
tool_length_mm = 100.0
[[tool_chain]]
axis = "W"
type = "linear"
direction = [0, 0, 1]
pole_mm = [0, 0, 0]
travel_mm = [-300, 0]
[[workpiece_chain]]
axis = "Y"
type = "linear"
direction = [0, -1, 0]
pole_mm = [0, 0, 0]
travel_mm = [0, 400]
[[workpiece_chain]]
axis = "X"
type = "linear"
direction = [-1, 0, 0]
pole_mm = [0, 0, 0]
travel_mm = [0, 500]
)";
  std::ofstream(dir / "p.ngc") << "G21 G90\nG0 X0 Y0\nG1 X10 F100\n";
  const fs::path out = dir / "out.ngc";
  const auto r = test::run_volcomp("predistort " + (dir / "xyw.toml").string() + " " + (dir / "p.ngc").string() +
                                   " -o " + out.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("xyw.toml: error: axis W: the pre-distorter writes the program axes X Y Z A B C only"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(out));
}

// A LinuxCNC set up in inches ([TRAJ]LINEAR_UNITS = inch) keeps its .var file and tool table in
// inches: the same machine described so, read with --machine-units inch, gives the same program
// as in millimetres; an INI in inches without the option is refused.
TEST(PredistortCli, AMachineSetUpInInchesReadsItsFilesInInches) {
  const fs::path dir = test::run_folder("predistort_inch_machine");
  std::ifstream var_mm(program("mill3.var"));
  std::ofstream var_inch(dir / "mill3_inch.var");
  int n = 0;
  double value = 0;
  while (var_mm >> n >> value) {
    const int axis = n >= 5221 ? (n - 5221) % 20 : n >= 5211 ? n - 5211 : n >= 5181 ? n - 5181 : n - 5161;
    const bool length = n != 5220 && n != 5210 && (axis <= 2 || (axis >= 6 && axis <= 8));
    var_inch << n << "\t" << std::setprecision(17) << (length ? value / 25.4 : value) << "\n";
  }
  var_inch.close();
  std::ofstream(dir / "mill3_inch.tbl") << "T1 P1 Z" << std::setprecision(17) << 100 / 25.4 << " D" << 10 / 25.4
                                        << "\nT2 P2 Z" << 85.5 / 25.4 << " D" << 6 / 25.4 << "\n";
  const std::string common = "predistort " + test::machine_path("mill3") + " " + program(kPocket.program) + " -q";
  const auto mm = test::run_volcomp(common + " -o " + (dir / "mm.ngc").string() + " --var " + program("mill3.var") +
                                    " --tool-table " + program("mill3.tbl"));
  const auto inch =
      test::run_volcomp(common + " -o " + (dir / "inch.ngc").string() + " --var " + (dir / "mill3_inch.var").string() +
                        " --tool-table " + (dir / "mill3_inch.tbl").string() + " --machine-units inch");
  ASSERT_EQ(mm.exit_code, 0) << mm.out;
  ASSERT_EQ(inch.exit_code, 0) << inch.out;
  const auto body = [](const fs::path& path) {  // the program after its header comments
    std::ifstream in(path);
    std::string line, text;
    while (std::getline(in, line))
      if (line.rfind("(volcomp", 0) != 0 && line.rfind("(machine:", 0) != 0 && line.rfind("(tolerance:", 0) != 0)
        text += line + "\n";
    return text;
  };
  const std::string in_mm = body(dir / "mm.ngc");
  EXPECT_GT(in_mm.size(), 1000u);
  EXPECT_EQ(body(dir / "inch.ngc"), in_mm);
  // Read as millimetres, the same files are another machine: the output differs.
  const auto wrong =
      test::run_volcomp(common + " -o " + (dir / "wrong.ngc").string() + " --var " + (dir / "mill3_inch.var").string() +
                        " --tool-table " + (dir / "mill3_inch.tbl").string());
  EXPECT_NE(body(dir / "wrong.ngc"), in_mm);

  std::ofstream(dir / "inch.ini") << "[TRAJ]\nCOORDINATES = X Y Z\nLINEAR_UNITS = inch\n[JOINT_0]\nHOME = 1\n";
  const auto refused = test::run_volcomp(common + " -o " + (dir / "start.ngc").string() + " --var " +
                                         (dir / "mill3_inch.var").string() + " --start " + (dir / "inch.ini").string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.out.find("inch.ini:3: error: --start: the INI's LINEAR_UNITS is inch: give --machine-units inch"),
            std::string::npos)
      << refused.out;
  const auto bad = test::run_volcomp(common + " -o " + (dir / "bad.ngc").string() + " --machine-units furlong");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.out.find("--machine-units must be mm or inch"), std::string::npos) << bad.out;
}

TEST(PredistortCli, WorksAsAnAxisFilter) {
  // AXIS runs `filter PROGRAM`, reads the program from stdout and FILTER_PROGRESS=n from stderr.
  const std::string command = "AXIS_PROGRESS_BAR=1 " + std::string(VC_VOLCOMP) + " predistort " +
                              test::machine_path("mill3") + " -o - --var " + program("mill3.var") + " --tool-table " +
                              program("mill3.tbl") + " -q " + program(kPocket.program);
  const fs::path dir = test::run_folder("predistort_filter");
  const int status =
      std::system((command + " > " + (dir / "out.ngc").string() + " 2> " + (dir / "err.txt").string()).c_str());
  EXPECT_EQ(WEXITSTATUS(status), 0);
  std::ifstream err(dir / "err.txt"), out(dir / "out.ngc");
  const std::string errors((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  std::string first;
  std::getline(out, first);
  EXPECT_EQ(first, "%");
  EXPECT_NE(errors.find("FILTER_PROGRESS=100\n"), std::string::npos) << errors;
  EXPECT_EQ(errors.find("error"), std::string::npos) << errors;
}

// A program that calls a subroutine file on the subroutine path: the output is flat (no O
// word, no call), each executed line once per execution, and the line map says where each
// output line comes from.
TEST(PredistortCli, FlattensSubroutinesAndMapsOutputLinesToTheirSource) {
  const fs::path dir = test::run_folder("predistort_flat");
  fs::create_directories(dir / "subs");
  std::ofstream(dir / "subs" / "slot.ngc") << "o<slot> sub\nG1 X#1 F300\nG1 X0\no<slot> endsub\n";
  std::ofstream(dir / "p.ngc") << "G21 G90 G54\nG0 X0 Y0 Z5\no1 repeat [2]\no<slot> call [20]\no1 endrepeat\nM2\n";
  const auto r =
      test::run_volcomp("predistort " + test::machine_path("mill3") + " " + (dir / "p.ngc").string() + " -o " +
                        (dir / "out.ngc").string() + " --var " + program("mill3.var") + " --subroutine-path " +
                        (dir / "subs").string() + " --line-map " + (dir / "map.csv").string() + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::ifstream out(dir / "out.ngc"), map(dir / "map.csv");
  std::vector<std::string> lines, rows;
  for (std::string line; std::getline(out, line);) lines.push_back(line);
  for (std::string row; std::getline(map, row);) rows.push_back(row);
  ASSERT_EQ(rows.size(), lines.size() + 1);
  EXPECT_EQ(rows[0], "output_line,input_file,input_line");
  std::vector<std::string> program_rows(rows.end() - 7, rows.end());  // after the header
  const std::string p = (dir / "p.ngc").string(), slot = (dir / "subs" / "slot.ngc").string();
  auto row = [&](std::size_t from_end, const std::string& file, int line) {
    return std::to_string(lines.size() - from_end) + "," + file + "," + std::to_string(line);
  };
  EXPECT_EQ(program_rows, (std::vector<std::string>{row(6, p, 1), row(5, p, 2), row(4, slot, 2), row(3, slot, 3),
                                                    row(2, slot, 2), row(1, slot, 3), row(0, p, 6)}))
      << r.out;
  for (std::string line : lines) {
    line = line.substr(0, line.find('('));  // the words, without comments
    EXPECT_EQ(line.find_first_of("oO#"), std::string::npos) << line;
  }
}

// In G93 each piece's F is 1 / its time: the pieces of a move take the move's time, also when
// the move begins with a short piece to its corrected start (after G28 here), which takes
// its length's share and not the whole move's time.
TEST(PredistortCli, InverseTimeMovesKeepTheirDuration) {
  const fs::path dir = test::run_folder("predistort_g93");
  std::ofstream(dir / "p.ngc") << "G21 G90 G54\nG0 X0 Y0 Z5\nG28\nG93 G1 X100 Y50 Z-5 F2\nG1 X200 F4\nG94\nM2\n";
  const auto r = test::run_volcomp("predistort " + test::machine_path("mill3") + " " + (dir / "p.ngc").string() +
                                   " -o " + (dir / "out.ngc").string() + " --var " + program("mill3.var") + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::ifstream out(dir / "out.ngc");
  std::vector<double> minutes;  // per output move after the G93
  bool inverse = false;
  for (std::string line; std::getline(out, line);) {
    if (line.find("G93") != std::string::npos) inverse = true;
    if (line.find("G94") != std::string::npos) inverse = false;
    const auto f = line.find('F');
    if (inverse && f != std::string::npos && line[0] != '(') minutes.push_back(1.0 / std::stod(line.substr(f + 1)));
  }
  ASSERT_GT(minutes.size(), 4u);
  // The first move (F2: 0.5 min) is its pieces up to where the second (F4: 0.25 min) begins.
  double total = 0;
  for (double m : minutes) total += m;
  EXPECT_NEAR(total, 0.75, 0.75 * 1e-4);  // the lead adds its few micrometres' share only
  EXPECT_LT(minutes.front(), 1e-3);       // the lead: not the move's 0.5 min
}

// A G64 without P gets the tolerance as P in the program's units: 0.0005 mm in a G20 program is
// P0.0000197 (inches), not P0.0005 (12.7 um).
TEST(PredistortCli, PathBlendingToleranceIsWrittenInTheProgramsUnits) {
  const fs::path dir = test::run_folder("predistort_g64_inch");
  std::ofstream(dir / "p.ngc") << "G20 G90 G54\nG64\nG0 X0 Y0 Z1\nG21\nG64\nM2\n";
  const auto r = test::run_volcomp("predistort " + test::machine_path("mill3") + " " + (dir / "p.ngc").string() +
                                   " -o - -q --var " + program("mill3.var"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("\nG64 P0.0000197 Q0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\nG64 P0.0005 Q0\n"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace vc
