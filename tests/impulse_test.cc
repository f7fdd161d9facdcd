// Impulses (section 2.1, "Modeling an impulse", "Calculation of the instantaneous change of
// velocity of the upper plate").
#include "plateball/impulse.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

#include "plateball/ball_state.h"
#include "plateball/free_motion.h"
#include "support/test_support.h"

namespace plateball {
namespace {

constexpr double kExactEnergy = 1e-14;  // relative: (9) holds by construction of (15)-(18)
constexpr double kRoundOff = 1e-13;
constexpr double kAgreement = 1e-9;  // two integrations at tolerances 1e-12

TEST(Impulse, EnergyPreservingImpulseKeepsMuExactly) {
  for (double lambda : {0.3, 1.0, 2.0, 5.0})
    for (const AngleState& a :
         {AngleState{M_PI / 3, 0.4, 0.1}, AngleState{0.0, 0.0, 1.0}, AngleState{2.9, -2.0, 0.5}}) {
      const BallModel model = BallModel::FromLambda(lambda);
      const double mu = 1.7;
      for (int i = -20; i <= 20; ++i) {
        const double dpsi = 0.37 * i;
        const Impulse imp = EnergyPreservingImpulse(a, mu, dpsi, model);
        EXPECT_NEAR(Energy(imp.state_after, model), mu, kExactEnergy * mu);
        EXPECT_NEAR(Energy(imp.state_before, model), mu, kExactEnergy * mu);
        EXPECT_EQ(imp.mu_after, mu);
        // theta and phi (the position variables) do not jump; z is unchanged.
        EXPECT_EQ(imp.after.theta, a.theta);
        EXPECT_EQ(imp.after.phi, a.phi);
        EXPECT_NEAR(imp.after.psi, a.psi + dpsi, 1e-15);
        EXPECT_LT((imp.state_after.z - imp.state_before.z).norm(), 1e-16);
      }
    }
}

TEST(Impulse, DeltaOmegaIsDeltaV0ZMinusDeltaU) {
  // Independent route: (z, u, v0) before and after from (15)-(18) directly, and the jump of the
  // angular velocity omega = v0 z - u.
  const BallModel model = BallModel::FromLambda(0.6);
  const AngleState a{1.1, -0.3, 0.9};
  const double mu = 2.2;
  for (double dpsi : {-2.0, 0.1, 1.0, 3.0}) {
    const Impulse imp = EnergyPreservingImpulse(a, mu, dpsi, model);
    const PhaseVariables p0 = PhaseFromAngles(a, mu, model);
    const PhaseVariables p1 = PhaseFromAngles({a.theta, a.phi, a.psi + dpsi}, mu, model);
    EXPECT_LT((imp.delta_u - (p1.u - p0.u)).norm(), kRoundOff);
    EXPECT_NEAR(imp.delta_v0, p1.v0 - p0.v0, kRoundOff);
    EXPECT_LT((imp.delta_omega - ((p1.v0 - p0.v0) * p0.z - (p1.u - p0.u))).norm(), kRoundOff);
    EXPECT_LT((imp.delta_omega - (imp.state_after.omega - imp.state_before.omega)).norm(), kRoundOff);
    EXPECT_NEAR(imp.delta_omega.z(), 0.0, kRoundOff);  // no spin before or after
  }
}

TEST(Impulse, PlateVelocityChangeIsTwiceTheJumpOfTheContactVelocity) {
  // The top of the ball moves at twice the centre's velocity x' = omega x e3; the upper plate
  // must change its velocity by 2 (x'_after - x'_before).
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState a{M_PI / 3, 0.4, 0.1};
  for (double dpsi : {-1.3, 0.5, 2.7}) {
    const Impulse imp = EnergyPreservingImpulse(a, 1.0, dpsi, model);
    const Eigen::Vector2d jump = ContactVelocity(imp.state_after.omega) - ContactVelocity(imp.state_before.omega);
    EXPECT_LT((imp.plate_velocity_change.head<2>() - 2.0 * jump).norm(), kRoundOff);
    EXPECT_EQ(imp.plate_velocity_change.z(), 0.0);
  }
}

TEST(Impulse, EnergyPreservingImpulseMovesKAlongTheEllipseOfTheSameEnergy) {
  // At fixed z, every delta psi gives a K of the same energy: omega from (z, K) reproduces mu.
  const BallModel model = BallModel::FromLambda(3.0);
  const AngleState a{0.7, 1.0, -0.5};
  for (double dpsi : {0.3, 1.9, 4.0}) {
    const Impulse imp = EnergyPreservingImpulse(a, 0.9, dpsi, model);
    const Eigen::Vector2d k = ConservedMomentum(imp.state_after, model);
    const BallState rebuilt{imp.state_after.z, OmegaFromMomentum(imp.state_after.z, k, model)};
    EXPECT_NEAR(Energy(rebuilt, model), 0.9, 1e-14);
  }
}

TEST(Impulse, EnergyChangingImpulseScalesOmegaAndKeepsThePath) {
  // Scaling |omega| by f keeps its direction, multiplies mu by f^2, and the motion after it is
  // the old one at time f t: the same path on the plate and the same orientations along it.
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState a{M_PI / 3, 0.4, 0.1};
  const double mu = 1.0;
  for (double f : {0.25, 0.5, 3.0}) {
    const Impulse imp = EnergyChangingImpulse(a, mu, f, model);
    EXPECT_NEAR(imp.mu_after, f * f * mu, 1e-15);
    EXPECT_NEAR(Energy(imp.state_after, model), f * f * mu, 1e-14 * f * f);
    EXPECT_LT((imp.state_after.omega - f * imp.state_before.omega).norm(), kRoundOff);
    const FreeMotion slow = FreeMotion::FromAngles(model, a, mu, {0.3, 0.1});
    FreeMotionStart start = slow.start();
    start.state = imp.state_after;
    const FreeMotion fast(model, start);
    for (double t : {0.5, 2.0, 7.5, 30.0}) {
      const MotionSample s = slow.At(t), q = fast.At(t / f);
      EXPECT_LT((s.x - q.x).norm(), kAgreement) << "f " << f << " t " << t;
      EXPECT_LT((s.A - q.A).norm(), kAgreement) << "f " << f << " t " << t;
    }
    EXPECT_NEAR(fast.Period(), slow.Period() / f, 1e-12);
    EXPECT_LT((fast.DriftPerPeriod() - slow.DriftPerPeriod()).norm(), kAgreement);
  }
  const Impulse to = ImpulseToEnergy(a, mu, 4.0, model);
  EXPECT_NEAR(to.mu_after, 4.0, 1e-15);
  EXPECT_LT((to.state_after.omega - 2.0 * to.state_before.omega).norm(), kRoundOff);
}

TEST(Impulse, InvalidInputIsRejectedNamingTheField) {
  const BallModel model = BallModel::FromLambda(2.0);
  const auto message = [](auto&& f) { return plateball::testing::InvalidArgumentMessage(f, "no exception"); };
  const AngleState a{1.0, 0.0, 0.0};
  EXPECT_NE(message([&] { EnergyPreservingImpulse(a, 1.0, NAN, model); }).find("delta_psi: value"), std::string::npos);
  EXPECT_NE(message([&] { EnergyPreservingImpulse(a, 0.0, 1.0, model); }).find("mu: value"), std::string::npos);
  EXPECT_NE(message([&] { EnergyChangingImpulse(a, 1.0, 0.0, model); }).find("factor: value"), std::string::npos);
  EXPECT_NE(message([&] { EnergyChangingImpulse(a, 1.0, -2.0, model); }).find("factor: value"), std::string::npos);
  EXPECT_NE(message([&] { ImpulseToEnergy(a, 1.0, -1.0, model); }).find("mu_after: value"), std::string::npos);
  EXPECT_NE(message([&] {
              EnergyPreservingImpulse({NAN, 0.0, 0.0}, 1.0, 1.0, model);
            }).find("theta: value"),
            std::string::npos);
}

}  // namespace
}  // namespace plateball
