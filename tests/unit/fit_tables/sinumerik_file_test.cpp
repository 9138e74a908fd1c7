// The Sinumerik files (AX_EEC.INI, NC_CEC.INI): written for the fit, read back by the
// project's reader and applied as the control does (LEC: the axis moves by minus its value; CEC:
// summed onto the output axis; every table read at its input's setpoint, linear, held outside,
// modulo) on top of the real model, they give the fit's M and Delta. Plus the reader's refusals.
#include "vc/fit_tables/sinumerik_file.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "vc/fit_tables/study.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::fit_tables {
namespace {

// M and Delta over `poses` with the joints the Sinumerik commands.
Figures simulated(const machine::Model& model, const std::vector<SinumerikTable>& tables,
                  const std::vector<Pose>& poses) {
  std::vector<double> errors;
  for (const Pose& p : poses)
    errors.push_back(
        (machine::tool_pose(model, machine::Machine::Real, sinumerik_commanded(tables, p.q), p.tool_length_mm).tip_mm -
         machine::tool_pose(model, machine::Machine::Ideal, p.q, p.tool_length_mm).tip_mm)
            .norm() *
        1e3);
  return figures(errors);
}

const SinumerikFile& file_named(const std::vector<SinumerikFile>& files, const std::string& name) {
  for (const SinumerikFile& f : files)
    if (f.file_name == name) return f;
  throw std::runtime_error("no file " + name);
}

TEST(FitTablesSinumerikFile, ReadBackAndAppliedAsTheControlDoesGivesTheFitsFigures) {
  const machine::Model model = machine::load_machine(test::machine_path("mc300"));
  const Controller controller = load_controller(controller_file("source14"));
  EXPECT_EQ(controller.format, "sinumerik-lec-cec");
  StudyOptions o;
  o.tool_lengths_mm = {0, 100, 200};
  o.fresh_poses = 300;
  const Study s = run_study(model, controller, o);

  const SinumerikResolution res = sinumerik_resolution(controller);
  EXPECT_DOUBLE_EQ(res.mm, 1e-4);   // 0.1 um
  EXPECT_DOUBLE_EQ(res.deg, 1e-4);  // 0.0001 deg
  const std::vector<SinumerikFile> files = sinumerik_files(model, s.set, s.modified, res);
  ASSERT_EQ(files.size(), 2u);
  const SinumerikFile& eec = file_named(files, "AX_EEC.INI");
  const SinumerikFile& cec = file_named(files, "NC_CEC.INI");
  EXPECT_EQ(eec.text.rfind("%_N_AX_EEC_INI\nCHANDATA(1)\n", 0), 0u) << eec.text;
  EXPECT_EQ(cec.text.rfind("%_N_NC_CEC_INI\nCHANDATA(1)\n", 0), 0u) << cec.text;
  EXPECT_EQ(eec.text.substr(eec.text.size() - 4), "M17\n");
  // C (AX5) over 0..360 deg is a modulo table; the others are not.
  EXPECT_NE(eec.text.find("$AA_ENC_COMP_IS_MODULO[0,AX5]=1\n"), std::string::npos) << eec.text;
  EXPECT_NE(eec.text.find("$AA_ENC_COMP_IS_MODULO[0,AX1]=0\n"), std::string::npos) << eec.text;

  std::vector<SinumerikTable> tables = read_sinumerik_file(eec.text, "AX_EEC.INI");
  ASSERT_EQ(tables.size(), 5u);  // X Y Z B C
  const std::vector<SinumerikTable> cross = read_sinumerik_file(cec.text, "NC_CEC.INI");
  ASSERT_EQ(cross.size(), 9u);  // 6 straightness + 3 squareness
  for (const SinumerikTable& t : tables) {
    EXPECT_EQ(t.kind, SinumerikTable::Kind::Lec);
    EXPECT_EQ(t.values.size(), 7u);
    EXPECT_EQ(t.modulo, t.input_axis == 4);
  }
  int two_node = 0;
  for (const SinumerikTable& t : cross) two_node += t.values.size() == 2u;
  EXPECT_EQ(two_node, 3);  // the squareness tables
  tables.insert(tables.end(), cross.begin(), cross.end());

  // Joint by joint: the control's joints are the fit's, q + c(q, x), except for the rounding of
  // a squareness's two end values to 0.1 um (at most 0.05 um each, linear between them): on the
  // MC-300 X is the output of two squareness tables (Y->X, Z->X), Y of one (Z->Y).
  GridSpec grid;
  grid.levels = s.levels;
  grid.tool_lengths_mm = s.fitted_lengths_mm;
  const std::vector<Pose> fitted = grid_poses(model, grid);
  const double bound_mm[] = {2 * 0.05e-3 + 1e-9, 0.05e-3 + 1e-9, 1e-9, 1e-9, 1e-9};
  double largest_mm = 0.0;
  for (const Pose& p : fitted) {
    const machine::Joints a = sinumerik_commanded(tables, p.q), b = compensated(s.set, s.modified, p.q);
    for (int j = 0; j < 5; ++j) {
      ASSERT_LE(std::abs(a[j] - b[j]), bound_mm[j]) << "joint " << j;
      largest_mm = std::max(largest_mm, std::abs(a[j] - b[j]));
    }
  }
  EXPECT_GT(largest_mm, 0.0);  // the rounding is there: the bound above is not vacuous

  // The figures, on the same poses as the study's rows. The joints differ only in X and Y, by
  // at most 0.1 and 0.05 um; a linear axis's change moves the tip by the same amount, so the
  // tip moves by at most sqrt(0.1^2 + 0.05^2) = 0.112 um: M within 0.12 um, Delta (max - min)
  // within twice that.
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
    const Figures f = simulated(model, tables, poses);
    EXPECT_NEAR(f.max_um, r.modified.max_um, 0.12) << r.tool_length_mm << " " << r.set;
    EXPECT_NEAR(f.delta_um, r.modified.delta_um, 0.24) << r.tool_length_mm << " " << r.set;
    EXPECT_LT(f.max_um, 0.5 * r.none.max_um);  // and the tables do compensate
    ++compared;
  }
  EXPECT_EQ(compared, 6);
}

