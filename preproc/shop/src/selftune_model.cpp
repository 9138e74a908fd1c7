#include "vc/shop/selftune_model.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "vc/machine/forward.hpp"

namespace vc::shop {
namespace {

// A full turn's table: rows every 10 deg, so that the written table follows the series.
constexpr int kFullTurnRows = 37;

// A tuning table on a copy of the model: its index there and its columns. Over a travel its
// unknowns are the values at `nodes` nodes, linearly interpolated; over a full turn (periodic)
// they are the coefficients of a Fourier series of order `order` (1, cos, sin of the angle,
// cos, sin of twice the angle, ...), written into the table's rows.
struct Probe {
  int joint;
  int table;  // index into the tuned model's tables
  std::vector<tables::ErrorSymbol> columns;
  bool periodic;
  int nodes;                                                               // table rows
  int order = 0;                                                           // periodic: the series' highest harmonic
  int distinct_nodes() const { return periodic ? 2 * order + 1 : nodes; }  // unknowns per column
};

// Term k of a full turn's series (0: 1; 2h - 1: cos h a; 2h: sin h a) at angle `deg`.
double harmonic(int k, double deg) {
  if (k == 0) return 1.0;
  const double h = (k + 1) / 2 * deg * M_PI / 180.0;
  return k % 2 ? std::cos(h) : std::sin(h);
}

// The angle of a full turn's row, deg: the last row's is the first's (the rows are equal).
double turn_angle(const tables::ErrorTable& t, int row) {
  const auto& nodes = t.grid()[0].nodes;
  return nodes[static_cast<std::size_t>(row) + 1 == nodes.size() ? 0 : static_cast<std::size_t>(row)];
}

// One unknown: a tuning table's value (probe, node, column; over a full turn, node is the
// series' term), or a location error of an axis line (joint, component 0..5: X Y Z in mm,
// A B C in rad).
struct Unknown {
  int probe = -1, node = 0, column = 0;
  int joint = -1, component = 0;
  bool location() const { return joint >= 0; }
};

struct Selection {
  std::map<int, std::vector<tables::ErrorSymbol>> tables;  // component errors, by joint
  std::vector<tables::ErrorSymbol> locations;
};

// What to tune: the given symbols, or all six component errors of every axis and the
// location errors of every rotary axis (its line's position and tilt: what a 5-axis part
// shows most).
Selection selected(const machine::Model& model, const ModelOptions& options) {
  Selection out;
  if (options.deviations.empty()) {
    for (int j = 0; j < model.joint_count(); ++j) {
      const machine::Axis& axis = model.axes[static_cast<std::size_t>(j)];
      for (int c = 0; c < 6; ++c) out.tables[j].push_back({c, axis.letter, false});
      if (axis.type == machine::AxisType::Rotary)
        for (int c = 0; c < 6; ++c) out.locations.push_back({c, axis.letter, true});
    }
    return out;
  }
  for (const std::string& name : options.deviations) {
    const auto symbol = tables::parse_error_symbol(name);
    if (!symbol)
      throw std::invalid_argument(name +
                                  " is not an error symbol (component errors EXX, EYX, ..., ECC; location "
                                  "errors EX0C, EA0C, ...)");
    const int j = model.joint_of(symbol->axis);
    if (j < 0) throw std::invalid_argument(name + ": the machine has no axis " + std::string(1, symbol->axis));
    if (symbol->location) {
      if (std::none_of(out.locations.begin(), out.locations.end(),
                       [&](const auto& s) { return s.name() == symbol->name(); }))
        out.locations.push_back(*symbol);
      continue;
    }
    auto& list = out.tables[j];
    if (std::none_of(list.begin(), list.end(), [&](const auto& s) { return s.component == symbol->component; }))
      list.push_back(*symbol);
  }
  return out;
}

double& location_value(machine::Axis& axis, int component) {
  return component < 3 ? axis.location_mm[component] : axis.location_rad[component - 3];
}

// A scatter s per report point reaches prediction k as s |row k of the influence matrix|
// (1 sigma): the median and the largest over the rows.
std::pair<double, double> carried(double scatter_mm, const Eigen::MatrixXd& influence) {
  std::vector<double> sigma(static_cast<std::size_t>(influence.rows()));
  for (Eigen::Index k = 0; k < influence.rows(); ++k)
    sigma[static_cast<std::size_t>(k)] = scatter_mm * influence.row(k).norm();
  std::sort(sigma.begin(), sigma.end());
  return {sigma[sigma.size() / 2], sigma.back()};
}

}  // namespace

std::string tuning_table_name(char axis) {
  return std::string("selftune_") + static_cast<char>(std::tolower(axis)) + ".csv";
}

ModelFit fit_model(const machine::Model& model, const FirstPart& part, const ModelOptions& options,
                   const FirstPart* next) {
  if (options.nodes < 2 || options.nodes > 101) throw std::invalid_argument("--nodes must be in [2, 101]");
  const Selection selection = selected(model, options);
  // Probe tables (all zero) on a copy of the model: the unknowns are their values.
  machine::Model tuned = model;
  std::vector<Probe> probes;
  for (const auto& [joint, columns] : selection.tables) {
    const char letter = model.axes[static_cast<std::size_t>(joint)].letter;
    const bool periodic = zero_table(model, joint, 2, columns, tuning_table_name(letter)).grid()[0].periodic;
    if (periodic && options.nodes < 3)
      throw std::invalid_argument("--nodes must be at least 3 for the full-turn axis " + std::string(1, letter));
    // A full turn: as many harmonics as the periodic nodes would give (5 nodes, 4 distinct:
    // order 2). Nodes 90 deg apart cannot hold a harmonic of order 2 (sin 2a is zero on every
    // node) and leave 29 % of the first between them; a table's errors round a turn are its
    // first harmonics (run-out, wobble, ovality).
    const int rows = periodic ? kFullTurnRows : options.nodes;
    machine::BoundTable bound(zero_table(model, joint, rows, columns, tuning_table_name(letter)));
    bound.joint[0] = joint;
    tuned.axes[static_cast<std::size_t>(joint)].tables.push_back(static_cast<int>(tuned.tables.size()));
    tuned.axes[static_cast<std::size_t>(joint)].moved_by |= 1u << joint;
    probes.push_back({joint, static_cast<int>(tuned.tables.size()), columns, periodic, rows,
                      periodic ? (options.nodes - 1) / 2 : 0});
    tuned.tables.push_back(std::move(bound));
  }
  std::vector<Unknown> unknowns;            // probe by probe, node by node, column by column; then locations
  std::vector<Eigen::Index> first_unknown;  // of each probe
  for (std::size_t p = 0; p < probes.size(); ++p) {
    first_unknown.push_back(static_cast<Eigen::Index>(unknowns.size()));
    for (int node = 0; node < probes[p].distinct_nodes(); ++node)
      for (std::size_t c = 0; c < probes[p].columns.size(); ++c)
        unknowns.push_back({static_cast<int>(p), node, static_cast<int>(c), -1, 0});
  }
  for (const tables::ErrorSymbol& s : selection.locations)
    unknowns.push_back({-1, 0, 0, model.joint_of(s.axis), s.component});
  // The unknown of a table value (a periodic table's nodes counted round the turn).
  const auto index = [&](int probe, int node, int column) {
    const Probe& pr = probes[static_cast<std::size_t>(probe)];
    node %= pr.distinct_nodes();
    if (node < 0) node += pr.distinct_nodes();
    return first_unknown[static_cast<std::size_t>(probe)] + node * static_cast<Eigen::Index>(pr.columns.size()) +
           column;
  };
  const auto quantity = [&](const Unknown& x) {
    return x.location()
               ? (x.component < 3 ? tables::Quantity::Length : tables::Quantity::Angle)
               : probes[static_cast<std::size_t>(x.probe)].columns[static_cast<std::size_t>(x.column)].quantity();
  };
  // Sets an unknown on the tuned model: a table's rows (a periodic table's first is also its
  // last), or a location error (the axis line's placement follows).
  const auto set_unknown = [&](const Unknown& x, double value) {
    if (x.location()) {
      machine::Axis& axis = tuned.axes[static_cast<std::size_t>(x.joint)];
      location_value(axis, x.component) = value;
      axis.real_base = machine::line_placement(axis.pole_mm, axis.location_mm, axis.location_rad);
      return;
    }
    const Probe& pr = probes[static_cast<std::size_t>(x.probe)];
    tables::ErrorTable& t = tuned.tables[static_cast<std::size_t>(pr.table)].table;
    if (!pr.periodic) {
      t.set_value(x.node, x.column, value);
      return;
    }
    // one term of the series (the others are zero while the sensitivities are taken); the
    // last row is the first
    for (int row = 0; row < pr.nodes; ++row) t.set_value(row, x.column, value * harmonic(x.node, turn_angle(t, row)));
  };

  // One equation per kept point: sensitivities by a small value of one unknown at a time.
  std::vector<const MatchedPoint*> kept;
  for (const MatchedPoint& m : part.points)
    if (!m.outlier) kept.push_back(&m);
  const auto rows = static_cast<Eigen::Index>(kept.size()), cols = static_cast<Eigen::Index>(unknowns.size());
  // A point's equation: its normal's share of the tip's move per unknown, where its first cut ran.
  const auto sensitivities = [&](const MatchedPoint& m, const ToolPath& path,
                                 Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>> row) {
    const Contact& cut = m.cuts.front();
    const PathSample& s0 = path[static_cast<std::size_t>(cut.sample)];
    const PathSample& s1 = path[static_cast<std::size_t>(cut.sample) + 1];
    const machine::Joints q = s0.joints + cut.u * (s1.joints - s0.joints);
    const Eigen::Vector3d base = machine::tool_pose(tuned, machine::Machine::Real, q, s0.tool_length_mm).tip_mm;
    for (Eigen::Index u = 0; u < cols; ++u) {
      const Unknown& x = unknowns[static_cast<std::size_t>(u)];
      const double step = quantity(x) == tables::Quantity::Length ? 1e-3 : 1e-5;
      const double before =
          x.location() ? location_value(tuned.axes[static_cast<std::size_t>(x.joint)], x.component) : 0.0;
      set_unknown(x, before + step);
      const Eigen::Vector3d moved = machine::tool_pose(tuned, machine::Machine::Real, q, s0.tool_length_mm).tip_mm;
      set_unknown(x, before);
      row[u] = m.point.normal.dot(moved - base) / step;
    }
  };
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(rows, cols);
  Eigen::VectorXd b(rows);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const MatchedPoint& m = *kept[static_cast<std::size_t>(k)];
    sensitivities(m, part.path, a.row(k));
    b[k] = m.filtered_mm - m.predicted_mm;
  }

