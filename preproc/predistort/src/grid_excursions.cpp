#include "vc/predistort/grid_excursions.hpp"

#include <filesystem>

#include "vc/tables/number_text.hpp"

namespace vc::predistort {

void GridExcursions::note(const machine::Model& model, const machine::Joints& q, int line) {
  bool outside = false;
  unsigned counted = 0;  // bit j: the point is counted for joint j already
  for (std::size_t t = 0; t < model.tables.size(); ++t) {
    const machine::BoundTable& bound = model.tables[t];
    const auto& grid = bound.table.grid();
    for (std::size_t v = 0; v < grid.size(); ++v) {
      const int joint = bound.joint[v];
      if (grid[v].periodic || joint < 0) continue;  // (temperatures: their range is checked where set)
      const double x = q[joint];
      const double beyond = x < grid[v].first ? grid[v].first - x : x - grid[v].last;
      if (!(beyond > 0.0)) continue;
      if (by_joint_.empty()) by_joint_.resize(static_cast<std::size_t>(model.joint_count()));
      Worst& worst = by_joint_[static_cast<std::size_t>(joint)];
      // A point counts once per joint, however many of the joint's tables it leaves.
      if (!(counted & (1u << joint))) ++worst.points;
      counted |= 1u << joint;
      outside = true;
      if (beyond > worst.beyond)
        worst = {worst.points, beyond, x, x < grid[v].first ? grid[v].first : grid[v].last, static_cast<int>(t), line};
    }
  }
  points_ += outside;
}

void GridExcursions::add(const GridExcursions& other) {
  points_ += other.points_;
  if (other.by_joint_.empty()) return;
  if (by_joint_.empty()) by_joint_.resize(other.by_joint_.size());
  for (std::size_t j = 0; j < by_joint_.size(); ++j) {
    const Worst& theirs = other.by_joint_[j];
    Worst& ours = by_joint_[j];
    const long points = ours.points + theirs.points;
    if (theirs.beyond > ours.beyond) ours = theirs;
    ours.points = points;
  }
}

std::vector<std::string> GridExcursions::warnings(const machine::Model& model) const {
  std::vector<std::string> out;
  for (std::size_t j = 0; j < by_joint_.size(); ++j) {
    const Worst& w = by_joint_[j];
    if (w.points == 0) continue;
    const machine::Axis& axis = model.axes[j];
    const bool rotary = axis.type == machine::AxisType::Rotary;
    const std::string unit = rotary ? " deg" : " mm";
    // Linear excursions below 0.1 mm in um (a few um past the end is common and harmless to read).
    const std::string beyond = rotary           ? fixed_text(w.beyond, 4) + " deg"
                               : w.beyond < 0.1 ? fixed_text(w.beyond * 1e3, 1) + " um"
                                                : fixed_text(w.beyond, 3) + " mm";
    const std::string table =
        std::filesystem::path(model.tables[static_cast<std::size_t>(w.table)].table.path()).filename().string();
    const std::string letter(1, axis.letter);
    out.push_back("warning: line " + std::to_string(w.line) + ": " + letter + " = " + fixed_text(w.position, 4) + unit +
                  " is " + beyond + " beyond the end of " + table + "'s grid (" + number_text(w.end) + unit +
                  "): the correction there holds the table's end value (" + std::to_string(w.points) + " point" +
                  (w.points == 1 ? "" : "s") + " outside " + letter + "'s grids)");
  }
  return out;
}

}  // namespace vc::predistort
