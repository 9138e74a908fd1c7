// Where corrected points left an error table's grid. Outside its grid a non-periodic table
// holds its end values (machines/README.md, Outside a table): the correction there is the one
// at the grid's end, not a measured one. Per axis the worst point and how many there were, for
//     warning: line 37: X = -601.2000 mm is 1.200 mm beyond the end of x.csv's grid (-600 mm): the
//     correction there holds the table's end value (3 points outside X's grids)
#pragma once

#include <string>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::predistort {

class GridExcursions {
 public:
  // A corrected point of a move of line `line`, joints `q` (mm, deg). Allocates only the
  // first time (one entry per joint).
  void note(const machine::Model& model, const machine::Joints& q, int line);
  void add(const GridExcursions& other);  // of another corrector (a lane of the same program)

  long points() const { return points_; }  // points outside at least one grid
  // One warning per axis with points outside, in joint order (no line ends).
  std::vector<std::string> warnings(const machine::Model& model) const;

 private:
  struct Worst {
    long points = 0;        // points outside a grid of this joint's
    double beyond = 0.0;    // mm or deg past the grid's end
    double position = 0.0;  // the joint there
    double end = 0.0;       // the grid's end it passed
    int table = -1;         // index into Model::tables
    int line = 0;
  };
  std::vector<Worst> by_joint_;
  long points_ = 0;
};

}  // namespace vc::predistort
