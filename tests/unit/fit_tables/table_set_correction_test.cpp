// The correction a table set applies is the controller's: each table read at its input joint's
// commanded position, linear between equally spaced nodes, held outside, modulo 360 where the
// controller says so, summed per output joint. Checked against an independent evaluation: the
// project's own error-table lookup (vc::tables::ErrorTable, linear, periodic over a full turn)
// built on the same nodes and values, and a squareness as value x position.
#include <gtest/gtest.h>

#include <random>

#include "test_support.hpp"
#include "vc/fit_tables/interpolation.hpp"
#include "vc/fit_tables/table_set.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/error_table.hpp"

namespace vc::fit_tables {
namespace {

// The table's value at `position` through vc::tables::ErrorTable (an independent lookup).
double reference_value(const machine::Model& model, const Table& t, const Eigen::VectorXd& x, double position) {
  tables::GridVariable g;
  g.nodes = t.nodes;
  g.periodic = t.modulo;
  g.rotary = model.axes[static_cast<std::size_t>(t.input)].type == machine::AxisType::Rotary;
  g.axis = model.axes[static_cast<std::size_t>(t.input)].letter;
  std::vector<double> values;
  for (std::size_t k = 0; k < t.nodes.size(); ++k) values.push_back(x[t.unknown_of_node(static_cast<int>(k))]);
  const tables::ErrorTable table("reference", {g}, {{tables::ErrorSymbol{0, 'X', false}, {}}}, values,
                                 tables::Interpolation::Linear);
  tables::ErrorTable::Sample sample;
  table.evaluate(&position, sample, false);
  return sample.value[0];
}

void check_against_reference(const std::string& machine_name, const std::string& controller, int nodes) {
  const machine::Model model = machine::load_machine(test::machine_path(machine_name));
  const TableSet set = resolve_tables(load_controller(controller_file(controller)), model, nodes);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd x(set.unknowns);
  for (int k = 0; k < set.unknowns; ++k) x[k] = 0.01 * unit(random);
  int outside = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    machine::Joints q(model.joint_count());
    for (int j = 0; j < model.joint_count(); ++j) {
      const machine::Axis& a = model.axes[static_cast<std::size_t>(j)];
      // 20 % beyond each end of the travel: the held values, and a C beyond one turn
      const double span = a.travel_max - a.travel_min;
      q[j] = a.travel_min + span * (0.5 + 0.7 * unit(random));
      outside += q[j] < a.travel_min || q[j] > a.travel_max;
    }
    machine::Joints expected = machine::Joints::Zero(model.joint_count());  // the correction c
    for (const Table& t : set.tables)
      expected[t.output] +=
          t.kind == TableKind::Squareness ? x[t.first_unknown] * q[t.input] : reference_value(model, t, x, q[t.input]);
    const machine::Joints got = compensated(set, x, q) - q;
    for (int j = 0; j < model.joint_count(); ++j) ASSERT_NEAR(got[j], expected[j], 1e-12) << "joint " << j;
  }
  EXPECT_GT(outside, 100);
}

TEST(FitTablesCorrection, LinuxcncOnTheMc300IsTheErrorTableLookup) { check_against_reference("mc300", "linuxcnc", 7); }
TEST(FitTablesCorrection, Source14OnTheMc300IsTheErrorTableLookup) { check_against_reference("mc300", "source14", 13); }
TEST(FitTablesCorrection, Source14OnMill3IsTheErrorTableLookup) { check_against_reference("mill3", "source14", 5); }

TEST(FitTablesCorrection, HeldOutsideAndModuloOnlyWhereAsked) {
  const std::vector<double> nodes = equally_spaced(0.0, 360.0, 5);  // 0 90 180 270 360
  // Held: below the first node the first value, above the last the last.
  NodeWeights w = node_weights(nodes, false, -10.0);
  EXPECT_EQ(w.low, 0);
  EXPECT_EQ(w.w_low, 1.0);
  w = node_weights(nodes, false, 370.0);
  EXPECT_EQ(w.low, 4);
  EXPECT_EQ(w.w_low, 1.0);
  // Modulo: 370 deg is 10 deg, -45 deg is 315 deg.
  w = node_weights(nodes, true, 370.0);
  EXPECT_EQ(w.low, 0);
  EXPECT_NEAR(w.w_high, 10.0 / 90.0, 1e-15);
  w = node_weights(nodes, true, -45.0);
  EXPECT_EQ(w.low, 3);
  EXPECT_NEAR(w.w_high, 0.5, 1e-15);
  // Between nodes: linear.
  w = node_weights(nodes, false, 135.0);
  EXPECT_EQ(w.low, 1);
  EXPECT_EQ(w.high, 2);
  EXPECT_NEAR(w.w_low, 0.5, 1e-15);
}

}  // namespace
}  // namespace vc::fit_tables
