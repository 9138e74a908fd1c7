// The usual practice, derived from the model (keep_only + a 1-D Gauss-Newton per node), cancels
// each table's own deviation when that deviation is the machine's only one: on the axis's
// measuring line at the nodes to ~1e-9 mm, and (translations and a rotary axis's own
// positioning move the tip the same everywhere) at any pose when the nodes are the measured
// table's own. Its sign and magnitude are the measured table's, read independently.
#include "vc/fit_tables/usual_practice.hpp"

#include <gtest/gtest.h>

#include <random>

#include "test_support.hpp"
#include "vc/machine/deviations.hpp"
#include "vc/machine/forward.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/machine/travel_samples.hpp"

namespace vc::fit_tables {
namespace {

double tip_error_mm(const machine::Model& m, const TableSet& set, const Eigen::VectorXd& x, const machine::Joints& q) {
  const double length = m.tool_length_mm;
  return (machine::tool_pose(m, machine::Machine::Real, compensated(set, x, q), length).tip_mm -
          machine::tool_pose(m, machine::Machine::Ideal, q, length).tip_mm)
      .norm();
}

// The table of `set` whose own deviations include `symbol`.
const Table& table_of(const TableSet& set, const std::string& symbol) {
  for (const Table& t : set.tables)
    for (const std::string& s : t.own_deviations)
      if (s == symbol) return t;
  throw std::runtime_error("no table for " + symbol);
}

// The value of component error `symbol` in the model's tables at joints q (the sum over its
// tables, mill3's EZZ(z) and EZZ(z, y)), core units.
double measured(const machine::Model& model, const std::string& symbol, const machine::Joints& q) {
  const int joint = model.joint_of(symbol.back());
  double sum = 0;
  for (int t : model.axes[static_cast<std::size_t>(joint)].tables) {
    const tables::ErrorTable& table = model.tables[static_cast<std::size_t>(t)].table;
    double at[tables::ErrorTable::kMaxVariables];
    for (std::size_t v = 0; v < table.grid().size(); ++v) at[v] = q[model.joint_of(table.grid()[v].axis)];
    tables::ErrorTable::Sample sample;
    table.evaluate(at, sample, false);
    for (std::size_t c = 0; c < table.columns().size(); ++c)
      if (table.columns()[c].symbol.name() == symbol) sum += sample.value[c];
  }
  return sum;
}

// keep_only(symbol): the usual practice cancels it at the nodes on the measuring line, and
// its values are +-the measured ones (one sign for the whole table).
void cancels_on_its_line(const std::string& machine_name, const std::string& symbol, int nodes) {
  SCOPED_TRACE(machine_name + " " + symbol);
  const machine::Model full = machine::load_machine(test::machine_path(machine_name));
  const machine::Model only = machine::keep_only(full, {symbol});
  const TableSet set = resolve_tables(load_controller(controller_file("source14")), only, nodes);
  const Eigen::VectorXd x = usual_practice(only, set);
  const Table& t = table_of(set, symbol);
  double largest = 0;
  int sign = 0;
  for (std::size_t k = 0; k < t.nodes.size(); ++k) {
    machine::Joints q = reference_pose(only, t.output);
    q[t.input] = t.nodes[k];
    const double before = (machine::tool_pose(only, machine::Machine::Real, q, only.tool_length_mm).tip_mm -
                           machine::tool_pose(only, machine::Machine::Ideal, q, only.tool_length_mm).tip_mm)
                              .norm();
    largest = std::max(largest, before);
    EXPECT_LT(tip_error_mm(only, set, x, q), 1e-9) << "node " << k << " (error before " << before * 1e3 << " um)";
    // In joint units: a linear joint's value is the measured translation (mm); a rotary
    // joint's the measured angle (rad) in deg. Not exactly: the joint moved by c reads the
    // error at q + c, so the value cancelling it is -e(q + c), off -e(q) by the error's slope
    // times c (MC-300 EXX: 3e-4 x 1 um).
    const bool rotary = only.axes[static_cast<std::size_t>(t.output)].type == machine::AxisType::Rotary;
    const double value = x[t.unknown_of_node(static_cast<int>(k))] * (rotary ? M_PI / 180.0 : 1.0);
    const double m = measured(only, symbol, q);
    EXPECT_NEAR(std::abs(value), std::abs(m), 1e-12 + 1e-3 * std::abs(m));
    if (std::abs(m) > 1e-6) {
      const int s = value * m > 0 ? 1 : -1;
      if (sign == 0) sign = s;
      EXPECT_EQ(s, sign) << "node " << k;
    }
  }
  EXPECT_GT(largest, 1e-4);  // the deviation was there to cancel (> 0.1 um somewhere)
}

TEST(FitTablesUsualPractice, CancelsEachPositioningDeviationOnItsLine) {
  for (const char* s : {"EXX", "EYY", "EZZ", "EBB", "ECC"}) cancels_on_its_line("mc300", s, 7);
  for (const char* s : {"EXX", "EYY", "EZZ"}) cancels_on_its_line("mill3", s, 11);
  // (its C line passes through the mid-travel tip: the reference moves the tip off it)
  for (const char* s : {"EXX", "EAA", "ECC"}) cancels_on_its_line("ac_trunnion", s, 9);
}

TEST(FitTablesUsualPractice, CancelsEachStraightnessOnItsLine) {
  for (const char* s : {"EYX", "EZX", "EXY", "EZY", "EXZ", "EYZ"}) cancels_on_its_line("mc300", s, 7);
  for (const char* s : {"EYX", "EZX", "EXY", "EZY", "EXZ", "EYZ"}) cancels_on_its_line("mill3", s, 11);
}

// With the nodes on the measured table's own grid (MC-300 X: 10 mm steps over -600..0, 61
// nodes; C: 5 deg steps, 73), the tables interpolate alike, and a translation error of the
// tool chain or a rotary axis's own positioning is cancelled at every pose of the volume, to
// a few nm: the joint moved by c reads the error c further on, and where the measured table
// bends at a node (EXX: its slope changes by up to 6e-4 there) that shifted reading differs
// from the linear interpolation by slope change x c (6e-4 x 6 um = 4 nm).
TEST(FitTablesUsualPractice, CancelsEverywhereOnTheMeasuredGrid) {
  const machine::Model full = machine::load_machine(test::machine_path("mc300"));
  for (const auto& [symbol, nodes] : std::vector<std::pair<std::string, int>>{{"EXX", 61}, {"EYX", 61}, {"ECC", 73}}) {
    SCOPED_TRACE(symbol);
    const machine::Model only = machine::keep_only(full, {symbol});
    const TableSet set = resolve_tables(load_controller(controller_file("source14")), only, nodes);
    const Eigen::VectorXd x = usual_practice(only, set);
    machine::TravelSamples samples(only);
    double worst = 0;
    for (int k = 0; k < 2000; ++k) worst = std::max(worst, tip_error_mm(only, set, x, samples.next()));
    EXPECT_LT(worst, 1e-5);
  }
}

// A squareness is one number: the slope of the cancelling correction over the input's travel.
// On the MC-300 (EC0Y = -5 arcsec: Y not square to X) the XY value cancels the error's part
// that grows with Y; what is left along Y's line is constant (the rotation about Y's pole also
// moves the tool, an offset no squareness value holds) to < 1 nm.
TEST(FitTablesUsualPractice, SquarenessIsTheSlope) {
  const machine::Model full = machine::load_machine(test::machine_path("mc300"));
  const machine::Model only = machine::keep_only(full, {"EC0Y"});
  const TableSet set = resolve_tables(load_controller(controller_file("source14")), only);
  const Eigen::VectorXd x = usual_practice(only, set);
  const Table& t = table_of(set, "EC0Y");
  EXPECT_NEAR(std::abs(std::atan(x[t.first_unknown])) * 180 / M_PI * 3600, 5.0, 1e-6);
  for (const Table& other : set.tables)
    if (&other != &t) {
      EXPECT_LT(x.segment(other.first_unknown, other.unknowns()).norm(), 1e-12);  // (their deviations are zero)
    }
  machine::Joints q = reference_pose(only);
  const machine::Axis& y = only.axes[static_cast<std::size_t>(t.input)];
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  double spread = 0, before = 0;
  for (int k = 0; k <= 10; ++k) {
    q[t.input] = y.travel_min + (y.travel_max - y.travel_min) * k / 10;
    const double L = only.tool_length_mm;
    const Eigen::Vector3d ideal = machine::tool_pose(only, machine::Machine::Ideal, q, L).tip_mm;
    const Eigen::Vector3d e =
        machine::tool_pose(only, machine::Machine::Real, compensated(set, x, q), L).tip_mm - ideal;
    const Eigen::Vector3d e0 = machine::tool_pose(only, machine::Machine::Real, q, L).tip_mm - ideal;
    if (k == 0) first = e;
    spread = std::max(spread, (e - first).norm());
    before = std::max(before, (e0 - first).norm());
  }
  EXPECT_GT(before, 5e-3);  // 320 mm x 5 arcsec = 7.8 um of it grows with Y
  EXPECT_LT(spread, 1e-6);
}

}  // namespace
}  // namespace vc::fit_tables