  // Unknowns in um and urad (their effects on the tip are then of one size), a ridge relative
  // to the mean diagonal (what the part cannot see stays near zero) and second-difference
  // smoothness along the tables.
  ModelFit fit;
  fit.points = static_cast<int>(rows);
  fit.parameters = static_cast<int>(cols);
  Eigen::VectorXd scale(cols);
  for (Eigen::Index u = 0; u < cols; ++u)
    scale[u] = quantity(unknowns[static_cast<std::size_t>(u)]) == tables::Quantity::Length ? 1e-3 : 1e-6;
  const Eigen::MatrixXd as = a * scale.asDiagonal();
  const Eigen::MatrixXd data = as.transpose() * as;
  const double mean_diagonal = cols ? data.diagonal().mean() : 0.0;
  for (Eigen::Index u = 0; u < cols; ++u)
    if (data(u, u) < 1e-12 * mean_diagonal) ++fit.unobservable;
  Eigen::MatrixXd prior = Eigen::MatrixXd::Zero(cols, cols);
  prior.diagonal().array() += options.regularisation * mean_diagonal;
  // A full turn's series weighed as its values on the nodes --nodes would put round the turn
  // (n = nodes - 1 of them, a apart): the ridge on a term is its sum of squares there (n for
  // the constant, n / 2 for a harmonic), the smoothness that of its second differences,
  // n / 2 (2 - 2 cos h a)^2 for harmonic h.
  const double turn_nodes = options.nodes - 1;
  for (Eigen::Index u = 0; u < cols; ++u) {
    const Unknown& x = unknowns[static_cast<std::size_t>(u)];
    if (x.location() || !probes[static_cast<std::size_t>(x.probe)].periodic) continue;
    const int h = (x.node + 1) / 2;
    const double bend = 2 - 2 * std::cos(2 * M_PI * h / turn_nodes);
    prior(u, u) = (x.node == 0 ? turn_nodes : turn_nodes / 2) *
                  (options.regularisation + options.smoothness * bend * bend) * mean_diagonal;
  }
  // Second differences of scaled values along each table column over a travel:
  // x[i-1] - 2 x[i] + x[i+1].
  for (std::size_t p = 0; p < probes.size(); ++p)
    for (std::size_t c = 0; c < probes[p].columns.size(); ++c)
      for (int node = 1; !probes[p].periodic && node + 1 < options.nodes; ++node) {
        const Eigen::Index i[3] = {index(static_cast<int>(p), node - 1, static_cast<int>(c)),
                                   index(static_cast<int>(p), node, static_cast<int>(c)),
                                   index(static_cast<int>(p), node + 1, static_cast<int>(c))};
        const double w[3] = {1, -2, 1};
        for (int r = 0; r < 3; ++r)
          for (int s = 0; s < 3; ++s) prior(i[r], i[s]) += options.smoothness * mean_diagonal * w[r] * w[s];
      }
  const Eigen::LDLT<Eigen::MatrixXd> solver(data + prior);
  const Eigen::VectorXd xs = solver.solve(as.transpose() * b);
  Eigen::VectorXd x(cols);
  for (Eigen::Index u = 0; u < cols; ++u) x[u] = xs[u] * scale[u];
  fit.rms_before_mm = rows ? b.norm() / std::sqrt(static_cast<double>(rows)) : 0.0;
  const double residual_norm = (b - a * x).norm();
  fit.rms_after_mm = rows ? residual_norm / std::sqrt(static_cast<double>(rows)) : 0.0;

