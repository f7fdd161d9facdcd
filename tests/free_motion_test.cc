// FreeMotion (one stored period, evaluated anywhere) and IntegrateFreeMotion (direct
// integration): conservation, periodicity, the poles, the paper's special cases, far times, the
// constraints (8)-(11) and SO(3) invariants. Expected values come from conservation laws, closed
// forms (straight lines, the harmonic z3) or the second method, never from the code under test.
#include "plateball/free_motion.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "plateball/ball_state.h"
#include "plateball/so3.h"
#include "support/test_support.h"

namespace plateball {
namespace {

using testing::IsRotationMatrix;

// Integration tolerances are 1e-12 (default); global errors over a few periods are ~1e-11.
constexpr double kAgreement = 1e-9;
// Energy over 100 periods: the drift measured is 1.7e-10 at tolerances 1e-12 and ~2e-11 at
// 1e-13 (lambda = 5 the worst), so the 100-period tests integrate at 1e-13.
constexpr double kConservation = 1e-10;
// A phase (not a conserved quantity) after 100 periods: the global error grows linearly in t;
// 1e-10 measured at tolerances 1e-13.
constexpr double kLongTimeAgreement = 1e-9;
// Straight-line and constant-axis special cases are exact: only round-off and the tolerance.
constexpr double kExactCase = 1e-10;

IntegrationOptions Tight() {
  IntegrationOptions o;
  o.absolute_tolerance = o.relative_tolerance = 1e-13;
  return o;
}

FreeMotionStart StartFromAngles(const BallModel& model,
                                const AngleState& a,
                                double mu,
                                const Eigen::Vector2d& x0 = Eigen::Vector2d::Zero()) {
  FreeMotionStart s;
  s.state = StateFromAngles(a, mu, model);
  s.x0 = x0;
  s.A0 = AlignOrientationToAxis(Eigen::Matrix3d::Identity(), s.state.z);
  return s;
}

TEST(FreeMotion, EnergyKeptOverHundredPeriods) {
  for (double lambda : {0.5, 1.0, 2.0, 5.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    for (const AngleState& a : {AngleState{M_PI / 3, 0.4, 0.1}, AngleState{0.2, -1.0, 1.0}}) {
      const double mu = 1.3;
      const FreeMotionStart start = StartFromAngles(model, a, mu);
      const double period = 2.0 * M_PI / std::sqrt(mu);
      std::vector<double> times;
      for (int k = 1; k <= 100; ++k) times.push_back((k + 0.29) * period);
      double worst = 0.0;
      for (const MotionSample& s : IntegrateFreeMotion(model, start, times, Tight()))
        worst = std::max(worst, std::abs(s.energy - mu));
      EXPECT_LT(worst, kConservation) << "lambda " << lambda;
      // FreeMotion integrates one period only and repeats it, so at the default tolerances its
      // energy error does not grow with t at all.
      const FreeMotion motion(model, start);
      double worst_periodic = 0.0;
      for (double t : times) worst_periodic = std::max(worst_periodic, std::abs(motion.At(t).energy - mu));
      EXPECT_LT(worst_periodic, kConservation) << "lambda " << lambda;
    }
  }
}

TEST(FreeMotion, Z3IsHarmonicWithFrequencySqrtMu) {
  // docs/paper_notes.md (periodicity theorem): z3'' = -mu z3 for every lambda, so
  // z3(t) = z3(0) cos(bt) + z3'(0)/b sin(bt) with z3'(0) = (omega x z)_3.
  for (double lambda : {0.5, 1.0, 2.0, 5.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    const double mu = 0.8, b = std::sqrt(mu);
    const FreeMotionStart start = StartFromAngles(model, {1.3, 0.7, -0.4}, mu);
    const double z30 = start.state.z.z(), dz30 = start.state.omega.cross(start.state.z).z();
    std::vector<double> times;
    for (int k = 0; k <= 400; ++k) times.push_back(k * 0.25 * 2.0 * M_PI / b + 0.1 * (k % 7));
    for (const MotionSample& s : IntegrateFreeMotion(model, start, times, Tight()))
      ASSERT_NEAR(s.state.z.z(), z30 * std::cos(b * s.t) + dz30 / b * std::sin(b * s.t), kLongTimeAgreement)
          << "lambda " << lambda << " t " << s.t;
  }
}

TEST(FreeMotion, WholeStateReturnsAfterOnePeriodForAnyLambda) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), energy(0.1, 5.0);
  for (double lambda : {0.2, 0.5, 1.0, 1.7, 2.0, 5.0})
    for (int i = 0; i < 6; ++i) {
      const BallModel model = BallModel::FromLambda(lambda);
      const double mu = energy(rng);
      const FreeMotionStart start = StartFromAngles(model, {angle(rng), angle(rng), angle(rng)}, mu);
      const auto s = IntegrateFreeMotion(model, start, {2.0 * M_PI / std::sqrt(mu)});
      EXPECT_LT((s[0].state.z - start.state.z).norm(), kAgreement) << "lambda " << lambda;
      EXPECT_LT((s[0].state.omega - start.state.omega).norm(), kAgreement) << "lambda " << lambda;
    }
}

TEST(FreeMotion, PeriodDriftAndMonodromyMatchDirectIntegration) {
  for (double lambda : {0.5, 2.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    const double mu = 2.5;
    const Eigen::Matrix3d a0 = ExpSO3({0.3, -0.2, 0.1});
    const FreeMotion motion = FreeMotion::FromAngles(model, {1.0, 0.2, 0.5}, mu, {1.0, -2.0}, a0);
    EXPECT_NEAR(motion.Period(), 2.0 * M_PI / std::sqrt(mu), 1e-15);
    EXPECT_NEAR(motion.mu(), mu, 1e-14);
    const auto d = IntegrateFreeMotion(model, motion.start(), {motion.Period()});
    EXPECT_LT((motion.DriftPerPeriod() - (d[0].x - motion.start().x0)).norm(), kAgreement);
    EXPECT_LT((motion.MeanVelocity() * motion.Period() - motion.DriftPerPeriod()).norm(), 1e-14);
    EXPECT_LT((motion.MonodromyRotation() * motion.start().A0 - d[0].A).norm(), kAgreement);
    EXPECT_TRUE(IsRotationMatrix(motion.MonodromyRotation()));
  }
}

TEST(FreeMotion, FarTimeEvaluationMatchesDirectIntegration) {
  for (double lambda : {0.5, 1.0, 2.0, 5.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    const Eigen::Matrix3d a0 = ExpSO3({-0.4, 0.9, 0.2});
    const FreeMotion motion = FreeMotion::FromAngles(model, {M_PI / 3, 0.4, 0.1}, 1.0, {0.5, 0.5}, a0);
    const double t = 37.3 * motion.Period();
    const MotionSample far = motion.At(t);
    const MotionSample direct = IntegrateFreeMotion(model, motion.start(), {t}, Tight())[0];
    EXPECT_LT((far.x - direct.x).norm(), kAgreement) << "lambda " << lambda;
    EXPECT_LT((far.A - direct.A).norm(), kAgreement) << "lambda " << lambda;
    EXPECT_LT((far.state.z - direct.state.z).norm(), kAgreement);
    EXPECT_LT((far.state.omega - direct.state.omega).norm(), kAgreement);
    EXPECT_TRUE(IsRotationMatrix(far.A));
    // PositionAt is the same x without the orientation.
    EXPECT_LT((motion.PositionAt(t) - far.x).norm(), 1e-13);
  }
}

TEST(FreeMotion, NegativeTimesMatchBackwardIntegration) {
  const BallModel model = BallModel::FromLambda(2.0);
  const FreeMotion motion = FreeMotion::FromAngles(model, {2.0, -0.3, 0.8}, 1.4, {0, 0}, ExpSO3({0.1, 0.2, 0.3}));
  const double t = -2.6 * motion.Period();
  const MotionSample back = IntegrateFreeMotion(model, motion.start(), {t})[0];
  const MotionSample m = motion.At(t);
  EXPECT_LT((m.x - back.x).norm(), kAgreement);
  EXPECT_LT((m.A - back.A).norm(), kAgreement);
}

TEST(FreeMotion, ReportedOmegaIsTheRateOfZAndOfX) {
  // Central differences of z and x from At (O(h^2) = 1e-8 with h = 1e-4) against omega x z and
  // omega x e3: the angular velocity reported is the one the motion has.
  const BallModel model = BallModel::FromLambda(0.5);
  const FreeMotion motion = FreeMotion::FromAngles(model, {0.9, 1.1, -0.7}, 2.0);
  const double h = 1e-4;
  for (double t : {0.3, 1.7, 4.4, 25.0}) {
    const MotionSample m = motion.At(t), p = motion.At(t + h), q = motion.At(t - h);
    const Eigen::Vector3d dz = (p.state.z - q.state.z) / (2 * h);
    const Eigen::Vector2d dx = (p.x - q.x) / (2 * h);
    EXPECT_LT((dz - m.state.omega.cross(m.state.z)).norm(), 1e-7);
    EXPECT_LT((dx - ContactVelocity(m.state.omega)).norm(), 1e-7);
    // A' A^T = hat(omega).
    const Eigen::Matrix3d da = (p.A - q.A) / (2 * h);
    EXPECT_LT((Vee(da * m.A.transpose()) - m.state.omega).norm(), 1e-7);
  }
}

TEST(FreeMotion, StraightLineFromTheNorthPole) {
  // theta0 = 0 (the paper's remark after (24)): at the pole omega = b (cos psi0, sin psi0, 0)
  // whatever phi0 (eqs. (15)-(18) at theta = 0); omega stays constant, z turns on the vertical
  // great circle, x(t) = x0 + b t (sin psi0, -cos psi0) and A(t) = exp(t hat(omega)) A0.
  for (double lambda : {0.5, 2.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    const double mu = 1.7, b = std::sqrt(mu), psi0 = 0.6;
    const Eigen::Vector2d x0(0.2, -1.0);
    const FreeMotion motion = FreeMotion::FromAngles(model, {0.0, 2.3, psi0}, mu, x0);
    const Eigen::Vector3d omega(b * std::cos(psi0), b * std::sin(psi0), 0.0);
    EXPECT_LT((motion.start().state.omega - omega).norm(), 1e-15);
    EXPECT_LT((motion.DriftPerPeriod() - motion.Period() * b * Eigen::Vector2d(std::sin(psi0), -std::cos(psi0))).norm(),
              kExactCase);
    for (double t : {0.1, 1.0, 0.5 * motion.Period(), 3.3, 40.0}) {
      const MotionSample m = motion.At(t);
      EXPECT_LT((m.x - (x0 + b * t * Eigen::Vector2d(std::sin(psi0), -std::cos(psi0)))).norm(), kExactCase) << t;
      EXPECT_LT((m.state.omega - omega).norm(), kExactCase) << t;
      EXPECT_LT((m.A - ExpSO3(t * omega) * motion.start().A0).norm(), kExactCase) << t;
      EXPECT_NEAR(m.state.z.norm(), 1.0, 1e-14);
      EXPECT_NEAR(m.energy, mu, kExactCase);
    }
  }
}

TEST(FreeMotion, EquatorialStartWithZeroWKeepsZAndMovesStraight) {
  // theta = pi/2, w = 0: theta' = 0, phi' = psi' = 0 ((19)-(21) with cos(theta) = 0), z is
  // constant, omega = a (cos phi0, sin phi0, 0) with a = sqrt(mu/lambda), x moves straight.
  for (double lambda : {0.5, 1.0, 3.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    const double mu = 0.9, phi0 = -1.1, a = std::sqrt(mu / lambda);
    const FreeMotion motion = FreeMotion::FromAngles(model, {M_PI / 2, phi0, phi0}, mu);
    const Eigen::Vector3d z0(std::cos(phi0), std::sin(phi0), 0.0);
    const Eigen::Vector3d omega = a * z0;
    for (double t : {0.4, 2.0, 17.9}) {
      const MotionSample m = motion.At(t);
      EXPECT_LT((m.state.z - z0).norm(), kExactCase);
      EXPECT_LT((m.x - t * a * Eigen::Vector2d(std::sin(phi0), -std::cos(phi0))).norm(), kExactCase);
      EXPECT_LT((m.A - ExpSO3(t * omega) * motion.start().A0).norm(), kExactCase);
    }
  }
}

TEST(FreeMotion, TrajectoriesThroughBothPolesKeepUnitZEnergyAndPeriod) {
  // c = 0 starts that cross theta = 0 and theta = pi each period (w0 = +-pi/2), a start on the
  // south pole, and a nearly polar one (c = 1e-7): FreeMotion::At against direct integration,
  // |z| = 1, energy, periodicity of z and omega, and the drift of a straight line for c = 0.
  const std::vector<AngleState> starts = {{1.0, M_PI / 2 + 0.3, 0.3},
                                          {2.9, -M_PI / 2, 0.0},
                                          {M_PI, 0.4, -1.0},
                                          {1.0, std::acos(1e-7 / std::sin(1.0)), 0.0}};
  for (double lambda : {0.5, 2.0, 5.0})
    for (const AngleState& a : starts) {
      const BallModel model = BallModel::FromLambda(lambda);
      const double mu = 1.2;
      const FreeMotion motion = FreeMotion::FromAngles(model, a, mu, {0, 0}, ExpSO3({0.2, 0.0, -0.3}));
      std::vector<double> times;
      for (int i = 0; i <= 50; ++i) times.push_back(3.0 * motion.Period() * i / 50.0);
      const auto direct = IntegrateFreeMotion(model, motion.start(), times);
      for (const MotionSample& d : direct) {
        const MotionSample m = motion.At(d.t);
        EXPECT_LT((m.x - d.x).norm(), kAgreement);
        EXPECT_LT((m.A - d.A).norm(), kAgreement);
        EXPECT_LT((m.state.z - d.state.z).norm(), kAgreement);
        EXPECT_NEAR(m.energy, mu, kConservation);
        EXPECT_NEAR(d.energy, mu, kConservation);
        EXPECT_TRUE(IsRotationMatrix(m.A));
      }
      const MotionSample end = motion.At(motion.Period());
      EXPECT_LT((end.state.z - motion.start().state.z).norm(), kAgreement);
      EXPECT_LT((end.state.omega - motion.start().state.omega).norm(), kAgreement);
    }
  // The pole family rolls straight: drift = b T along omega x e3 (constant omega).
  const BallModel model = BallModel::FromLambda(2.0);
  const FreeMotion line = FreeMotion::FromAngles(model, starts[0], 1.2);
  EXPECT_LT((line.DriftPerPeriod() - line.Period() * ContactVelocity(line.start().state.omega)).norm(), kExactCase);
  EXPECT_NEAR(line.DriftPerPeriod().norm(), line.Period() * std::sqrt(1.2), kExactCase);
}

TEST(FreeMotion, ConstraintsHoldAlongTrajectories) {
  // (8)-(11) for the phase variables rebuilt from the returned (canonical) angles, and the
  // angles give back the returned z and omega.
  for (double lambda : {0.5, 2.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    for (const AngleState& a :
         {AngleState{M_PI / 3, 0.4, 0.1}, AngleState{0.0, 0.0, 1.0}, AngleState{-M_PI / 3, M_PI / 2, 0.0}}) {
      const double mu = 1.5;
      const FreeMotion motion = FreeMotion::FromAngles(model, a, mu);
      for (const MotionSample& s : motion.Sample(0.0, 2.0 * motion.Period(), 41)) {
        const PhaseVariables p = PhaseFromAngles(s.angles, mu, model);
        const Eigen::Vector4d r = ConstraintResiduals(p, mu, model);
        EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-12) << "t " << s.t;
        EXPECT_LT((p.z - s.state.z).norm(), 1e-12);
        EXPECT_LT((p.omega - s.state.omega).norm(), 1e-9);
        EXPECT_NEAR(s.state.omega.z(), 0.0, 1e-15);  // no spin
        EXPECT_GE(s.angles.theta, 0.0);
        EXPECT_LE(s.angles.theta, M_PI);
      }
    }
  }
}

TEST(FreeMotion, EveryOrientationIsARotationCarryingZ) {
  const BallModel model = BallModel::FromLambda(1.5);
  const FreeMotion motion = FreeMotion::FromAngles(model, {1.2, -0.5, 2.0}, 3.0, {0, 0}, ExpSO3({2.0, -1.0, 0.5}));
  for (const MotionSample& s : motion.Sample(-5.0 * motion.Period(), 55.5 * motion.Period(), 301)) {
    EXPECT_TRUE(IsRotationMatrix(s.A));
    EXPECT_LT((s.A.col(2) - s.state.z).norm(), kAgreement);  // z = A e3
  }
}

TEST(FreeMotion, FromAnglesRotatesA0MinimallyOntoZ) {
  const BallModel model = BallModel::FromLambda(2.0);
  const FreeMotion m = FreeMotion::FromAngles(model, {M_PI / 3, 0.4, 0.1}, 1.0);
  EXPECT_TRUE(IsRotationMatrix(m.start().A0));
  EXPECT_LT((m.start().A0.col(2) - m.start().state.z).norm(), 1e-14);
  // A0 = -z case (antipodal): still a rotation carrying z.
  const FreeMotion s = FreeMotion::FromAngles(model, {M_PI, 0.0, 0.0}, 1.0);
  EXPECT_TRUE(IsRotationMatrix(s.start().A0));
  EXPECT_LT((s.start().A0.col(2) - Eigen::Vector3d(0, 0, -1)).norm(), 1e-14);
}

TEST(FreeMotion, RejectsInvalidInputNamingTheField) {
  const BallModel model = BallModel::FromLambda(2.0);
  const auto message = [](auto&& f) { return plateball::testing::InvalidArgumentMessage(f, "no exception"); };
  FreeMotionStart at_rest;  // omega = 0
  EXPECT_NE(message([&] { FreeMotion(model, at_rest); }).find("mu"), std::string::npos);
  FreeMotionStart bad_a0 = StartFromAngles(model, {1.0, 0.0, 0.0}, 1.0);
  bad_a0.A0 *= 2.0;
  EXPECT_NE(message([&] { FreeMotion(model, bad_a0); }).find("A0"), std::string::npos);
  FreeMotionStart spin = StartFromAngles(model, {1.0, 0.0, 0.0}, 1.0);
  spin.state.omega.z() = 0.5;
  EXPECT_NE(message([&] { FreeMotion(model, spin); }).find("omega[2]"), std::string::npos);
  FreeMotionStart nan_x = StartFromAngles(model, {1.0, 0.0, 0.0}, 1.0);
  nan_x.x0.x() = NAN;
  EXPECT_NE(message([&] { FreeMotion(model, nan_x); }).find("x0"), std::string::npos);
  IntegrationOptions bad;
  bad.relative_tolerance = -1.0;
  EXPECT_NE(message([&] {
              FreeMotion::FromAngles(model, {1.0, 0.0, 0.0}, 1.0, {0, 0}, Eigen::Matrix3d::Identity(), bad);
            }).find("relative_tolerance"),
            std::string::npos);
  EXPECT_NE(message([&] { FreeMotion::FromAngles(model, {1.0, 0.0, 0.0}, -1.0); }).find("mu"), std::string::npos);
  const FreeMotion ok = FreeMotion::FromAngles(model, {1.0, 0.0, 0.0}, 1.0);
  EXPECT_NE(message([&] { ok.At(NAN); }).find("t: value"), std::string::npos);
  EXPECT_NE(message([&] { ok.Sample(0.0, 1.0, 1); }).find("samples"), std::string::npos);
  EXPECT_NE(message([&] { IntegrateFreeMotion(model, ok.start(), {1.0, 0.5}); }).find("times[1]"), std::string::npos);
}

}  // namespace
}  // namespace plateball
