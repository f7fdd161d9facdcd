// Tolerances and limits of the ODE integrations (Boost.Odeint, Dormand-Prince 5(4)).
#pragma once

#include <string>

#include "plateball/export.h"
#include "plateball/field_list.h"

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

  /// The field list (field_list.h): the problem file's "integration" section.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(PLATEBALL_FIELD(absolute_tolerance, "absolute error tolerance of each step").Tolerance(),
             PLATEBALL_FIELD(relative_tolerance, "relative error tolerance of each step").Tolerance(),
             PLATEBALL_FIELD(max_steps, "largest number of accepted + rejected steps of one integration").Counts(1));
  }
};

}  // namespace PLATEBALL_EXPORT