  // How much of each deviation the part determines: the diagonal of the resolution matrix
  // (data + prior)^-1 data, 1 where the points alone fix an unknown, 0 where only the prior
  // does, averaged over the deviation's unknowns.
  const Eigen::MatrixXd resolution_matrix = solver.solve(data);
  const Eigen::VectorXd resolution = resolution_matrix.diagonal();
  // The noise: the influence matrix H = A (A^T A + prior)^-1 A^T maps the report onto the
  // tuned model's prediction at the points; its trace is what the fit spends of them, and a
  // scatter s per point reaches prediction k as s |H row k|.
  fit.effective_unknowns = resolution.sum();
  const double freedom = static_cast<double>(rows) - fit.effective_unknowns;
  // The next part's sensitivities (mm per scaled unknown), for both the noise and the unseen.
  Eigen::MatrixXd next_scaled;
  if (next && !next->points.empty()) {
    Eigen::MatrixXd a_next(static_cast<Eigen::Index>(next->points.size()), cols);
    for (std::size_t k = 0; k < next->points.size(); ++k)
      sensitivities(next->points[k], next->path, a_next.row(static_cast<Eigen::Index>(k)));
    fit.next_points = static_cast<int>(next->points.size());
    next_scaled = a_next * scale.asDiagonal();
  }
  if (rows > 0 && freedom > 0.5) {
    fit.scatter_mm = residual_norm / std::sqrt(freedom);
    const Eigen::MatrixXd gain = solver.solve(as.transpose());  // report -> scaled unknowns
    const Eigen::MatrixXd influence = as * gain;
    std::tie(fit.carried_median_mm, fit.carried_largest_mm) = carried(fit.scatter_mm, influence);
    // The next part's points: the same map from this report onto the tuned model there.
    if (next_scaled.size() > 0)
      std::tie(fit.next_carried_median_mm, fit.next_carried_largest_mm) = carried(fit.scatter_mm, next_scaled * gain);
  }
  // The tuned model's error at the next part's points is next_scaled (resolution - I) x_true
  // plus the noise: the first term is what this part cannot see.
  const Eigen::MatrixXd next_unseen =
      next_scaled.size() > 0
          ? Eigen::MatrixXd(next_scaled * (Eigen::MatrixXd::Identity(cols, cols) - resolution_matrix))
          : Eigen::MatrixXd();
  std::map<std::string, std::pair<double, int>> by_symbol;
  std::map<std::string, std::vector<Eigen::Index>> columns_of;
  for (Eigen::Index u = 0; u < cols; ++u) {
    const Unknown& k = unknowns[static_cast<std::size_t>(u)];
    const tables::ErrorSymbol symbol =
        k.location() ? tables::ErrorSymbol{k.component, model.axes[static_cast<std::size_t>(k.joint)].letter, true}
                     : probes[static_cast<std::size_t>(k.probe)].columns[static_cast<std::size_t>(k.column)];
    auto& [sum, count] = by_symbol[symbol.name()];
    sum += std::clamp(resolution[u], 0.0, 1.0);
    ++count;
    columns_of[symbol.name()].push_back(u);
  }
  for (const auto& [name, value] : by_symbol) fit.seen.push_back({name, value.first / value.second});
  std::sort(fit.seen.begin(), fit.seen.end(), [](const auto& l, const auto& r) { return l.share > r.share; });
  // Per deviation: the largest move of a next point for a unit (norm over its unknowns) of it.
  for (const auto& [name, columns] : columns_of) {
    if (next_unseen.size() == 0) break;
    double largest = 0.0;
    for (Eigen::Index r = 0; r < next_unseen.rows(); ++r) {
      double sum = 0.0;
      for (const Eigen::Index c : columns) sum += next_unseen(r, c) * next_unseen(r, c);
      largest = std::max(largest, std::sqrt(sum));
    }
    const bool angle = quantity(unknowns[static_cast<std::size_t>(columns.front())]) != tables::Quantity::Length;
    fit.next_unseen.push_back({name, angle, largest});
  }
  std::sort(fit.next_unseen.begin(), fit.next_unseen.end(),
            [](const auto& l, const auto& r) { return l.largest_mm_per_unit > r.largest_mm_per_unit; });

