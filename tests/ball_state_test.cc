// The map (12)-(18) from angles to (z, u, v0), the constraints (8)-(11), the theta < 0
// convention, the inverse chart, the conserved K and the velocity ellipse (27)-(28).
#include "plateball/ball_state.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "support/test_support.h"

namespace plateball {
namespace {

constexpr double kRoundOff = 1e-13;  // a few ulps of O(1) quantities after trigonometry

bool SamePhase(const PhaseVariables& p, const PhaseVariables& q, double tol) {
  return (p.z - q.z).norm() < tol && (p.u - q.u).norm() < tol && std::abs(p.v0 - q.v0) < tol &&
         (p.omega - q.omega).norm() < tol;
}

TEST(BallState, PhaseFromAnglesSatisfiesConstraints8To11) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-4.0, 4.0), pos(0.1, 5.0);
  for (int i = 0; i < 200; ++i) {
    const BallModel model = BallModel::FromLambda(pos(rng));
    const double mu = pos(rng);
    const PhaseVariables p = PhaseFromAngles({angle(rng), angle(rng), angle(rng)}, mu, model);
    EXPECT_LT(ConstraintResiduals(p, mu, model).cwiseAbs().maxCoeff(), kRoundOff * std::max(1.0, mu));
    EXPECT_NEAR(p.omega.z(), 0.0, kRoundOff);                        // omega = v0 z - u has omega_3 = 0
    EXPECT_NEAR(p.omega.dot(p.z), p.v0, kRoundOff * std::sqrt(mu));  // v0 = <omega, z>
    // u = z' x z with z' = omega x z (the definition of u in (4)-(7)).
    EXPECT_LT((p.omega.cross(p.z).cross(p.z) - p.u).norm(), kRoundOff * std::sqrt(mu));
    BallState s{p.z, p.omega};
    EXPECT_NEAR(Energy(s, model), mu, kRoundOff * mu);
  }
}

TEST(BallState, NegativeThetaIsTheSamePhysicalState) {
  // (theta, phi, psi) ~ (-theta, phi + pi, psi) and ~ (theta + 2 pi, phi, psi) in (12)-(18).
  const BallModel model = BallModel::FromLambda(2.0);
  for (const AngleState& a :
       {AngleState{M_PI / 3, M_PI / 2, 0.0}, AngleState{1.0, -0.3, 2.0}, AngleState{2.8, 4.0, -5.0}}) {
    const PhaseVariables p = PhaseFromAngles(a, 1.3, model);
    EXPECT_TRUE(SamePhase(p, PhaseFromAngles({-a.theta, a.phi + M_PI, a.psi}, 1.3, model), kRoundOff));
    EXPECT_TRUE(SamePhase(p, PhaseFromAngles({a.theta + 2 * M_PI, a.phi, a.psi}, 1.3, model), kRoundOff));
    const AngleState c = AngleState{-a.theta, a.phi + M_PI, a.psi}.Canonicalize();
    EXPECT_GE(c.theta, 0.0);
    EXPECT_LE(c.theta, M_PI);
    EXPECT_GT(c.phi, -M_PI);
    EXPECT_LE(c.phi, M_PI);
    EXPECT_GT(c.psi, -M_PI);
    EXPECT_LE(c.psi, M_PI);
    EXPECT_TRUE(SamePhase(p, PhaseFromAngles(c, 1.3, model), kRoundOff));
  }
  // Figure 8's start: theta0 = -pi/3, phi0 = pi/2 is the axis at theta = pi/3, phi = -pi/2.
  const AngleState c = AngleState{-M_PI / 3, M_PI / 2, 0.0}.Canonicalize();
  EXPECT_NEAR(c.theta, M_PI / 3, 1e-15);
  EXPECT_NEAR(c.phi, -M_PI / 2, 1e-15);
}

