// Internal: the chart-free equations of motion (docs/paper_notes.md) and an odeint driver with a
// step bound. The join's sensitivities (SensitivityRhs) are the variational equations written out
// by hand (tests/fehlberg78_test.cc checks them against ceres::Jet on the kinematics kernel).
#pragma once

#include <ceres/jet.h>

#include <algorithm>
#include <array>
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
/// y = (z[3], x[2], dz/ds[3], dx/ds[2]). K depends on s, z(0) and x(0) do not.
using SensitivityState = std::array<double, 10>;

/// The right-hand side of OmegaFromZK and ZxRhs with its variational equations written out by
/// hand (forward mode, the derivative d/ds of every line; one division). The same values as
/// evaluating OmegaFromZK and ZxRhs on ceres::Jet<double, 1> (tests/fehlberg78_test.cc checks it)
/// at a third of the instructions: this is the inner loop of every join.
struct SensitivityRhs {
  double lambda;
  double k[2];   ///< K(s)
  double dk[2];  ///< dK/ds
  void operator()(const SensitivityState& y, SensitivityState& dy, double /*t*/) const {
    const double z0 = y[0], z1 = y[1], z2 = y[2], d0 = y[5], d1 = y[6], d2 = y[7];
    // v0 = p / q with p = <K, z_h>, q = z3^2 + lambda |z_h|^2 (OmegaFromZK).
    const double p = k[0] * z0 + k[1] * z1;
    const double dp = dk[0] * z0 + k[0] * d0 + dk[1] * z1 + k[1] * d1;
    const double q = z2 * z2 + lambda * (z0 * z0 + z1 * z1);
    const double dq = 2.0 * (z2 * d2 + lambda * (z0 * d0 + z1 * d1));
    const double inv_q = 1.0 / q;
    const double v0 = p * inv_q;
    const double dv0 = (dp - v0 * dq) * inv_q;
    const double c = lambda - 1.0;
    const double w0 = k[0] - c * v0 * z0, w1 = k[1] - c * v0 * z1;
    const double dw0 = dk[0] - c * (dv0 * z0 + v0 * d0), dw1 = dk[1] - c * (dv0 * z1 + v0 * d1);
    // z' = omega x z, x' = (omega_2, -omega_1) (ZxRhs) and their derivatives.
    dy[0] = w1 * z2;
    dy[1] = -w0 * z2;
    dy[2] = w0 * z1 - w1 * z0;
    dy[3] = w1;
    dy[4] = -w0;
    dy[5] = dw1 * z2 + w1 * d2;
    dy[6] = -(dw0 * z2 + w0 * d2);
    dy[7] = dw0 * z1 + w0 * d1 - (dw1 * z0 + w1 * d0);
    dy[8] = dw1;
    dy[9] = -dw0;
  }
};

/// The motion alone, y = (z[3], x[2]): the join's check of a point whose Jacobian is known.
using MotionState = std::array<double, 5>;
struct MotionRhs {
  double lambda;
  double k[2];
  void operator()(const MotionState& y, MotionState& dy, double /*t*/) const {
    double w[2];
    OmegaFromZK(y.data(), k, lambda, w);
    ZxRhs(y.data(), w, dy.data(), dy.data() + 3);
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
#if !defined(__clang__)  // clang knows no -Wmaybe-uninitialized and warns about the pragma itself
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
template <typename Stepper = void, typename State, typename Rhs, typename Observer>
double IntegrateAdaptive(const Rhs& rhs,
                         State& y,
                         double t0,
                         double t1,
                         double dt0,
                         const IntegrationOptions& options,
                         Observer&& observer) {
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
        if (!std::isfinite(v))
          throw std::runtime_error("integration produced a non-finite state at t = " + std::to_string(t_before));
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
double IntegrateAdaptive(
    const Rhs& rhs, State& y, double t0, double t1, double dt0, const IntegrationOptions& options) {
  return IntegrateAdaptive(rhs, y, t0, t1, dt0, options, [](double, const State&) {});
}

/// Integrates y from times[0] forward with Dormand-Prince 5(4) and its continuous extension
/// (odeint's dense output), calling observer(i, y_i) with the state at each of the non-decreasing
/// times[i] in order: one pass over a whole track at the steps the tolerance needs, however dense
/// the times (IntegrateAdaptive would stop at every time). The same step limit and finiteness
/// checks as IntegrateAdaptive.
template <typename State, typename Rhs, typename Observer>
void IntegrateDenseAtTimes(const Rhs& rhs,
                           const State& y0,
                           const double* times,
                           std::size_t n,
                           double dt0,
                           const IntegrationOptions& options,
                           Observer&& observer) {
  namespace odeint = boost::numeric::odeint;
  if (n == 0) return;
  auto stepper = odeint::make_dense_output(
      options.absolute_tolerance, options.relative_tolerance, odeint::runge_kutta_dopri5<State>());
  std::size_t i = 0;
  for (; i < n && times[i] == times[0]; ++i) observer(i, y0);
  if (i == n) return;
  stepper.initialize(y0, times[0], std::min(dt0, times[n - 1] - times[0]));
  State y;
  long steps = 0;
  while (i < n) {
    if (++steps > options.max_steps)
      throw StepLimitError("integration exceeded max_steps = " + std::to_string(options.max_steps) +
                           " at t = " + std::to_string(stepper.current_time()));
    stepper.do_step(rhs);
    for (double v : stepper.current_state())
      if (!std::isfinite(v))
        throw std::runtime_error("integration produced a non-finite state at t = " +
                                 std::to_string(stepper.previous_time()));
    for (; i < n && times[i] <= stepper.current_time(); ++i) {
      stepper.calc_state(times[i], y);
      observer(i, static_cast<const State&>(y));
    }
  }
}

}  // namespace plateball::internal