  // The location errors: the model's plus the change.
  for (Eigen::Index u = 0; u < cols; ++u) {
    const Unknown& k = unknowns[static_cast<std::size_t>(u)];
    if (!k.location()) continue;
    machine::Axis axis = model.axes[static_cast<std::size_t>(k.joint)];
    const double before = location_value(axis, k.component);
    fit.locations.push_back({k.joint, k.component, before + x[u]});
    (k.component < 3 ? fit.largest_change_mm : fit.largest_change_rad) =
        std::max(k.component < 3 ? fit.largest_change_mm : fit.largest_change_rad, std::abs(x[u]));
  }

  // The tables: an earlier tuning of the axis (same file name) plus this one.
  for (std::size_t p = 0; p < probes.size(); ++p) {
    const Probe& probe = probes[p];
    const char letter = model.axes[static_cast<std::size_t>(probe.joint)].letter;
    std::vector<tables::ErrorSymbol> columns = probe.columns;
    const machine::BoundTable* earlier = nullptr;
    for (int t : model.axes[static_cast<std::size_t>(probe.joint)].tables)
      if (std::filesystem::path(model.tables[static_cast<std::size_t>(t)].table.path()).filename() ==
          tuning_table_name(letter))
        earlier = &model.tables[static_cast<std::size_t>(t)];
    if (earlier)
      for (const auto& c : earlier->table.columns())
        if (std::none_of(columns.begin(), columns.end(),
                         [&](const auto& s) { return s.component == c.symbol.component; }))
          columns.push_back(c.symbol);
    tables::ErrorTable table = zero_table(model, probe.joint, probe.nodes, columns, tuning_table_name(letter));
    for (int node = 0; node < probe.nodes; ++node) {
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
        double change = 0;
        if (!probe.periodic)
          change = x[index(static_cast<int>(p), node, static_cast<int>(c))];
        else
          for (int k = 0; k < probe.distinct_nodes(); ++k)
            change += x[index(static_cast<int>(p), k, static_cast<int>(c))] * harmonic(k, turn_angle(table, node));
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