TEST(BallState, AnglesFromStateInvertsTheChart) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> th(0.05, M_PI - 0.05), ang(-M_PI, M_PI);
  for (int i = 0; i < 100; ++i) {
    const BallModel model = BallModel::FromLambda(0.3 + 0.05 * i);
    const AngleState a{th(rng), ang(rng), ang(rng)};
    const double mu = 0.5 + 0.03 * i;
    const AngleState b = AnglesFromState(StateFromAngles(a, mu, model), model);
    EXPECT_NEAR(b.theta, a.theta, 1e-12);
    EXPECT_NEAR(std::remainder(b.phi - a.phi, 2 * M_PI), 0.0, 1e-12);
    EXPECT_NEAR(std::remainder(b.psi - a.psi, 2 * M_PI), 0.0, 1e-12);
  }
  // On a pole phi is not determined by z; the state (z, omega) still round-trips.
  const BallModel model = BallModel::FromLambda(2.0);
  for (const AngleState& a : {AngleState{0.0, 1.0, 0.4}, AngleState{M_PI, -2.0, 1.1}}) {
    const BallState s = StateFromAngles(a, 1.0, model);
    const BallState t = StateFromAngles(AnglesFromState(s, model), 1.0, model);
    EXPECT_LT((s.z - t.z).norm(), kRoundOff);
    EXPECT_LT((s.omega - t.omega).norm(), kRoundOff);
  }
}

TEST(BallState, MomentumAndOmegaFromMomentumAreInverse) {
  // K = omega_h + (lambda - 1) v0 z_h; given z and K, omega with omega_3 = 0 is unique.
  const BallModel model = BallModel::FromLambda(3.0);
  const BallState s = StateFromAngles({1.1, 0.2, -0.9}, 2.0, model);
  const Eigen::Vector2d k = ConservedMomentum(s, model);
  const double v0 = s.omega.dot(s.z);
  EXPECT_LT((k - (s.omega.head<2>() + 2.0 * v0 * s.z.head<2>())).norm(), kRoundOff);
  EXPECT_LT((OmegaFromMomentum(s.z, k, model) - s.omega).norm(), kRoundOff);
}

TEST(BallState, VelocityEllipseMatchesEquations27And28) {
  // |x'|^2 = a^2 cos^2 w + b^2 sin^2 w (27); |d x' / d psi|^2 = a^2 sin^2 w + b^2 cos^2 w (28)
  // (s shifts psi, so d/ds = d/dpsi; central difference, error O(h^2)).
  const BallModel model = BallModel::FromLambda(0.4);
  const double mu = 1.8, h = 1e-5;
  for (const AngleState& a : {AngleState{1.0, 0.3, -0.5}, AngleState{2.5, -1.0, 2.0}}) {
    const double w = a.phi - a.psi, A = SemiAxisA(a.theta, mu, model.lambda()), B = std::sqrt(mu);
    const Eigen::Vector2d v = ContactVelocity(StateFromAngles(a, mu, model).omega);
    EXPECT_NEAR(v.squaredNorm(), A * A * std::cos(w) * std::cos(w) + B * B * std::sin(w) * std::sin(w), kRoundOff);
    const Eigen::Vector2d vp = ContactVelocity(StateFromAngles({a.theta, a.phi, a.psi + h}, mu, model).omega);
    const Eigen::Vector2d vm = ContactVelocity(StateFromAngles({a.theta, a.phi, a.psi - h}, mu, model).omega);
    const Eigen::Vector2d dv = (vp - vm) / (2 * h);
    EXPECT_NEAR(dv.squaredNorm(), A * A * std::sin(w) * std::sin(w) + B * B * std::cos(w) * std::cos(w), 1e-8);
  }
}

TEST(BallState, InvalidStatesAreRejectedNamingTheField) {
  const BallModel model = BallModel::FromLambda(2.0);
  const auto message = [](auto&& f) { return plateball::testing::InvalidArgumentMessage(f, "no exception"); };
  EXPECT_NE(message([&] { StateFromAngles({1.0, 0.0, 0.0}, 0.0, model); }).find("mu: value"), std::string::npos);
  EXPECT_NE(message([&] { StateFromAngles({1.0, NAN, 0.0}, 1.0, model); }).find("phi: value"), std::string::npos);
  EXPECT_NE(message([&] {
              ValidateState({Eigen::Vector3d(0, 0, 2), Eigen::Vector3d::Zero()});
            }).find("z norm"),
            std::string::npos);
  EXPECT_NE(message([&] {
              ValidateState({Eigen::Vector3d::UnitZ(), Eigen::Vector3d(1, 0, 1)});
            }).find("omega[2]"),
            std::string::npos);
  EXPECT_NE(message([&] {
              AnglesFromState({Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()}, model);
            }).find("mu"),
            std::string::npos);
}

}  // namespace
}  // namespace plateball
