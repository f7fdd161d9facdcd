// Internal: a hand-written Dormand-Prince 5(4) step for small fixed-size states (the planner's
// short free arcs, the 14-component (z, x, Phi)), without odeint's generic machinery: the tableau
// of boost::numeric::odeint::runge_kutta_dopri5 (the 5th-order solution is propagated, the error
// is the difference to the embedded 4th-order one, with the first same-as-last stage) and the
// same error measure as odeint's controlled stepper (fehlberg78.h), so that a step accepted here
// is a step odeint's controller would accept. A refused step is the caller's to redo adaptively.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace plateball::internal {

/// One Dormand-Prince 5(4) step of length h from (t, y): y becomes the 5th-order solution at
/// t + h (7 evaluations). Returns odeint's error measure max_i |err_i| / (abs_tol + rel_tol (|y_i|
/// + |h| |y'_i|)) (y and y' at the start of the step): within the tolerances when <= 1.
template <std::size_t N, typename Rhs>
double DormandPrince5Step(
    const Rhs& rhs, std::array<double, N>& y, double t, double h, double abs_tol, double rel_tol) {
  using State = std::array<double, N>;
  State k1, k2, k3, k4, k5, k6, k7, tmp, y5;
  rhs(y, k1, t);
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + h * (1.0 / 5) * k1[i];
  rhs(tmp, k2, t + h / 5);
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + h * ((3.0 / 40) * k1[i] + (9.0 / 40) * k2[i]);
  rhs(tmp, k3, t + h * (3.0 / 10));
  for (std::size_t i = 0; i < N; ++i)
    tmp[i] = y[i] + h * ((44.0 / 45) * k1[i] - (56.0 / 15) * k2[i] + (32.0 / 9) * k3[i]);
  rhs(tmp, k4, t + h * (4.0 / 5));
  for (std::size_t i = 0; i < N; ++i)
    tmp[i] = y[i] + h * ((19372.0 / 6561) * k1[i] - (25360.0 / 2187) * k2[i] + (64448.0 / 6561) * k3[i] -
                         (212.0 / 729) * k4[i]);
  rhs(tmp, k5, t + h * (8.0 / 9));
  for (std::size_t i = 0; i < N; ++i)
    tmp[i] = y[i] + h * ((9017.0 / 3168) * k1[i] - (355.0 / 33) * k2[i] + (46732.0 / 5247) * k3[i] +
                         (49.0 / 176) * k4[i] - (5103.0 / 18656) * k5[i]);
  rhs(tmp, k6, t + h);
  for (std::size_t i = 0; i < N; ++i)
    y5[i] = y[i] + h * ((35.0 / 384) * k1[i] + (500.0 / 1113) * k3[i] + (125.0 / 192) * k4[i] -
                        (2187.0 / 6784) * k5[i] + (11.0 / 84) * k6[i]);
  rhs(y5, k7, t + h);
  double err = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    const double e = h * ((71.0 / 57600) * k1[i] - (71.0 / 16695) * k3[i] + (71.0 / 1920) * k4[i] -
                          (17253.0 / 339200) * k5[i] + (22.0 / 525) * k6[i] - (1.0 / 40) * k7[i]);
    const double scale = abs_tol + rel_tol * (std::abs(y[i]) + std::abs(h) * std::abs(k1[i]));
    err = std::max(err, std::abs(e) / scale);
  }
  y = y5;
  return err;
}

}  // namespace plateball::internal
