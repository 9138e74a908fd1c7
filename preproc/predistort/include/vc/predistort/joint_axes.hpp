// Which program axis (X Y Z A B C) each joint of a machine is: LinuxCNC's world coordinates
// in joint order, and back.
#pragma once

#include <string>
#include <string_view>

#include "vc/interpreter/move.hpp"
#include "vc/machine/model.hpp"
#include "vc/tables/source_error.hpp"

namespace vc::predistort {

class JointAxes {
 public:
  // Throws LoadError (naming the machine file) for a joint no program axis has: U, V, W.
  explicit JointAxes(const machine::Model& model) : count_(model.joint_count()) {
    for (int j = 0; j < count_; ++j) {
      const char letter = model.axes[static_cast<std::size_t>(j)].letter;
      axis_[j] = std::string_view(interpreter::kAxisLetters).find(letter);
      if (axis_[j] == std::string_view::npos)
        throw LoadError({model.path}, std::string("axis ") + letter +
                                          ": the pre-distorter writes the program axes X Y Z A B C only; a machine "
                                          "with U, V or W axes is not supported");
    }
  }

  // The world coordinates of the joints' axes, in joint order.
  machine::Joints joints_of(const interpreter::Position& world) const {
    machine::Joints q(count_);
    for (int j = 0; j < count_; ++j) q[j] = world[axis_[j]];
    return q;
  }
  // Sets the joints' axes of `world` to `joints` (the other axes stay).
  void set(interpreter::Position& world, const machine::Joints& joints) const {
    for (int j = 0; j < count_; ++j) world[axis_[j]] = joints[j];
  }
  // The program axes the machine has (bit i of XYZABC).
  unsigned mask() const {
    unsigned axes = 0;
    for (int j = 0; j < count_; ++j) axes |= 1u << axis_[j];
    return axes;
  }

 private:
  int count_;
  std::size_t axis_[machine::kMaxAxes];  // index in interpreter::kAxisLetters
};

}  // namespace vc::predistort
