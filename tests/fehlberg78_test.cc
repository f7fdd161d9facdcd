// The join's integration kernel (src/fehlberg78.h), the planner's one-step Dormand-Prince 5(4)
// (src/dopri5.h), the hand-written variational right-hand side (SensitivityRhs, src/dynamics.h)
// and the Taylor model of the join's first guess (src/contact_series.h), each against an
// independent computation: ceres::Jet forward mode, odeint's steppers, odeint's adaptive dopri5 at
// a tolerance 100 times tighter, a closed form.
#include "fehlberg78.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <initializer_list>

#include "arc.h"
#include "contact_series.h"
#include "dopri5.h"
#include "dynamics.h"

namespace {

using plateball::IntegrationOptions;
using plateball::internal::SensitivityRhs;
using plateball::internal::SensitivityState;

// Agreement of the kernel with the reference integration: both within tolerances of 1e-12 (the
// kernel) and 1e-14 (the reference) over arcs of length <= 3.
constexpr double kAgreement = 1e-13;

// A start of the join's problem (lambda, angles, mu) with the impulse s: the rollout's start state
// and right-hand side, as the join builds them.
struct Arc {
  SensitivityRhs rhs;
  SensitivityState y0;
};
Arc MakeArc(double lambda, const plateball::AngleState& angles, double mu, double s) {
  const auto dir = plateball::internal::DirectionFor(angles, mu, lambda, s);
  Arc a{SensitivityRhs{lambda, {dir.k.x(), dir.k.y()}, {dir.dk_ds.x(), dir.dk_ds.y()}}, {}};
  a.y0 = {dir.z0.x(), dir.z0.y(), dir.z0.z(), 0, 0, 0, 0, 0, 0, 0};
  return a;
}

// The reference: odeint's adaptive Dormand-Prince 5(4) at 1e-14 (dynamics.h).
SensitivityState Reference(const Arc& a, double t) {
  IntegrationOptions tight;
  tight.absolute_tolerance = tight.relative_tolerance = 1e-14;
  SensitivityState y = a.y0;
  plateball::internal::IntegrateAdaptive(a.rhs, y, 0.0, t, 1e-3, tight);
  return y;
}

double MaxDifference(const SensitivityState& a, const SensitivityState& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

// odeint's controller's error measure of one step of length h from a.y0 with the error estimate
// err: max_i |err_i| / (1e-12 + 1e-12 (|y_i| + |h| |y'_i|)).
double OdeintErrorMeasure(const Arc& a, double h, const SensitivityState& err) {
  SensitivityState dydt{};
  a.rhs(a.y0, dydt, 0.0);
  double measure = 0.0;
  for (std::size_t i = 0; i < err.size(); ++i)
    measure =
        std::max(measure, std::abs(err[i]) / (1e-12 + 1e-12 * (std::abs(a.y0[i]) + std::abs(h) * std::abs(dydt[i]))));
  return measure;
}

TEST(SensitivityRhs, HandWrittenVariationalEquationsEqualJetForwardMode) {
  using Jet = ceres::Jet<double, 1>;
  for (double lambda : {0.5, 1.0, 2.0, 7.0}) {
    for (int trial = 0; trial < 8; ++trial) {
      const double th = 0.3 + 0.37 * trial, ph = -1.0 + 0.61 * trial;
      const SensitivityState y{std::sin(th) * std::cos(ph),
                               std::sin(th) * std::sin(ph),
                               std::cos(th),
                               0.1,
                               -0.2,
                               0.3 - 0.1 * trial,
                               0.05 * trial,
                               -0.4,
                               0.2,
                               0.7};
      const SensitivityRhs rhs{lambda, {0.8 - 0.1 * trial, 0.3 + 0.2 * trial}, {-0.5, 0.25 * trial}};
      SensitivityState dy{};
      rhs(y, dy, 0.0);
      // The same right-hand side from the kinematics kernel evaluated on Jets.
      Jet z[3], k[2], w[2], dz[3], dx[2];
      for (int i = 0; i < 3; ++i) {
        z[i] = Jet(y[i]);
        z[i].v[0] = y[5 + i];
      }
      for (int i = 0; i < 2; ++i) {
        k[i] = Jet(rhs.k[i]);
        k[i].v[0] = rhs.dk[i];
      }
      plateball::internal::OmegaFromZK(z, k, lambda, w);
      plateball::internal::ZxRhs(z, w, dz, dx);
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(dy[i], dz[i].a, 1e-15);
        EXPECT_NEAR(dy[5 + i], dz[i].v[0], 1e-14);
      }
      for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR(dy[3 + i], dx[i].a, 1e-15);
        EXPECT_NEAR(dy[8 + i], dx[i].v[0], 1e-14);
      }
    }
  }
}

