// The contact-point velocity and acceleration of a free arc (src/arc.h), as the planner's arcs
// measure them for the bounds: checked against forward-mode Jets and central differences.
#include "arc.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <string>
#include <utility>

#include "kinematics.h"

TEST(ContactVelocityAndAcceleration, HandDerivativeEqualsJetForwardModeAndFiniteDifferences) {
  // x'' = d/dt (omega_2, -omega_1) along z' = omega x z at constant K: the hand derivative against
  // forward-mode Jets through OmegaFromZK and against central differences along z'.
  using Jet = ceres::Jet<double, 1>;
  for (double lambda : {0.5, 1.0, 2.0, 7.0}) {
    for (int trial = 0; trial < 8; ++trial) {
      const double th = 0.3 + 0.37 * trial, ph = -1.0 + 0.61 * trial;
      const double z[3] = {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)};
      const double k[2] = {0.7 - 0.2 * trial, 0.4 + 0.15 * trial};
      double w[2], acc[2], w_ref[2];
      plateball::internal::ContactVelocityAndAcceleration(lambda, z, k, w, acc);
      plateball::internal::OmegaFromZK(z, k, lambda, w_ref);
      EXPECT_EQ(w[0], w_ref[0]);
      EXPECT_EQ(w[1], w_ref[1]);
      const double dz[3] = {w[1] * z[2], -w[0] * z[2], w[0] * z[1] - w[1] * z[0]};
      Jet zj[3], kj[2] = {Jet(k[0]), Jet(k[1])}, wj[2];
      for (int i = 0; i < 3; ++i) zj[i] = Jet(z[i]), zj[i].v[0] = dz[i];
      plateball::internal::OmegaFromZK(zj, kj, lambda, wj);
      EXPECT_NEAR(acc[0], wj[1].v[0], 1e-14 * (1 + std::abs(wj[1].v[0])));
      EXPECT_NEAR(acc[1], -wj[0].v[0], 1e-14 * (1 + std::abs(wj[0].v[0])));
      const double h = 1e-5;
      double zp[3], zm[3], wp[2], wm[2];
      for (int i = 0; i < 3; ++i) zp[i] = z[i] + h * dz[i], zm[i] = z[i] - h * dz[i];
      plateball::internal::OmegaFromZK(zp, k, lambda, wp);
      plateball::internal::OmegaFromZK(zm, k, lambda, wm);
      EXPECT_NEAR(acc[0], (wp[1] - wm[1]) / (2 * h), 1e-8);
      EXPECT_NEAR(acc[1], -(wp[0] - wm[0]) / (2 * h), 1e-8);
      const Eigen::Vector2d a = plateball::internal::ContactAcceleration(
          lambda, Eigen::Vector3d(z[0], z[1], z[2]), Eigen::Vector2d(k[0], k[1]));
      EXPECT_EQ(a.x(), acc[0]);
      EXPECT_EQ(a.y(), acc[1]);
    }
  }
}

namespace {

// The largest |x'| and |x''| of the arc from (z0, K) over [0, t] at 2001 equally spaced times,
// z integrated between them by odeint's dopri5 at 1e-13 (independent of arc.cc's closed forms).
std::pair<double, double> DenselySampledMaxima(double lambda,
                                               const Eigen::Vector3d& z0,
                                               const Eigen::Vector2d& k,
                                               double t) {
  namespace odeint = boost::numeric::odeint;
  using State = std::array<double, 3>;
  const auto rhs = [&](const State& z, State& dz, double) {
    double w[2];
    plateball::internal::OmegaFromZK(z.data(), k.data(), lambda, w);
    dz = {w[1] * z[2], -w[0] * z[2], w[0] * z[1] - w[1] * z[0]};
  };
  State z{z0.x(), z0.y(), z0.z()};
  double max_v = 0.0, max_a = 0.0;
  constexpr int kPoints = 2000;
  for (int i = 0; i <= kPoints; ++i) {
    if (i > 0)
      odeint::integrate_adaptive(odeint::make_controlled(1e-13, 1e-13, odeint::runge_kutta_dopri5<State>()),
                                 rhs,
                                 z,
                                 t * (i - 1) / kPoints,
                                 t * i / kPoints,
                                 t / kPoints);
    double w[2], acc[2];
    plateball::internal::ContactVelocityAndAcceleration(lambda, z.data(), k.data(), w, acc);
    max_v = std::max(max_v, std::hypot(w[0], w[1]));
    max_a = std::max(max_a, std::hypot(acc[0], acc[1]));
  }
  return {max_v, max_a};
}

}  // namespace

