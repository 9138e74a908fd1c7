// LinuxCNC's COMP_FILE: the files written for the fit, read back as LinuxCNC 2.9 reads them
// (usrmotLoadComp, EMCMOT_SET_JOINT_COMP: float trims and slopes) and applied as its servo
// thread does (compute_screw_comp) on top of the real model, give the fit's M and Delta: a
// controller simulator for LinuxCNC's tables. Plus the reader's LinuxCNC quirks.
#include "vc/fit_tables/comp_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "test_support.hpp"
#include "vc/fit_tables/study.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::fit_tables {
namespace {

// M and Delta over `poses` with the joints LinuxCNC commands: q + each joint's comp value.
Figures simulated(const machine::Model& model, const std::vector<LinuxcncComp>& comp, const std::vector<int>& joint,
                  const std::vector<Pose>& poses, bool forward) {
  std::vector<double> errors;
  for (const Pose& p : poses) {
    machine::Joints q = p.q;
    for (std::size_t k = 0; k < comp.size(); ++k) q[joint[k]] += linuxcnc_comp_value(comp[k], p.q[joint[k]], forward);
    errors.push_back((machine::tool_pose(model, machine::Machine::Real, q, p.tool_length_mm).tip_mm -
                      machine::tool_pose(model, machine::Machine::Ideal, p.q, p.tool_length_mm).tip_mm)
                         .norm() *
                     1e3);
  }
  return figures(errors);
}

TEST(FitTablesLinuxcncCompFile, ReadBackAndAppliedAsLinuxcncDoesGivesTheFitsFigures) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const Controller controller = load_controller(controller_file("linuxcnc"));
  EXPECT_EQ(controller.format, "linuxcnc-comp-file");
  StudyOptions o;
  o.tool_lengths_mm = {0, 100, 200};
  o.fresh_poses = 300;
  const Study s = run_study(model, controller, o);

  const std::vector<LinuxcncCompFile> files = linuxcnc_comp_files(model, s.set, s.modified);
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(files[4].file_name, "joint_4_c.comp");
  const std::string ini = linuxcnc_ini_lines(files);
  EXPECT_NE(ini.find("[JOINT_3]\nCOMP_FILE = joint_3_b.comp\nCOMP_FILE_TYPE = 1\n"), std::string::npos) << ini;
  std::vector<LinuxcncComp> comp;
  std::vector<int> joint;
  for (const LinuxcncCompFile& f : files) {
    comp.push_back(read_linuxcnc_comp(f.text, 1));
    joint.push_back(f.joint);
    EXPECT_EQ(comp.back().nominal.size(), 7u);  // every line read
  }

  // The same poses as the study's rows: the grid, and the check set after the probe set.
  GridSpec grid;
  grid.levels = s.levels;
  grid.tool_lengths_mm = s.fitted_lengths_mm;
  const std::vector<Pose> fitted = grid_poses(model, grid);
  FreshPoses fresh(model);
  fresh.next(o.fresh_poses, s.fitted_lengths_mm);
  std::vector<double> all = s.fitted_lengths_mm;
  all.insert(all.end(), s.check_lengths_mm.begin(), s.check_lengths_mm.end());
  const std::vector<Pose> check = fresh.next(o.fresh_poses, all);
  int compared = 0;
  for (const ReportRow& r : s.rows) {
    if (!r.fitted_length) continue;
    std::vector<Pose> poses;
    for (const Pose& p : r.set == "grid" ? fitted : check)
      if (p.tool_length_mm == r.tool_length_mm) poses.push_back(p);
    for (bool forward : {true, false}) {  // both directions hold the same values
      const Figures f = simulated(model, comp, joint, poses, forward);
      EXPECT_NEAR(f.max_um, r.modified.max_um, 1e-4) << r.tool_length_mm << " " << r.set;
      EXPECT_NEAR(f.delta_um, r.modified.delta_um, 1e-4) << r.tool_length_mm << " " << r.set;
    }
    ++compared;
  }
  EXPECT_EQ(compared, 6);
}

TEST(FitTablesLinuxcncCompFile, TypeZeroHoldsActualPositions) {
  const std::string type1 = "-10 0.002 -0.001\n0 0.004 0.003\n10 -0.002 0\n";
  const std::string type0 = "-10 -10.002 -9.999\n0 -0.004 -0.003\n10 10.002 10\n";  // actual = nominal - trim
  const LinuxcncComp a = read_linuxcnc_comp(type1, 1), b = read_linuxcnc_comp(type0, 0);
  for (double at : {-20.0, -10.0, -5.0, 0.0, 2.5, 10.0, 30.0})
    for (bool forward : {true, false})
      EXPECT_NEAR(linuxcnc_comp_value(a, at, forward), linuxcnc_comp_value(b, at, forward), 1e-6);
  EXPECT_FLOAT_EQ(linuxcnc_comp_value(a, -20, true), 0.002f);  // held below the first entry
  EXPECT_FLOAT_EQ(linuxcnc_comp_value(a, 30, false), 0.0f);    // held above the last
  EXPECT_NEAR(linuxcnc_comp_value(a, -5, true), 0.003, 1e-9);  // linear between
  EXPECT_NEAR(linuxcnc_comp_value(a, 5, false), 0.0015, 1e-9);
}