// y' = y: one step of length h leaves exp(h) to O(h^(order + 1)), so halving h divides the
// error by ~2^(order + 1) (checked between 0.6 and 1.4 times that).
template <typename Step>
void CheckOrderOnExponential(const Step& step, int order, std::initializer_list<double> hs) {
  const auto rhs = [](const std::array<double, 1>& y, std::array<double, 1>& dy, double) { dy[0] = y[0]; };
  const double ratio = std::pow(2.0, order + 1);
  double previous = 0.0;
  for (double h : hs) {
    std::array<double, 1> y{1.0};
    step(rhs, y, h);
    const double err = std::abs(y[0] - std::exp(h));
    EXPECT_GT(err, 0.0) << "h = " << h;
    if (previous > 0) {
      EXPECT_GT(previous / err, 0.6 * ratio) << "h = " << h;
      EXPECT_LT(previous / err, 1.4 * ratio) << "h = " << h;
    }
    previous = err;
  }
}

// One step of ours agrees with odeint's stepper of the same tableau to round-off, and our error
// measure is odeint's controller's computed from odeint's own estimate (its try_step accepts
// exactly when ours is <= 1, up to round-off: the error is a difference of stages that cancel to
// ~1e-14, so the two sums agree to ~4 eps max|k| |h| / 1e-12 ~ 1e-4 |h| in units of the tolerance).
template <typename OdeintStepper, typename Step>
void CheckStepEqualsOdeints(const Step& step) {
  const Arc a = MakeArc(2.0, {M_PI / 3, 0.4, 0.1}, 1.0, 1.36);
  for (double h : {0.01, 0.05, 0.2, -0.1}) {
    SensitivityState ours = a.y0, theirs = a.y0, err{};
    const double measure = step(a.rhs, ours, h);
    OdeintStepper stepper;
    stepper.do_step(a.rhs, theirs, 0.0, h, err);
    EXPECT_LT(MaxDifference(ours, theirs), 1e-15) << "h = " << h;
    const double expected = OdeintErrorMeasure(a, h, err);
    EXPECT_NEAR(measure, expected, 1e-3 * expected + 1e-4 * std::abs(h)) << "h = " << h;
  }
}

// The two kernels as generic callables (rhs, y, h) -> error measure at tolerances 1e-12.
const auto kFehlberg78 = [](const auto& rhs, auto& y, double h) {
  return plateball::internal::Fehlberg78Step(rhs, y, 0.0, h, 1e-12, 1e-12);
};
const auto kDormandPrince5 = [](const auto& rhs, auto& y, double h) {
  return plateball::internal::DormandPrince5Step(rhs, y, 0.0, h, 1e-12, 1e-12);
};

TEST(Fehlberg78, OneStepOnAnExponentialIsEighthOrder) { CheckOrderOnExponential(kFehlberg78, 8, {0.8, 0.4, 0.2}); }

TEST(Fehlberg78, OneStepEqualsOdeintsFehlberg78StepAndErrorMeasure) {
  CheckStepEqualsOdeints<boost::numeric::odeint::runge_kutta_fehlberg78<SensitivityState>>(kFehlberg78);
}

// The planner's short rollouts and arcs take one hand-written Dormand-Prince 5(4) step (dopri5.h).
TEST(DormandPrince5, OneStepEqualsOdeintsDopri5StepAndErrorMeasure) {
  CheckStepEqualsOdeints<boost::numeric::odeint::runge_kutta_dopri5<SensitivityState>>(kDormandPrince5);
}

TEST(DormandPrince5, OneStepOnAnExponentialIsFifthOrder) {
  CheckOrderOnExponential(kDormandPrince5, 5, {0.4, 0.2, 0.1});
}

