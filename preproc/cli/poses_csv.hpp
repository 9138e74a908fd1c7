// The poses file of `volcomp error` and `volcomp correct`: a CSV with a header of lower-case
// axis letters (x,y,z,b,c for the MC-300), any order, then one pose per row (mm, deg).
#pragma once

#include <string>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::cli {

struct Poses {
  std::vector<std::string> header;      // as written, e.g. {"x","y","z","b","c"}
  std::vector<int> joint_of_column;     // joint index of each header column
  std::vector<machine::Joints> joints;  // one per row, in joint order
  std::vector<int> lines;               // line of each row in the file
};

// Throws vc::LoadError naming file, line and column of the first problem.
Poses read_poses(const std::string& path, const machine::Model& model);

}  // namespace vc::cli
