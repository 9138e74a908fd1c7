#include "vc/identify/rotary_grid.hpp"

#include <cstddef>

namespace vc::identify {

std::vector<std::vector<double>> rotary_grid(const std::vector<std::vector<double>>& positions) {
  std::vector<std::vector<double>> poses;
  std::vector<std::size_t> index(positions.size(), 0);  // an odometer, its first wheel the fastest
  while (true) {
    std::vector<double> pose;
    for (std::size_t r = 0; r < positions.size(); ++r) pose.push_back(positions[r][index[r]]);
    poses.push_back(pose);
    std::size_t r = 0;
    while (r < positions.size() && ++index[r] == positions[r].size()) index[r++] = 0;
    if (r == positions.size()) return poses;
  }
}

}  // namespace vc::identify