TEST(ArcDerivativeMaxima, NeverBelowADenseIndependentSampling) {
  // max |x'| is exact (a function of z3^2 decreasing in it): equal to the dense maximum up to the
  // sampling's own shortfall; max |x''| (samples plus the largest change) never below it. Arcs from
  // 0.01 (T2 at n = 1024) to more than a period, lambda below, at and above 1, mu != 1.
  for (double lambda : {0.5, 1.0, 2.0, 7.0}) {
    for (int trial = 0; trial < 6; ++trial) {
      const double th = 0.2 + 0.5 * trial, ph = -1.0 + 0.61 * trial;
      const Eigen::Vector3d z0(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
      const Eigen::Vector2d k(0.7 - 0.25 * trial, 0.4 + 0.15 * trial);
      for (double t : {0.01, 0.13, 0.8, 2.5, 7.0}) {
        SCOPED_TRACE("lambda " + std::to_string(lambda) + ", trial " + std::to_string(trial) + ", t " +
                     std::to_string(t));
        const auto [v, a] = DenselySampledMaxima(lambda, z0, k, t);
        const plateball::internal::ArcMaxima m = plateball::internal::ArcDerivativeMaxima(lambda, z0, k, t);
        EXPECT_GE(m.speed, v - 1e-12);
        EXPECT_LE(m.speed, v + 1e-6 * (1 + v));  // exact: only the dense sampling's shortfall
        EXPECT_GE(m.acceleration, a - 1e-12);
        // A bound, not a gross overestimate (beyond the planner's arcs, t above half a period, the
        // 16 samples are coarser).
        EXPECT_LE(m.acceleration, (t < 3 ? 1.5 : 3.0) * a + 1e-12);
        // The planner's arcs (equal Fehlberg 7(8) steps) report the same maxima.
        plateball::internal::ArcStepHints hints{{0.1, 0.5}, {0.1, 0.5}};
        const plateball::internal::ArcEnd arc = plateball::internal::IntegrateArc(lambda, z0, k, t, {}, &hints);
        EXPECT_EQ(arc.max_speed, m.speed);
        EXPECT_EQ(arc.max_acceleration, m.acceleration);
      }
    }
  }
}

TEST(IntegrateArc, EqualFehlbergStepsAgreeWithAdaptiveDopri5) {
  // The planner's integration (equal Fehlberg 7(8) steps, the step carried from arc to arc, refused
  // steps retried adaptively) and the adaptive dopri5 of the executor: the same (z, x, Phi) to the
  // tolerance's order, for a hint far too long (refused), far too short and none.
  const double lambda = 2.0;
  const Eigen::Vector3d z0 = Eigen::Vector3d(0.5, -0.3, 0.8).normalized();
  const Eigen::Vector2d k(0.6, 0.45);
  for (double hint : {0.0, 5.0, 1e-3, 0.2}) {
    for (double t : {0.01, 0.3, 1.1, 4.0}) {
      plateball::internal::ArcStepHints hints{{hint, 0.5}, {hint, 0.5}};
      const plateball::internal::ArcEnd a = plateball::internal::IntegrateArc(lambda, z0, k, t, {}, &hints);
      const plateball::internal::ArcEnd b = plateball::internal::IntegrateArc(lambda, z0, k, t, {});
      EXPECT_LT((a.z - b.z).norm(), 1e-11);
      EXPECT_LT((a.dx - b.dx).norm(), 1e-11);
      EXPECT_LT((a.phi - b.phi).norm(), 1e-11);
      EXPECT_GT(t >= 0.3 ? hints.fehlberg78.h : hints.dopri5.h, 0.0);
    }
  }
}