TEST(Fehlberg78, ShortAndLongArcsAgreeWithAdaptiveDopri5) {
  const IntegrationOptions options;  // 1e-12, as the join
  struct Case {
    double lambda;
    plateball::AngleState angles;
    double mu, s, t;
    int steps;
  };
  const Case cases[] = {
      {2.0, {M_PI / 3, 0.4, 0.1}, 1.0, 1.36, 0.0528, 1},  // T1
      {2.0, {M_PI / 3, 0.4, 0.1}, 1.0, -2.0, 0.2, 2},     // a longer arc in two steps
      {0.5, {2.5, -1.2, 0.7}, 4.0, 0.3, -0.15, 2},        // backwards in time, lambda < 1
      {7.0, {0.05, 2.0, -0.4}, 0.25, 1.0, 3.0, 48},       // near the pole, a long arc
      {1.0, {M_PI / 2, 0.0, 0.0}, 1.0, 0.5, 1.5, 16},     // homogeneous ball
  };
  for (const Case& c : cases) {
    const Arc a = MakeArc(c.lambda, c.angles, c.mu, c.s);
    SensitivityState y = a.y0;
    ASSERT_TRUE(plateball::internal::IntegrateEqualSteps(a.rhs, y, 0.0, c.t, c.steps, options))
        << "lambda " << c.lambda << ", t " << c.t;
    EXPECT_LT(MaxDifference(y, Reference(a, c.t)), kAgreement) << "lambda " << c.lambda << ", t " << c.t;
  }
}

TEST(Fehlberg78, ATooLongStepIsRefusedAndLeavesTheStateUnchanged) {
  const Arc a = MakeArc(2.0, {M_PI / 3, 0.4, 0.1}, 1.0, 1.0);
  IntegrationOptions options;
  SensitivityState y = a.y0;
  // A whole period (2 pi) in one step is far outside 1e-12.
  EXPECT_FALSE(plateball::internal::IntegrateEqualSteps(a.rhs, y, 0.0, 2 * M_PI, 1, options));
  EXPECT_EQ(y, a.y0);
  // The same arc in enough steps is accepted and agrees with the reference.
  EXPECT_TRUE(plateball::internal::IntegrateEqualSteps(a.rhs, y, 0.0, 2 * M_PI, 64, options));
  EXPECT_LT(MaxDifference(y, Reference(a, 2 * M_PI)), 1e-12);
  // A non-finite right-hand side is refused too.
  const auto nan_rhs = [](const std::array<double, 1>&, std::array<double, 1>& dy, double) { dy[0] = NAN; };
  std::array<double, 1> u{1.0};
  EXPECT_FALSE(plateball::internal::IntegrateEqualSteps(nan_rhs, u, 0.0, 0.1, 1, options));
  EXPECT_EQ(u[0], 1.0);
}

TEST(ContactSeries, TaylorModelMatchesTheRolloutAndItsSensitivity) {
  using Dual = plateball::internal::SeriesDual;
  for (double lambda : {0.5, 2.0, 5.0}) {
    const Arc a = MakeArc(lambda, {1.1, 0.4, -0.3}, 1.0, 0.8);
    const double z0[3] = {a.y0[0], a.y0[1], a.y0[2]};
    const Dual k[2] = {Dual(a.rhs.k[0], a.rhs.dk[0]), Dual(a.rhs.k[1], a.rhs.dk[1])};
    std::array<std::array<Dual, 2>, 13> x;
    plateball::internal::ContactSeries<12>(z0, k, lambda, &x);
    for (double t : {0.02, 0.05, 0.1}) {
      const SensitivityState ref = Reference(a, t);
      // Horner: x(t) = sum_{m >= 1} x_m t^m, and its derivative in s.
      double xs[2] = {0, 0}, dxs[2] = {0, 0};
      for (int m = 12; m >= 1; --m) {
        for (int i = 0; i < 2; ++i) {
          xs[i] = (xs[i] + x[m][i].a) * t;
          dxs[i] = (dxs[i] + x[m][i].d) * t;
        }
      }
      // Truncation t^13 is far below the reference's own error at these t.
      EXPECT_NEAR(xs[0], ref[3], 1e-13) << "lambda " << lambda << ", t " << t;
      EXPECT_NEAR(xs[1], ref[4], 1e-13);
      EXPECT_NEAR(dxs[0], ref[8], 1e-13);
      EXPECT_NEAR(dxs[1], ref[9], 1e-13);
    }
  }
}

TEST(ContactSeries, HomogeneousBallRollsStraight) {
  // lambda = 1: omega = K is constant, x(t) = t (K2, -K1) exactly; every higher coefficient is 0.
  const double z0[3] = {0.6, 0.0, 0.8};
  const double k[2] = {0.3, -0.4};
  std::array<std::array<double, 2>, 6> x;
  plateball::internal::ContactSeries<5>(z0, k, 1.0, &x);
  EXPECT_DOUBLE_EQ(x[1][0], -0.4);
  EXPECT_DOUBLE_EQ(x[1][1], -0.3);
  for (int m = 2; m <= 5; ++m) {
    EXPECT_EQ(x[m][0], 0.0);
    EXPECT_EQ(x[m][1], 0.0);
  }
}

}  // namespace