// A hand-written pair of tables: how the evaluator reads them.
const char* const kEec =
    "%_N_AX_EEC_INI\n"
    "CHANDATA(1)\n"
    "; a comment line\n"
    "$AA_ENC_COMP[0,0,AX1]=0.003 ; node 0\n"
    "$AA_ENC_COMP[0,1,AX1]=0.01\n"
    "$AA_ENC_COMP[0,2,AX1]=-0.002\n"
    "$AA_ENC_COMP_STEP[0,AX1]=100.0\n"
    "$AA_ENC_COMP_MIN[0,AX1]=-100.0\n"
    "$AA_ENC_COMP_MAX[0,AX1]=100.0\n"
    "$AA_ENC_COMP_IS_MODULO[0,AX1]=0\n"
    "M17\n";

const char* const kCec =
    "%_N_NC_CEC_INI\n"
    "CHANDATA(1)\n"
    "$AN_CEC[0,0]=0.0\n"
    "$AN_CEC[0,1]=0.004\n"
    "$AN_CEC[0,2]=0.002\n"
    "$AN_CEC[0,3]=0.0\n"
    "$AN_CEC_INPUT_AXIS[0]=(AX2)\n"
    "$AN_CEC_OUTPUT_AXIS[0]=(AX1)\n"
    "$AN_CEC_STEP[0]=120.0\n"
    "$AN_CEC_MIN[0]=0.0\n"
    "$AN_CEC_MAX[0]=360.0\n"
    "$AN_CEC_DIRECTION[0]=0\n"
    "$AN_CEC_MULT_BY_TABLE[0]=0\n"
    "$AN_CEC_IS_MODULO[0]=1\n"
    "M17\n";

