// The rotary poses of a sphere probing plan (volcomp probe-plan --grid B=... --grid C=...):
// every combination of each rotary axis's positions.
#pragma once

#include <vector>

namespace vc::identify {

// `positions[r]`: the positions of the r-th rotary axis (joint order), none empty. Each pose
// holds one position per axis; the first axis varies fastest. No axes: one empty pose.
std::vector<std::vector<double>> rotary_grid(const std::vector<std::vector<double>>& positions);

}  // namespace vc::identify
