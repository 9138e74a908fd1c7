#include "vc/machine/status.hpp"

namespace vc::machine {

const char* describe(Status status) noexcept {
  switch (status) {
    case Status::Ok:
      return "converged";
    case Status::NotConverged:
      return "did not converge within the iteration limit";
    case Status::NonFinite:
      return "non-finite value (NaN or infinity) in the input or the model";
    case Status::Singular:
      return "singular Jacobian: the axes cannot reach this pose";
  }
  return "unknown status";
}

}  // namespace vc::machine
