// Tolerances and limits of the ODE integrations (Boost.Odeint, Dormand-Prince 5(4)).
#pragma once

#include <string>

#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

struct IntegrationOptions {
  double absolute_tolerance = 1e-12;
  double relative_tolerance = 1e-12;
  /// Upper bound on accepted + rejected steps of one integration; exceeding it is an error
  /// status (never a hang).
  long max_steps = 2'000'000;
  /// Empty when valid, else a message naming the field, the value and the bound. Each tolerance
  /// must be in [1e-15, 1) (below, the step size underflows in double precision).
  std::string Validate() const;
};

}  // namespace plateball