TEST(FitTablesSinumerikFile, EvaluatesAsTheControlInterpolates) {
  const std::vector<SinumerikTable> lec = read_sinumerik_file(kEec, "AX_EEC.INI");
  ASSERT_EQ(lec.size(), 1u);
  const SinumerikTable& x = lec[0];
  EXPECT_EQ(x.input_axis, 0);
  EXPECT_NEAR(sinumerik_table_value(x, -300), 0.003, 1e-12);  // held below MIN
  EXPECT_NEAR(sinumerik_table_value(x, 500), -0.002, 1e-12);  // held above MAX
  EXPECT_NEAR(sinumerik_table_value(x, -50), 0.0065, 1e-12);  // linear between nodes
  EXPECT_NEAR(sinumerik_table_value(x, 25), 0.0070, 1e-12);

  const std::vector<SinumerikTable> cec = read_sinumerik_file(kCec, "NC_CEC.INI");
  ASSERT_EQ(cec.size(), 1u);
  EXPECT_TRUE(cec[0].modulo);
  EXPECT_NEAR(sinumerik_table_value(cec[0], 180), 0.003, 1e-12);
  EXPECT_NEAR(sinumerik_table_value(cec[0], 180 + 360), 0.003, 1e-12);  // repeats with period MAX - MIN
  EXPECT_NEAR(sinumerik_table_value(cec[0], -60), 0.001, 1e-12);        // -60 = 300

  // Both on one axis: LEC moves the axis by minus its value, CEC by plus.
  std::vector<SinumerikTable> both = lec;
  both.push_back(cec[0]);
  machine::Joints q(2);
  q << -50.0, 180.0;
  const machine::Joints c = sinumerik_commanded(both, q);
  EXPECT_NEAR(c[0], -50.0 - 0.0065 + 0.003, 1e-12);
  EXPECT_EQ(c[1], 180.0);
}

// The text with one line replaced (1-based), or with a line removed (replacement nullptr).
std::string edited(const std::string& text, int line, const char* replacement) {
  std::string out;
  std::size_t from = 0;
  for (int n = 1; from < text.size(); ++n) {
    const std::size_t end = text.find('\n', from);
    if (n != line) {
      out += text.substr(from, end - from + 1);
    } else if (replacement) {
      out += std::string(replacement) + "\n";
    }
    from = end + 1;
  }
  return out;
}

std::string refusal(const std::string& text) {
  try {
    read_sinumerik_file(text, "bad.INI");
  } catch (const LoadError& e) {
    return e.what();
  }
  return "(read without complaint)";
}

