// Outcome of a real-time computation: a small code with a static text, no allocation.
#pragma once

namespace vc::machine {

enum class Status {
  Ok = 0,             // converged below the solver tolerances
  NotConverged = -1,  // max_iterations reached with the residual above the tolerances
  NonFinite = -2,     // an input or an intermediate value was NaN or infinite
  Singular = -3,      // the Jacobian cannot be inverted (axis directions degenerate)
};

// A sentence for messages and HAL logs; static storage.
const char* describe(Status status) noexcept;

}  // namespace vc::machine
