// How a controller reads a 1-D table at a position: linear between equally spaced nodes, the
// first and last values held outside them, a modulo table (a rotary input over a full turn)
// read at the position taken into its one turn. LinuxCNC's compute_screw_comp() and
// Sinumerik's LEC / CEC do this (controllers/*.toml say where it was checked).
#pragma once

#include <vector>

namespace vc::fit_tables {

// The two nodes around a position and their weights (w_low + w_high = 1): the value there is
// w_low * v[low] + w_high * v[high].
struct NodeWeights {
  int low = 0, high = 0;
  double w_low = 1.0, w_high = 0.0;
};

// `nodes`: equally spaced, increasing, at least 2. `modulo`: the nodes span one turn (360 deg)
// and the position is taken into it first.
NodeWeights node_weights(const std::vector<double>& nodes, bool modulo, double position);

// `count` equally spaced positions from `first` to `last`, both included.
std::vector<double> equally_spaced(double first, double last, int count);

}  // namespace vc::fit_tables