TEST(FitTablesSinumerikFile, RefusesWhatItDoesNotUnderstandWithFileLineColumn) {
  const std::string eec = kEec, cec = kCec;
  ASSERT_NO_THROW(read_sinumerik_file(eec, "ok.INI"));
  // Missing header: line 1 is CHANDATA(1) then.
  EXPECT_EQ(refusal(edited(eec, 1, nullptr)).rfind("bad.INI:1:1: error: expected the header", 0), 0u)
      << refusal(edited(eec, 1, nullptr));
  EXPECT_EQ(refusal(edited(eec, 2, "CHANDATA(2)")).rfind("bad.INI:2:1: error: expected CHANDATA(1)", 0), 0u);
  // A bad index: the node is not a whole number (column of the index).
  EXPECT_EQ(refusal(edited(eec, 5, "$AA_ENC_COMP[0,x,AX1]=0.01")).rfind("bad.INI:5:16: error: the node N", 0), 0u)
      << refusal(edited(eec, 5, "$AA_ENC_COMP[0,x,AX1]=0.01"));
  // A machine axis name that is not AXn.
  EXPECT_EQ(
      refusal(edited(eec, 5, "$AA_ENC_COMP[0,1,X1]=0.01")).rfind("bad.INI:5:18: error: expected a machine axis", 0), 0u)
      << refusal(edited(eec, 5, "$AA_ENC_COMP[0,1,X1]=0.01"));
  // A node beyond (MAX - MIN) / STEP + 1 = 3.
  EXPECT_EQ(refusal(edited(eec, 5, "$AA_ENC_COMP[0,3,AX1]=0.01")).rfind("bad.INI:5:16: error: node 3 is beyond", 0), 0u)
      << refusal(edited(eec, 5, "$AA_ENC_COMP[0,3,AX1]=0.01"));
  // A missing node (reported at the table's first line).
  EXPECT_EQ(
      refusal(edited(eec, 5, nullptr)).rfind("bad.INI:4:1: error: the EEC table of AX1 has no value for node 1", 0), 0u)
      << refusal(edited(eec, 5, nullptr));
  // An unknown variable (column of its name, after '$').
  EXPECT_EQ(
      refusal(edited(cec, 13, "  $AN_CEC_FOO[0]=0")).rfind("bad.INI:13:4: error: unknown variable $AN_CEC_FOO", 0), 0u)
      << refusal(edited(cec, 13, "  $AN_CEC_FOO[0]=0"));
  // An EEC variable in a CEC file is unknown there too.
  EXPECT_NE(refusal(edited(cec, 13, "$AA_ENC_COMP_STEP[0,AX1]=1.0")).find("bad.INI:13:2: error: unknown variable"),
            std::string::npos);
  // A value that is not a number (column of the value).
  EXPECT_EQ(refusal(edited(cec, 4, "$AN_CEC[0,1]=0.0a4")).rfind("bad.INI:4:14: error: '0.0a4' is not a number", 0), 0u)
      << refusal(edited(cec, 4, "$AN_CEC[0,1]=0.0a4"));
  // STEP not giving a whole number of intervals.
  EXPECT_EQ(refusal(edited(cec, 9, "$AN_CEC_STEP[0]=100.0")).rfind("bad.INI:9:17: error: (MAX - MIN) / STEP", 0), 0u)
      << refusal(edited(cec, 9, "$AN_CEC_STEP[0]=100.0"));
  // A direction-dependent table is not read here.
  EXPECT_EQ(refusal(edited(cec, 12, "$AN_CEC_DIRECTION[0]=1")).rfind("bad.INI:12:22: error: $AN_CEC_DIRECTION", 0), 0u)
      << refusal(edited(cec, 12, "$AN_CEC_DIRECTION[0]=1"));
  // A table without its input axis; a value set twice; no M17; text after M17.
  EXPECT_EQ(refusal(edited(cec, 7, nullptr)).rfind("bad.INI:3:1: error: CEC table 0 has no $AN_CEC_INPUT_AXIS", 0), 0u);
  EXPECT_EQ(refusal(edited(cec, 4, "$AN_CEC[0,0]=0.004")).rfind("bad.INI:4:11: error: node 0 is set twice", 0), 0u)
      << refusal(edited(cec, 4, "$AN_CEC[0,0]=0.004"));
  EXPECT_EQ(refusal(edited(cec, 15, nullptr)).rfind("bad.INI:15:1: error: the file ends without M17", 0), 0u)
      << refusal(edited(cec, 15, nullptr));
  EXPECT_EQ(refusal(cec + "$AN_CEC[1,0]=0\n").rfind("bad.INI:16:1: error: '$AN_CEC[1,0]=0' after M17", 0), 0u);
}

TEST(FitTablesSinumerikFile, WritesTheControlsResolutionAndRefusesDirectionDependentTables) {
  const machine::Model model = machine::load_machine(test::machine_path("mill3"));
  const TableSet set = resolve_tables(load_controller(controller_file("source14")), model);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(set.unknowns, 0.0012345);  // 1.2345 um
  const std::vector<SinumerikFile> files = sinumerik_files(model, set, x, {1e-4, 1e-4});
  const std::string& eec = file_named(files, "AX_EEC.INI").text;
  EXPECT_NE(eec.find("$AA_ENC_COMP[0,0,AX1]=-0.0012\n"), std::string::npos) << eec;  // negated, to 0.1 um
  const std::string& cec = file_named(files, "NC_CEC.INI").text;
  EXPECT_NE(cec.find("$AN_CEC[0,0]=0.0012\n"), std::string::npos) << cec;
  EXPECT_NE(cec.find("$AN_CEC_INPUT_AXIS[0]=(AX1)\n$AN_CEC_OUTPUT_AXIS[0]=(AX2)\n"), std::string::npos) << cec;  // X->Y

  // LinuxCNC's tables are direction dependent: no Sinumerik table for them here.
  const TableSet lc = resolve_tables(load_controller(controller_file("linuxcnc")), model);
  EXPECT_THROW(sinumerik_files(model, lc, Eigen::VectorXd::Zero(lc.unknowns), {1e-4, 1e-4}), std::invalid_argument);
}

}  // namespace
}  // namespace vc::fit_tables
