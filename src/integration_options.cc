#include "plateball/integration_options.h"

#include <cmath>

#include "check.h"

namespace plateball {

namespace {
bool IsTolerance(double v) { return v >= internal::kMinTolerance && v < 1; }  // false for NaN
// Built only for a bad value: Validate runs on every join (T1 hot path).
std::string ToleranceRange() { return "must be in [" + internal::FormatNumber(internal::kMinTolerance) + ", 1)"; }
}  // namespace

std::string IntegrationOptions::Validate() const {
  // Tolerances below 1e-15 ask for more than double precision gives: the step size underflows.
  if (!IsTolerance(absolute_tolerance))
    return internal::InvalidValueMessage("absolute_tolerance", absolute_tolerance, ToleranceRange());
  if (!IsTolerance(relative_tolerance))
    return internal::InvalidValueMessage("relative_tolerance", relative_tolerance, ToleranceRange());
  if (max_steps < 1) return internal::InvalidValueMessage("max_steps", static_cast<double>(max_steps), "must be >= 1");
  return {};
}

}  // namespace plateball
