#include "vc/shop/selftune_model.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "vc/machine/forward.hpp"

namespace vc::shop {
namespace {

// A tuning table on a copy of the model: its index there and its columns.
struct Probe {
  int joint;
  int table;  // index into the tuned model's tables
  std::vector<tables::ErrorSymbol> columns;
  bool periodic;  // a full turn: the last node is the first (one unknown)
  int nodes;
  int distinct_nodes() const { return periodic ? nodes - 1 : nodes; }
};

// The components to tune on each joint.
std::map<int, std::vector<tables::ErrorSymbol>> selected(const machine::Model& model, const ModelOptions& options) {
  std::map<int, std::vector<tables::ErrorSymbol>> by_joint;
  if (options.deviations.empty()) {
    for (int j = 0; j < model.joint_count(); ++j)
      for (int c = 0; c < 6; ++c) by_joint[j].push_back({c, model.axes[static_cast<std::size_t>(j)].letter, false});
    return by_joint;
  }
  for (const std::string& name : options.deviations) {
    const auto symbol = tables::parse_error_symbol(name);
    if (!symbol || symbol->location)
      throw std::invalid_argument(name + " is not a component error (EXX, EYX, ..., ECC): location errors are "
                                         "tuned through the linear shape of a component");
    const int j = model.joint_of(symbol->axis);
    if (j < 0) throw std::invalid_argument(name + ": the machine has no axis " + std::string(1, symbol->axis));
    auto& list = by_joint[j];
    if (std::none_of(list.begin(), list.end(), [&](const auto& s) { return s.component == symbol->component; }))
      list.push_back(*symbol);
  }
  return by_joint;
}

}  // namespace

std::string tuning_table_name(char axis) {
  return std::string("selftune_") + static_cast<char>(std::tolower(axis)) + ".csv";
}

ModelFit fit_tables(const machine::Model& model, const FirstPart& part, const ModelOptions& options) {
  if (options.nodes < 2 || options.nodes > 101) throw std::invalid_argument("--nodes must be in [2, 101]");
  // Probe tables (all zero) on a copy of the model: the unknowns are their values.
  machine::Model tuned = model;
  std::vector<Probe> probes;
  for (const auto& [joint, columns] : selected(model, options)) {
    const char letter = model.axes[static_cast<std::size_t>(joint)].letter;
    machine::BoundTable bound{zero_table(model, joint, options.nodes, columns, tuning_table_name(letter)), {}};
    bound.joint[0] = joint;
    const bool periodic = bound.table.grid()[0].periodic;
    if (periodic && options.nodes < 3)
      throw std::invalid_argument("--nodes must be at least 3 for the full-turn axis " + std::string(1, letter));
    tuned.axes[static_cast<std::size_t>(joint)].tables.push_back(static_cast<int>(tuned.tables.size()));
    tuned.axes[static_cast<std::size_t>(joint)].moved_by |= 1u << joint;
    probes.push_back({joint, static_cast<int>(tuned.tables.size()), columns, periodic, options.nodes});
    tuned.tables.push_back(std::move(bound));
  }
  struct Unknown {
    int probe, node, column;
  };
  std::vector<Unknown> unknowns;            // probe by probe, node by node, column by column
  std::vector<Eigen::Index> first_unknown;  // of each probe
  for (std::size_t p = 0; p < probes.size(); ++p) {
    first_unknown.push_back(static_cast<Eigen::Index>(unknowns.size()));
    for (int node = 0; node < probes[p].distinct_nodes(); ++node)
      for (std::size_t c = 0; c < probes[p].columns.size(); ++c)
        unknowns.push_back({static_cast<int>(p), node, static_cast<int>(c)});
  }
  // The unknown of a table value (a periodic table's nodes counted round the turn).
  const auto index = [&](int probe, int node, int column) {
    const Probe& pr = probes[static_cast<std::size_t>(probe)];
    node %= pr.distinct_nodes();
    if (node < 0) node += pr.distinct_nodes();
    return first_unknown[static_cast<std::size_t>(probe)] + node * static_cast<Eigen::Index>(pr.columns.size()) + column;
  };
  // The table rows an unknown sets: its node, and the last one too for a periodic table's first.
  const auto set_unknown = [&](tables::ErrorTable& t, const Unknown& x, double value) {
    t.set_value(x.node, x.column, value);
    const Probe& pr = probes[static_cast<std::size_t>(x.probe)];
    if (pr.periodic && x.node == 0) t.set_value(pr.nodes - 1, x.column, value);
  };

  // One equation per kept point: sensitivities by a small value at one node at a time.
  std::vector<const MatchedPoint*> kept;
  for (const MatchedPoint& m : part.points)
    if (!m.outlier) kept.push_back(&m);
  const auto rows = static_cast<Eigen::Index>(kept.size()), cols = static_cast<Eigen::Index>(unknowns.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(rows, cols);
  Eigen::VectorXd b(rows);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const MatchedPoint& m = *kept[static_cast<std::size_t>(k)];
    const Contact& cut = m.cuts.front();
    const PathSample& s0 = part.path[static_cast<std::size_t>(cut.sample)];
    const PathSample& s1 = part.path[static_cast<std::size_t>(cut.sample) + 1];
    const machine::Joints q = s0.joints + cut.u * (s1.joints - s0.joints);
    const Eigen::Vector3d base = machine::tool_pose(tuned, machine::Machine::Real, q, s0.tool_length_mm).tip_mm;
    for (Eigen::Index u = 0; u < cols; ++u) {
      const Unknown& x = unknowns[static_cast<std::size_t>(u)];
      tables::ErrorTable& t = tuned.tables[static_cast<std::size_t>(probes[static_cast<std::size_t>(x.probe)].table)].table;
      const double step = probes[static_cast<std::size_t>(x.probe)].columns[static_cast<std::size_t>(x.column)].quantity() ==
                                  tables::Quantity::Length ? 1e-3 : 1e-5;
      set_unknown(t, x, step);
      const Eigen::Vector3d moved = machine::tool_pose(tuned, machine::Machine::Real, q, s0.tool_length_mm).tip_mm;
      set_unknown(t, x, 0.0);
      a(k, u) = m.point.normal.dot(moved - base) / step;
    }
    b[k] = m.filtered_mm - m.predicted_mm;
  }

  // Unknowns in um and urad (their effects on the tip are then of one size), a ridge relative
  // to the mean diagonal (what the part cannot see stays near zero) and second-difference
  // smoothness.
  ModelFit fit;
  fit.points = static_cast<int>(rows);
  fit.parameters = static_cast<int>(cols);
  Eigen::VectorXd scale(cols);
  for (Eigen::Index u = 0; u < cols; ++u) {
    const Unknown& x = unknowns[static_cast<std::size_t>(u)];
    scale[u] = probes[static_cast<std::size_t>(x.probe)].columns[static_cast<std::size_t>(x.column)].quantity() ==
                       tables::Quantity::Length ? 1e-3 : 1e-6;
  }
  const Eigen::MatrixXd as = a * scale.asDiagonal();
  Eigen::MatrixXd normal = as.transpose() * as;
  const double mean_diagonal = cols ? normal.diagonal().mean() : 0.0;
  for (Eigen::Index u = 0; u < cols; ++u)
    if (normal(u, u) < 1e-12 * mean_diagonal) ++fit.unobservable;
  normal.diagonal().array() += options.regularisation * mean_diagonal;
  // Second differences of scaled values along each table column: x[i-1] - 2 x[i] + x[i+1]
  // (round the turn on a periodic table).
  for (std::size_t p = 0; p < probes.size(); ++p)
    for (std::size_t c = 0; c < probes[p].columns.size(); ++c)
      for (int node = probes[p].periodic ? 0 : 1; node + 1 < options.nodes; ++node) {
        const Eigen::Index i[3] = {index(static_cast<int>(p), node - 1, static_cast<int>(c)),
                                   index(static_cast<int>(p), node, static_cast<int>(c)),
                                   index(static_cast<int>(p), node + 1, static_cast<int>(c))};
        const double w[3] = {1, -2, 1};
        for (int r = 0; r < 3; ++r)
          for (int s = 0; s < 3; ++s) normal(i[r], i[s]) += options.smoothness * mean_diagonal * w[r] * w[s];
      }
  const Eigen::VectorXd xs = normal.ldlt().solve(as.transpose() * b);
  Eigen::VectorXd x(cols);
  for (Eigen::Index u = 0; u < cols; ++u) x[u] = xs[u] * scale[u];
  fit.rms_before_mm = rows ? b.norm() / std::sqrt(static_cast<double>(rows)) : 0.0;
  fit.rms_after_mm = rows ? (b - a * x).norm() / std::sqrt(static_cast<double>(rows)) : 0.0;

  // The tables: an earlier tuning of the axis (same file name) plus this one.
  for (std::size_t p = 0; p < probes.size(); ++p) {
    const Probe& probe = probes[p];
    const char letter = model.axes[static_cast<std::size_t>(probe.joint)].letter;
    std::vector<tables::ErrorSymbol> columns = probe.columns;
    const machine::BoundTable* earlier = nullptr;
    for (int t : model.axes[static_cast<std::size_t>(probe.joint)].tables)
      if (std::filesystem::path(model.tables[static_cast<std::size_t>(t)].table.path()).filename() == tuning_table_name(letter))
        earlier = &model.tables[static_cast<std::size_t>(t)];
    if (earlier)
      for (const auto& c : earlier->table.columns())
        if (std::none_of(columns.begin(), columns.end(), [&](const auto& s) { return s.component == c.symbol.component; }))
          columns.push_back(c.symbol);
    tables::ErrorTable table = zero_table(model, probe.joint, options.nodes, columns, tuning_table_name(letter));
    for (int node = 0; node < options.nodes; ++node) {
      if (earlier) {
        tables::ErrorTable::Sample sample;
        const double at = table.grid()[0].nodes[static_cast<std::size_t>(node)];
        earlier->table.evaluate(&at, sample, false);
        for (std::size_t c = 0; c < earlier->table.columns().size(); ++c)
          for (std::size_t d = 0; d < columns.size(); ++d)
            if (columns[d].component == earlier->table.columns()[c].symbol.component)
              table.set_value(node, static_cast<int>(d), table.value(node, static_cast<int>(d)) + sample.value[c]);
      }
      for (std::size_t c = 0; c < probe.columns.size(); ++c) {
        const double change = x[index(static_cast<int>(p), node, static_cast<int>(c))];
        table.set_value(node, static_cast<int>(c), table.value(node, static_cast<int>(c)) + change);
        if (probe.columns[c].quantity() == tables::Quantity::Length)
          fit.largest_change_mm = std::max(fit.largest_change_mm, std::abs(change));
        else
          fit.largest_change_rad = std::max(fit.largest_change_rad, std::abs(change));
      }
    }
    fit.tables.push_back({probe.joint, tuning_table_name(letter), std::move(table)});
  }
  return fit;
}

}  // namespace vc::shop
