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

#include "kinematics.h"
#include "plateball/integration_options.h"

namespace plateball::internal {

/// Thrown by IntegrateAdaptive when IntegrationOptions::max_steps is exceeded.
struct StepLimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

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
    RotationRhs(w[0], w[1], y.data() + 5, dy.data() + 5);
  }
};

/// A' = hat(e3 x p'(tau)) A for a planar velocity p'(tau) = velocity(tau): rolling along a curve
/// (section 2.2), A row-major.
using RowMajor3x3 = std::array<double, 9>;
template <typename Velocity>
struct RollingRhs {
  Velocity velocity;
  void operator()(const RowMajor3x3& a, RowMajor3x3& da, double tau) const {
    double w0, w1;
    RollingOmega(velocity(tau), &w0, &w1);
    RotationRhs(w0, w1, a.data(), da.data());
  }
};
template <typename Velocity>
RollingRhs(Velocity) -> RollingRhs<Velocity>;

/// (z0, x = 0, Phi = I): the start of a free arc.
inline FullState InitialFullState(const Eigen::Vector3d& z0) {
  FullState y{};
  y[0] = z0.x();
  y[1] = z0.y();
  y[2] = z0.z();
  y[5] = y[9] = y[13] = 1.0;
  return y;
}

/// Integrates y from t0 to t1 (either direction) with a controlled explicit Runge-Kutta stepper
/// (Dormand-Prince 5(4) unless another odeint error stepper is named), calling observer(t, y)
/// after every accepted step (and at t1). An observer that returns bool stops the integration by
/// returning false. Returns the time reached (t1 unless stopped). Throws StepLimitError when
/// options.max_steps is exceeded, std::runtime_error when the state stops being finite or the step
/// underflows. The one adaptive loop of the library.
// Boost 1.74's generic RK steppers (rkf78) trip GCC's -Wuninitialized on their unused copy constructor.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
template <typename Stepper = void, typename State, typename Rhs, typename Observer>
double IntegrateAdaptive(const Rhs& rhs, State& y, double t0, double t1, double dt0,
                         const IntegrationOptions& options, Observer&& observer) {
  namespace odeint = boost::numeric::odeint;
  using ErrorStepper = std::conditional_t<std::is_void_v<Stepper>, odeint::runge_kutta_dopri5<State>, Stepper>;
  auto stepper = odeint::make_controlled(options.absolute_tolerance, options.relative_tolerance, ErrorStepper());
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
#pragma GCC diagnostic pop

template <typename State, typename Rhs>
double IntegrateAdaptive(const Rhs& rhs, State& y, double t0, double t1, double dt0,
                         const IntegrationOptions& options) {
  return IntegrateAdaptive(rhs, y, t0, t1, dt0, options, [](double, const State&) {});
}

}  // namespace plateball::internal
