// Golden-section search for the minimum of a unimodal function on an interval: the line search of
// the reach's closest approach and of the rig planner's flight margins.
#pragma once

#include <algorithm>
#include <cmath>

namespace plateball::internal {

/// The minimum of f, unimodal on [lo, hi], after 40 golden-section steps (the bracket shrinks to
/// 0.618^40 ~ 4e-9 of its width): the smaller of the last two probes, and where it is (`x_min`,
/// when not null). The steps stop early when the probes no longer lie in order (a bracket at the
/// resolution of double).
template <typename F>
double GoldenSection(const F& f, double lo, double hi, double* x_min = nullptr) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
  double fa = f(a), fb = f(b);
  for (int it = 0; it < 40 && a < b; ++it) {
    if (fa < fb) {
      hi = b;
      b = a;
      fb = fa;
      a = hi - g * (hi - lo);
      fa = f(a);
    } else {
      lo = a;
      a = b;
      fa = fb;
      b = lo + g * (hi - lo);
      fb = f(b);
    }
  }
  if (x_min) *x_min = fa < fb ? a : b;
  return std::min(fa, fb);
}

}  // namespace plateball::internal
