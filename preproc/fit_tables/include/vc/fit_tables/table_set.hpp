// A controller's tables resolved against one machine: which joint feeds each table, which
// joint it corrects, where its nodes lie; and the correction the set applies, exactly as the
// controller interpolates (interpolation.hpp).
//
// The correction is linear in the tables' node values x (the unknowns of the fit): the
// controller commands q + c(q, x) for the nominal joints q, c(q, x) = B(q) x, each table adding
// its interpolated value to its output joint, all tables of a joint summed.
// Units of x: a table correcting a linear joint holds mm, a rotary joint deg; a squareness
// value is a ratio (mm of the output per mm of the input: the angle's tangent).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "vc/fit_tables/controller.hpp"
#include "vc/machine/model.hpp"

namespace vc::fit_tables {

struct Table {
  TableKind kind = TableKind::Positioning;
  int input = -1, output = -1;  // joints
  // Node positions (mm or deg), equally spaced over the input joint's travel, both ends
  // included; empty for a squareness value.
  std::vector<double> nodes;
  // The input is read modulo 360 deg: its last node is its first one (one unknown for both).
  bool modulo = false;
  bool direction_dependent = false;
  double resolution = 0.0;  // in the unit of x (mm, deg or ratio); 0: exact
  int first_unknown = 0;    // index of its first node's value in x
  // The deviations whose cancelling the usual practice puts in this table (ISO 230-1 symbols):
  // positioning of X: EXX, of C: ECC; cross X -> Y: EYX; squareness Y -> X: EC0X and EC0Y.
  std::vector<std::string> own_deviations;

  int unknowns() const { return kind == TableKind::Squareness ? 1 : static_cast<int>(nodes.size()) - (modulo ? 1 : 0); }
  // The unknown that holds node k's value (the last node of a modulo table is the first).
  int unknown_of_node(int k) const {
    return first_unknown + (modulo && k == static_cast<int>(nodes.size()) - 1 ? 0 : k);
  }
};

struct TableSet {
  std::vector<Table> tables;
  int unknowns = 0;
  std::vector<std::string> notes;  // tables of the controller this machine cannot use, and why
  std::string name(const machine::Model& model, const Table& table) const;  // "X", "X->Y", "Y->X squareness"
};

// Resolves `controller` against `model`. `nodes` (if given) replaces every table's default
// node count. A table naming an axis the machine lacks is skipped with a note; so is a cross
// or squareness table whose input or output has the wrong type. Throws std::invalid_argument
// for a node count outside 2 .. the controller's max_nodes.
TableSet resolve_tables(const Controller& controller, const machine::Model& model, std::optional<int> nodes = {});

// One contribution to the correction: c[joint] += weight * x[unknown].
struct Contribution {
  int unknown;
  int joint;
  double weight;
};

// The contributions at nominal joints q (at most two per table), appended to `out` (cleared
// first).
void contributions(const TableSet& set, const machine::Joints& q, std::vector<Contribution>& out);

// q + c(q, x): the joints the controller commands.
machine::Joints compensated(const TableSet& set, const Eigen::VectorXd& x, const machine::Joints& q);

// x rounded to each table's resolution (what the controller stores).
Eigen::VectorXd rounded(const TableSet& set, const Eigen::VectorXd& x);

}  // namespace vc::fit_tables