TEST(FitTablesLinuxcncCompFile, ReaderKeepsLinuxcncsRules) {
  // usrmotLoadComp stops at the first line that is not three numbers: a comment first loads nothing.
  EXPECT_TRUE(read_linuxcnc_comp("# X axis\n0 0.001 0.001\n", 1).nominal.empty());
  EXPECT_EQ(read_linuxcnc_comp("0 0.001 0.001\n1 0 0\nend\n2 0 0\n", 1).nominal.size(), 2u);
  EXPECT_THROW(read_linuxcnc_comp("0 0 0\n0 0 0\n", 1), std::invalid_argument);  // must increase
  std::ostringstream many;
  for (int k = 0; k < 257; ++k) many << k << " 0 0\n";
  EXPECT_THROW(read_linuxcnc_comp(many.str(), 1), std::invalid_argument);  // EMCMOT_COMP_SIZE 256
}

// The joint's correction period by period: nothing until the joint moves, the table's value held
// while it stands, and a jump reached along LinuxCNC's ramp at half the joint's acceleration
// (checked against the kinematics of a bang-bang move, not the ramp's own formulas).
TEST(FitTablesLinuxcncCompFile, JointCorrectionStartsAtZeroHoldsAndRamps) {
  const LinuxcncComp comp = read_linuxcnc_comp("-100 0.05 -0.05\n100 0.05 -0.05\n", 1);  // 50 um, -50 um reversing
  const double v_max = 100, a_max = 1000, dt = 1e-3;  // INI values: the ramp uses half of each
  LinuxcncCompJoint joint(comp, v_max, a_max, dt);
  for (int n = 0; n < 10; ++n) EXPECT_EQ(joint.next(0.0, 0.0), 0.0) << "standing since the start: no correction";
  EXPECT_FALSE(joint.settled());
  // It moves up: the 50 um are reached as a move at 500 mm/s^2 from rest to rest would, in
  // 2 sqrt(s / a) = 20 ms (the speed limit, 50 mm/s, is not reached), landing exactly.
  int periods = 0;
  double previous = 0.0, fastest = 0.0;
  while (!joint.settled() && periods < 1000) {
    const double c = joint.next(0.001 * periods, 1.0);
    fastest = std::max(fastest, (c - previous) / dt);
    previous = c;
    ++periods;
  }
  EXPECT_EQ(joint.next(0.5, 1.0), 0.05f);
  EXPECT_NEAR(periods * dt, 2 * std::sqrt(0.05 / (0.5 * a_max)), 2 * dt);
  EXPECT_LE(fastest, 0.5 * a_max * (periods * dt / 2) + 0.5 * a_max * dt);  // a triangle's peak speed
  // Standing: held, whatever the position.
  EXPECT_EQ(joint.next(0.5, 0.0), 0.05f);
  // Moving down: the reverse value, -50 um, mirrored: the same time for twice the distance is
  // sqrt(2) longer.
  periods = 0;
  while (joint.next(0.5, -1.0) != -0.05f && periods < 1000) ++periods;
  EXPECT_NEAR((periods + 1) * dt, 2 * std::sqrt(0.1 / (0.5 * a_max)), 2 * dt);
  EXPECT_TRUE(joint.settled());
}

// A homing's move to HOME before the first period (moved_before): the correction is that
// direction's value there from the start, held while the joint stands; no move: still nothing.
TEST(FitTablesLinuxcncCompFile, AHomingMoveAppliesItsDirectionsValueFromTheStart) {
  const LinuxcncComp comp = read_linuxcnc_comp("-100 0.05 -0.05\n100 0.07 -0.03\n", 1);
  LinuxcncCompJoint down(comp, 100, 1000, 1e-3), none(comp, 100, 1000, 1e-3);
  down.moved_before(-0.1, -1);
  none.moved_before(-0.1, 0);
  EXPECT_TRUE(down.settled());
  EXPECT_FLOAT_EQ(down.next(-0.1, 0.0), -0.05f + (0.02f / 200) * 99.9f);  // the reverse column at -0.1
  EXPECT_FALSE(none.settled());
  EXPECT_EQ(none.next(-0.1, 0.0), 0.0);
}

TEST(FitTablesLinuxcncCompFile, HoldsPositioningTablesOnly) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const TableSet s14 = resolve_tables(load_controller(controller_file("source14")), model);
  EXPECT_THROW(linuxcnc_comp_files(model, s14, Eigen::VectorXd::Zero(s14.unknowns)), std::invalid_argument);
}

}  // namespace
}  // namespace vc::fit_tables
