// Internal: a hand-written Fehlberg 7(8) step for small fixed-size states (the join's
// 10-component sensitivity system), without odeint's generic machinery: the same tableau as
// boost::numeric::odeint::runge_kutta_fehlberg78 (the 8th-order solution is propagated, the
// error is h 41/840 (k12 + k13 - k1 - k11)) and the same error measure as odeint's controlled
// stepper, so that a step accepted here is a step odeint's controller would accept.
// IntegrateEqualSteps covers an interval in n equal steps and refuses (returns false, y
// unchanged) as soon as one step's error exceeds the tolerance: the caller then falls back to the
// adaptive loop (dynamics.h, IntegrateAdaptive), so the accuracy control stays that of the
// tolerances given.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

#include "plateball/integration_options.h"

namespace plateball::internal {

/// One Fehlberg 7(8) step of length h from (t, y): y becomes the 8th-order solution at t + h.
/// Returns odeint's error measure max_i |err_i| / (abs_tol + rel_tol (|y_i| + |h| |y'_i|)) (y
/// and y' at the start of the step): the step is within the tolerances when it is <= 1.
template <std::size_t N, typename Rhs>
double Fehlberg78Step(const Rhs& rhs, std::array<double, N>& y, double t, double h, double abs_tol, double rel_tol) {
  using State = std::array<double, N>;
  State k[13], tmp;
  using T = std::pair<int, double>;
  // tmp = y + h (c0 k[J0] + c1 k[J1] + ...): the stage arguments of the tableau, unrolled at
  // compile time (only the non-zero coefficients).
  auto stage = [&](auto... terms) {
    for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + h * ((terms.second * k[terms.first][i]) + ...);
  };
  rhs(y, k[0], t);
  stage(T{0, 2.0 / 27});
  rhs(tmp, k[1], t + h * (2.0 / 27));
  stage(T{0, 1.0 / 36}, T{1, 1.0 / 12});
  rhs(tmp, k[2], t + h / 9);
  stage(T{0, 1.0 / 24}, T{2, 1.0 / 8});
  rhs(tmp, k[3], t + h / 6);
  stage(T{0, 5.0 / 12}, T{2, -25.0 / 16}, T{3, 25.0 / 16});
  rhs(tmp, k[4], t + h * (5.0 / 12));
  stage(T{0, 1.0 / 20}, T{3, 1.0 / 4}, T{4, 1.0 / 5});
  rhs(tmp, k[5], t + h / 2);
  stage(T{0, -25.0 / 108}, T{3, 125.0 / 108}, T{4, -65.0 / 27}, T{5, 125.0 / 54});
  rhs(tmp, k[6], t + h * (5.0 / 6));
  stage(T{0, 31.0 / 300}, T{4, 61.0 / 225}, T{5, -2.0 / 9}, T{6, 13.0 / 900});
  rhs(tmp, k[7], t + h / 6);
  stage(T{0, 2.0}, T{3, -53.0 / 6}, T{4, 704.0 / 45}, T{5, -107.0 / 9}, T{6, 67.0 / 90}, T{7, 3.0});
  rhs(tmp, k[8], t + h * (2.0 / 3));
  stage(T{0, -91.0 / 108},
        T{3, 23.0 / 108},
        T{4, -976.0 / 135},
        T{5, 311.0 / 54},
        T{6, -19.0 / 60},
        T{7, 17.0 / 6},
        T{8, -1.0 / 12});
  rhs(tmp, k[9], t + h / 3);
  stage(T{0, 2383.0 / 4100},
        T{3, -341.0 / 164},
        T{4, 4496.0 / 1025},
        T{5, -301.0 / 82},
        T{6, 2133.0 / 4100},
        T{7, 45.0 / 82},
        T{8, 45.0 / 164},
        T{9, 18.0 / 41});
  rhs(tmp, k[10], t + h);
  stage(T{0, 3.0 / 205}, T{5, -6.0 / 41}, T{6, -3.0 / 205}, T{7, -3.0 / 41}, T{8, 3.0 / 41}, T{9, 6.0 / 41});
  rhs(tmp, k[11], t);
  stage(T{0, -1777.0 / 4100},
        T{3, -341.0 / 164},
        T{4, 4496.0 / 1025},
        T{5, -289.0 / 82},
        T{6, 2193.0 / 4100},
        T{7, 51.0 / 82},
        T{8, 33.0 / 164},
        T{9, 12.0 / 41},
        T{11, 1.0});
  rhs(tmp, k[12], t + h);
  double err = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    const double e = h * (41.0 / 840) * (k[11][i] + k[12][i] - k[0][i] - k[10][i]);
    const double scale = abs_tol + rel_tol * (std::abs(y[i]) + std::abs(h) * std::abs(k[0][i]));
    err = std::max(err, std::abs(e) / scale);
    y[i] += h * ((34.0 / 105) * k[5][i] + (9.0 / 35) * (k[6][i] + k[7][i]) + (9.0 / 280) * (k[8][i] + k[9][i]) +
                 (41.0 / 840) * (k[11][i] + k[12][i]));
  }
  return err;
}

/// The step to try next after steps of length h whose largest error measure was err (<= 1): h
/// lengthened as far as an error ~ h^8 allows with a margin (0.9 err^(-1/8)), at most 1.5 h.
/// Three square roots instead of pow.
inline double LengthenedStep(double h, double err) {
  if (!(err > 0.0)) return 1.5 * h;
  return h * std::min(1.5, 0.9 / std::sqrt(std::sqrt(std::sqrt(err))));
}

/// Integrates y from t0 to t1 in n >= 1 equal steps of `step` (step(w, t, h) advances w from t to
/// t + h and returns its error measure). Returns true when every step met the tolerances (error
/// measure <= 1) and the state stayed finite; otherwise false with y unchanged (the caller
/// integrates adaptively instead). *largest_error (when given): the largest error measure of the
/// steps, from which a caller may lengthen its next steps.
template <std::size_t N, typename Step>
bool EqualSteps(const Step& step, std::array<double, N>& y, double t0, double t1, int n, double* largest_error) {
  std::array<double, N> w = y;
  const double h = (t1 - t0) / n;
  double largest = 0.0;
  for (int i = 0; i < n; ++i) {
    const double err = step(w, t0 + i * h, h);
    if (!(err <= 1.0)) return false;  // also false for a NaN error
    largest = std::max(largest, err);
  }
  for (double v : w)
    if (!std::isfinite(v)) return false;
  y = w;
  if (largest_error != nullptr) *largest_error = largest;
  return true;
}

/// EqualSteps of Fehlberg 7(8) within the tolerances of `options`.
template <std::size_t N, typename Rhs>
bool IntegrateEqualSteps(const Rhs& rhs,
                         std::array<double, N>& y,
                         double t0,
                         double t1,
                         int n,
                         const IntegrationOptions& options,
                         double* largest_error = nullptr) {
  const auto step = [&](std::array<double, N>& w, double t, double h) {
    return Fehlberg78Step(rhs, w, t, h, options.absolute_tolerance, options.relative_tolerance);
  };
  return EqualSteps(step, y, t0, t1, n, largest_error);
}

}  // namespace plateball::internal
