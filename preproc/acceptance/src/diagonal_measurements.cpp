#include "vc/acceptance/diagonal_measurements.hpp"

#include <cmath>
#include <map>
#include <set>

#include "vc/tables/number_text.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::acceptance {
namespace {

std::string run_name(int run, identify::Direction d) {
  return "run " + std::to_string(run) + (d == identify::Direction::Up ? "+" : "-");
}

}  // namespace

identify::LaserRuns read_diagonal_runs(const std::string& path, const Diagonal& d) {
  identify::LaserRuns runs = identify::read_laser_runs(path);
  if (runs.rotary) throw LoadError({path}, "the targets are in deg; a diagonal's are distances in mm: target[mm]");
  if (runs.quantity != tables::Quantity::Length)
    throw LoadError({path}, "the deviations are angles; a diagonal's are lengths (deviation[um])");
  // Each reading at a target of the plan; per run and direction the target index -> line.
  using Key = std::pair<int, identify::Direction>;
  std::map<Key, std::map<std::size_t, int>> seen;
  std::map<Key, int> last_line;
  for (identify::Reading& r : runs.readings) {
    std::size_t index = d.targets_mm.size();
    for (std::size_t i = 0; i < d.targets_mm.size(); ++i)
      if (std::abs(r.target - d.targets_mm[i]) <= 5e-4) index = i;
    if (index == d.targets_mm.size())
      throw LoadError({path, r.line}, "target " + number_text(r.target) + " mm is none of the plan's " +
                                          std::to_string(d.targets_mm.size()) + " targets of " + d.name);
    r.target = d.targets_mm[index];
    const Key key{r.run, r.direction};
    if (const auto [it, fresh] = seen[key].emplace(index, r.line); !fresh)
      throw LoadError({path, r.line}, run_name(r.run, r.direction) + " reads target " + std::to_string(index + 1) +
                                          " (" + number_text(r.target) + " mm) again (first on line " +
                                          std::to_string(it->second) + ")");
    last_line[key] = std::max(last_line[key], r.line);
  }
  int up = 0, down = 0, last = 0;
  for (const auto& [key, targets] : seen) {
    (key.second == identify::Direction::Up ? up : down)++;
    last = std::max(last, last_line[key]);
    for (std::size_t i = 0; i < d.targets_mm.size(); ++i)
      if (!targets.count(i))
        throw LoadError({path, last_line[key]},
                        run_name(key.first, key.second) + " (its last reading on this line) has no reading at target " +
                            std::to_string(i + 1) + " (" + number_text(d.targets_mm[i]) + " mm) of " + d.name +
                            ": every run reads every target");
  }
  // The plan's runs are bidirectional: a run read one way only lost its other half.
  for (const auto& [key, targets] : seen) {
    const Key other{key.first, key.second == identify::Direction::Up ? identify::Direction::Down : identify::Direction::Up};
    if (!seen.count(other))
      throw LoadError({path, last_line[key]}, run_name(key.first, key.second) +
                                                  " (its last reading on this line) has no " +
                                                  run_name(other.first, other.second) +
                                                  ": every run of the plan reads both ways");
  }
  if (up < 2 || down < 2)
    throw LoadError({path, last}, std::to_string(up) + (up == 1 ? " run" : " runs") + " + and " +
                                      std::to_string(down) + (down == 1 ? " run" : " runs") +
                                      " - (the last reading on this line): ISO 230-2 needs at least 2 in "
                                      "each direction (it asks for 5), or R and A are unsupported");
  return runs;
}

}  // namespace vc::acceptance
