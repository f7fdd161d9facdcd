// Internal: the chart-free equations of motion (docs/paper_notes.md) and an odeint driver with a
// step bound. Templated on the scalar so that ceres::Jet gives exact sensitivities.
#pragma once

#include <array>
#include <ceres/jet.h>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "plateball/integration_options.h"

namespace plateball::internal {

/// Thrown by IntegrateAdaptive when IntegrationOptions::max_steps is exceeded.
struct StepLimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// omega_h from (z, K): v0 = <K, z_h>/(z3^2 + lambda |z_h|^2), omega_h = K - (lambda-1) v0 z_h.
template <typename T>
inline void OmegaFromZK(const T* z, const T* k, double lambda, T* w) {
  const T v0 = (k[0] * z[0] + k[1] * z[1]) / (z[2] * z[2] + lambda * (z[0] * z[0] + z[1] * z[1]));
  w[0] = k[0] - (lambda - 1.0) * v0 * z[0];
  w[1] = k[1] - (lambda - 1.0) * v0 * z[1];
}

/// z' = omega x z (omega_3 = 0), x' = omega x e3 = (omega_2, -omega_1).
template <typename T>
inline void ZxRhs(const T* z, const T* w, T* dz, T* dx) {
  dz[0] = w[1] * z[2];
  dz[1] = -w[0] * z[2];
  dz[2] = w[0] * z[1] - w[1] * z[0];
  dx[0] = w[1];
  dx[1] = -w[0];
}

/// (z, x) together with their derivatives with respect to s = delta psi:
/// y = (z[3], x[2], dz/ds[3], dx/ds[2]). K depends on s, z(0) and x(0) do not; the variational
/// equations come exactly from evaluating OmegaFromZK and ZxRhs on ceres::Jet (forward mode).
using SensitivityState = std::array<double, 10>;

struct SensitivityRhs {
  double lambda;
  double k[2];   ///< K(s)
  double dk[2];  ///< dK/ds
  void operator()(const SensitivityState& y, SensitivityState& dy, double /*t*/) const {
    using Jet = ceres::Jet<double, 1>;
    Jet z[3], kk[2], w[2], dz[3], dx[2];
    for (int i = 0; i < 3; ++i) {
      z[i].a = y[i];
      z[i].v[0] = y[5 + i];
    }
    for (int i = 0; i < 2; ++i) {
      kk[i].a = k[i];
      kk[i].v[0] = dk[i];
    }
    OmegaFromZK(z, kk, lambda, w);
    ZxRhs(z, w, dz, dx);
    for (int i = 0; i < 3; ++i) {
      dy[i] = dz[i].a;
      dy[5 + i] = dz[i].v[0];
    }
    for (int i = 0; i < 2; ++i) {
      dy[3 + i] = dx[i].a;
      dy[8 + i] = dx[i].v[0];
    }
  }
};

/// Full state y = (z[3], x[2], Phi[9] row-major) with Phi' = hat(omega) Phi.
using FullState = std::array<double, 14>;

struct FullRhs {
  double lambda;
  std::array<double, 2> k;
  void operator()(const FullState& y, FullState& dy, double /*t*/) const {
    double w[2];
    OmegaFromZK(y.data(), k.data(), lambda, w);
    ZxRhs(y.data(), w, dy.data(), dy.data() + 3);
    // hat(w) with w = (w0, w1, 0): rows (0, 0, w1), (0, 0, -w0), (-w1, w0, 0).
    const double* p = y.data() + 5;
    double* d = dy.data() + 5;
    for (int c = 0; c < 3; ++c) {
      d[0 + c] = w[1] * p[6 + c];
      d[3 + c] = -w[0] * p[6 + c];
      d[6 + c] = -w[1] * p[0 + c] + w[0] * p[3 + c];
    }
  }
};

/// Integrates y from t0 to t1 (either direction) with a controlled Dormand-Prince 5(4) stepper,
/// calling observer(t, y) after every accepted step (and at t1). An observer that returns bool
/// stops the integration by returning false. Returns the time reached (t1 unless stopped).
/// Throws std::runtime_error when options.max_steps is exceeded or the state stops being finite.
template <typename State, typename Rhs, typename Observer>
double IntegrateAdaptive(const Rhs& rhs, State& y, double t0, double t1, double dt0,
                         const IntegrationOptions& options, Observer&& observer) {
  namespace odeint = boost::numeric::odeint;
  using Stepper = odeint::runge_kutta_dopri5<State>;
  auto stepper = odeint::make_controlled(options.absolute_tolerance, options.relative_tolerance, Stepper());
  const double dir = t1 >= t0 ? 1.0 : -1.0;
  double t = t0;
  double dt = dir * std::min(std::abs(dt0), std::abs(t1 - t0));
  if (t1 == t0) return t1;
  long steps = 0;
  while (dir * (t1 - t) > 0) {
    if (dir * (t + dt - t1) > 0) dt = t1 - t;
    if (++steps > options.max_steps)
      throw StepLimitError("integration exceeded max_steps = " + std::to_string(options.max_steps) +
                               " at t = " + std::to_string(t));
    const double t_before = t;
    if (stepper.try_step(rhs, y, t, dt) == odeint::success) {
      for (double v : y)
        if (!std::isfinite(v)) throw std::runtime_error("integration produced a non-finite state at t = " + std::to_string(t_before));
      if constexpr (std::is_same_v<decltype(observer(t, y)), bool>) {
        if (!observer(t, y)) return t;
      } else {
        observer(t, y);
      }
    } else if (std::abs(dt) < 1e-14 * std::max(1.0, std::abs(t))) {
      throw std::runtime_error("integration step size underflow at t = " + std::to_string(t));
    }
  }
  return t;
}

template <typename State, typename Rhs>
double IntegrateAdaptive(const Rhs& rhs, State& y, double t0, double t1, double dt0,
                         const IntegrationOptions& options) {
  return IntegrateAdaptive(rhs, y, t0, t1, dt0, options, [](double, const State&) {});
}

}  // namespace plateball::internal
