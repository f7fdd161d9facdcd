// Physical parameters -> (alpha, beta, lambda) by hand numbers, and rejection of invalid values
// with the field named.
#include "plateball/ball_model.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "plateball/ball_state.h"
#include "plateball/free_motion.h"
#include "support/test_support.h"

namespace plateball {
namespace {

std::string Message(const PhysicalParameters& p) {
  try {
    BallModel::FromPhysical(p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

// A rigid ball: 2 I1 + I3 = 7 <= 2 M_ball r^2 = 12.
PhysicalParameters Example() {
  PhysicalParameters p;
  p.inertia_1 = 2.0;
  p.inertia_3 = 3.0;
  p.ball_mass = 1.5;
  p.radius = 2.0;
  p.plate_mass = 0.25;
  return p;
}

TEST(BallModel, PhysicalParametersGiveAlphaBetaLambdaByHand) {
  // M = 1.5 + 4 * 0.25 = 2.5; alpha = 3/2; beta = M r^2 / I1 = 2.5 * 4 / 2 = 5;
  // lambda = (1.5 + 5) / (1 + 5) = 13/12.
  const BallModel m = BallModel::FromPhysical(Example());
  EXPECT_TRUE(m.has_inertia());
  EXPECT_DOUBLE_EQ(Example().EffectiveMass(), 2.5);
  EXPECT_DOUBLE_EQ(m.alpha(), 1.5);
  EXPECT_DOUBLE_EQ(m.beta(), 5.0);
  EXPECT_DOUBLE_EQ(m.lambda(), 13.0 / 12.0);
  EXPECT_TRUE(m.IsRealisable());
  // mu = 2E / (I1 + M r^2) = 6 / 12.
  EXPECT_DOUBLE_EQ(BallModel::EnergyToMu(Example(), 3.0), 0.5);
}

TEST(BallModel, RigidBallsHaveLambdaBetweenOneHalfAndFourThirds) {
  // A thin ring of radius r in the equatorial plane (I3 = M r^2, I1 = M r^2 / 2) sits on both rigid-body
  // bounds and, without a plate, has lambda = (2 + 2)/(1 + 2) = 4/3.
  PhysicalParameters ring;
  ring.ball_mass = 2.0;
  ring.radius = 0.5;
  ring.inertia_3 = 0.5;
  ring.inertia_1 = 0.25;
  EXPECT_TRUE(ring.Validate().empty()) << ring.Validate();
  EXPECT_DOUBLE_EQ(BallModel::FromPhysical(ring).lambda(), 4.0 / 3.0);
  // Two point masses at the poles (I1 = M r^2, I3 -> 0): lambda -> (0 + 1)/(1 + 1) = 1/2. I1 is 1e-9 short
  // of M r^2 so that 2 I1 + I3 <= 2 M r^2 holds with I3 = 1e-9.
  PhysicalParameters poles = ring;
  poles.inertia_1 = 0.5 - 1e-9;
  poles.inertia_3 = 1e-9;
  EXPECT_NEAR(BallModel::FromPhysical(poles).lambda(), 0.5, 2e-9);  // alpha = 2e-9, beta = 1 + 2e-9
  // The plate's mass pulls lambda toward 1 from either side: M = 2 + 4 * 10 = 42, so beta = 42 for the
  // ring (lambda = 44/43) and 21 for the poles (lambda = 21/22, up to alpha ~ 2e-9).
  ring.plate_mass = poles.plate_mass = 10.0;
  EXPECT_NEAR(BallModel::FromPhysical(ring).lambda(), 44.0 / 43.0, 1e-15);
  EXPECT_NEAR(BallModel::FromPhysical(poles).lambda(), 21.0 / 22.0, 1e-8);
  // The realisable flag: bare lambda in (1/2, 4/3]; alpha, beta with beta >= 1 + alpha/2.
  EXPECT_TRUE(BallModel::FromLambda(4.0 / 3.0).IsRealisable());
  EXPECT_TRUE(BallModel::FromLambda(0.51).IsRealisable());
  EXPECT_FALSE(BallModel::FromLambda(0.5).IsRealisable());
  EXPECT_FALSE(BallModel::FromLambda(1.34).IsRealisable());
  EXPECT_FALSE(BallModel::FromLambda(2.0).IsRealisable());  // the paper's examples: mathematics, not a ball
  EXPECT_TRUE(BallModel::FromAlphaBeta(2.0, 2.0).IsRealisable());
  EXPECT_FALSE(BallModel::FromAlphaBeta(2.0, 1.9).IsRealisable());  // a ring heavier than its ball
  EXPECT_FALSE(BallModel::FromAlphaBeta(0.5, 0.0).IsRealisable());
}

// Newton-Euler for the ball and the upper plate as two bodies, with the contact forces as unknowns:
// an independent route to the effective mass. Ball: m a = F_top + F_bot,
// d(I omega)/dt = r e3 x F_top - r e3 x F_bot + tau e3; plate: M_plate A_plate = -F_top; rolling at both
// contacts: v = r omega x e3, V_plate = 2 r omega x e3; no spin: omega_3 = 0.
struct PlateBall {
  PhysicalParameters p;
  Eigen::Matrix3d Inertia(const Eigen::Vector3d& z) const {
    return p.inertia_1 * Eigen::Matrix3d::Identity() + (p.inertia_3 - p.inertia_1) * z * z.transpose();
  }
  // omega' from the 8 x 8 linear system in (omega', F_top, F_bot, tau).
  Eigen::Vector3d AngularAcceleration(const Eigen::Vector3d& z, const Eigen::Vector3d& w) const {
    Eigen::Matrix3d cross_e3;  // w -> w x e3
    cross_e3 << 0, 1, 0, -1, 0, 0, 0, 0, 0;
    Eigen::Matrix<double, 3, 2> e3_cross;  // horizontal F -> e3 x F
    e3_cross << 0, -1, 1, 0, 0, 0;
    const Eigen::Matrix<double, 2, 3> acc = p.radius * cross_e3.topRows<2>();  // omega' -> centre acceleration
    const Eigen::Matrix3d I = Inertia(z);
    Eigen::Matrix<double, 8, 8> a = Eigen::Matrix<double, 8, 8>::Zero();
    Eigen::Matrix<double, 8, 1> b = Eigen::Matrix<double, 8, 1>::Zero();
    a.block<2, 3>(0, 0) = p.ball_mass * acc;  // ball, linear
    a.block<2, 2>(0, 3) = -Eigen::Matrix2d::Identity();
    a.block<2, 2>(0, 5) = -Eigen::Matrix2d::Identity();
    a.block<3, 3>(2, 0) = I;  // ball, angular about the centre
    a.block<3, 2>(2, 3) = -p.radius * e3_cross;
    a.block<3, 2>(2, 5) = p.radius * e3_cross;
    a(4, 7) = -1.0;
    b.segment<3>(2) = -w.cross(I * w);
    a.block<2, 3>(5, 0) = p.plate_mass * 2.0 * acc;  // plate
    a.block<2, 2>(5, 3) = Eigen::Matrix2d::Identity();
    a(7, 2) = 1.0;  // no spin
    return a.colPivHouseholderQr().solve(b).head<3>();
  }
  double Energy(const Eigen::Vector3d& z, const Eigen::Vector3d& w) const {
    const double v2 = p.radius * p.radius * (w.x() * w.x() + w.y() * w.y());
    return 0.5 * w.dot(Inertia(z) * w) + 0.5 * p.ball_mass * v2 + 0.5 * p.plate_mass * 4.0 * v2;
  }
};

TEST(BallModel, NewtonEulerOfBallAndPlateFollowsTheEffectiveMass) {
  // problems/physical_units.json's ball: M = 0.1 + 4 * 0.05 = 0.3 kg, lambda = (0.75 + 7.5)/(1 + 7.5).
  const PhysicalParameters phys = plateball::testing::PhysicalUnitsBall();
  const BallModel model = BallModel::FromPhysical(phys);
  EXPECT_NEAR(model.lambda(), 8.25 / 8.5, 1e-15);
  const AngleState angles{M_PI / 3, 0.4, 0.1};
  const double mu = 4.0, period = 2.0 * M_PI / std::sqrt(mu);
  const BallState start = StateFromAngles(angles, mu, model);
  // Classical RK4 on (z, omega, x): error ~ dt^4, far below the tolerance at dt = period / 20000.
  const PlateBall ne{phys};
  Eigen::Matrix<double, 8, 1> y;
  y << start.z, start.omega, 0.0, 0.0;
  auto rhs = [&](const Eigen::Matrix<double, 8, 1>& s) {
    const Eigen::Vector3d z = s.head<3>(), w = s.segment<3>(3);
    Eigen::Matrix<double, 8, 1> d;
    d << w.cross(z), ne.AngularAcceleration(z, w), w.y(), -w.x();  // contact point moves with r omega x e3 / r
    return d;
  };
  const int steps = 40000;
  const double dt = 2.0 * period / steps, energy0 = ne.Energy(start.z, start.omega);
  for (int i = 0; i < steps; ++i) {
    const auto k1 = rhs(y), k2 = rhs(y + 0.5 * dt * k1), k3 = rhs(y + 0.5 * dt * k2), k4 = rhs(y + dt * k3);
    y += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  // Tolerances: RK4's global error at this step is ~1e-12; the library integrates at 1e-12.
  constexpr double kAgreement = 1e-9;
  IntegrationOptions tight;
  tight.absolute_tolerance = tight.relative_tolerance = 1e-13;
  const MotionSample lib =
      FreeMotion::FromAngles(model, angles, mu, {0, 0}, Eigen::Matrix3d::Identity(), tight).At(2.0 * period);
  EXPECT_NEAR(ne.Energy(y.head<3>(), y.segment<3>(3)) / energy0, 1.0, kAgreement);
  EXPECT_LT((y.head<3>() - lib.state.z).norm(), kAgreement);
  EXPECT_LT((y.segment<3>(3) - lib.state.omega).norm(), kAgreement);
  EXPECT_LT((y.tail<2>() - lib.x).norm(), kAgreement);
  // The paper's M = M_ball + 2 M_plate gives lambda = 5.75/6 and a visibly different motion.
  const BallModel paper = BallModel::FromAlphaBeta(0.75, (0.1 + 2 * 0.05) * 4e-4 / 1.6e-5);
  EXPECT_NEAR(paper.lambda(), 5.75 / 6.0, 1e-15);
  const MotionSample wrong =
      FreeMotion::FromAngles(paper, angles, mu, {0, 0}, Eigen::Matrix3d::Identity(), tight).At(2.0 * period);
  EXPECT_GT((y.tail<2>() - wrong.x).norm(), 1e-2);
}

TEST(BallModel, UniformSolidBallHasLambdaOne) {
  // I1 = I3 = 2/5 M r^2: alpha = 1, so lambda = 1 whatever beta.
  PhysicalParameters p;
  p.ball_mass = 3.0;
  p.radius = 0.2;
  p.inertia_1 = p.inertia_3 = 0.4 * 3.0 * 0.04;
  p.plate_mass = 7.0;
  EXPECT_NEAR(BallModel::FromPhysical(p).lambda(), 1.0, 1e-15);
  EXPECT_NEAR(BallModel::FromAlphaBeta(0.5, 0.0).lambda(), 0.5, 1e-15);  // beta = 0: lambda = alpha
  EXPECT_NEAR(BallModel::FromAlphaBeta(2.0, 1.0).lambda(), 1.5, 1e-15);
  EXPECT_FALSE(BallModel::FromLambda(2.0).has_inertia());
}

TEST(BallModel, InvalidPhysicalParametersAreRejectedNamingTheField) {
  struct Bad {
    const char* field;
    PhysicalParameters p;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Bad> bad;
  auto with = [](auto f) {
    PhysicalParameters p = Example();
    f(p);
    return p;
  };
  bad.push_back({"inertia_1", with([](PhysicalParameters& p) { p.inertia_1 = 0.0; })});
  bad.push_back({"inertia_1", with([&](PhysicalParameters& p) { p.inertia_1 = nan; })});
  bad.push_back({"inertia_3", with([](PhysicalParameters& p) { p.inertia_3 = -1.0; })});
  bad.push_back({"inertia_3", with([](PhysicalParameters& p) { p.inertia_3 = 4.5; })});  // > 2 I1
  bad.push_back({"ball_mass", with([](PhysicalParameters& p) { p.ball_mass = -0.1; })});
  bad.push_back({"plate_mass", with([](PhysicalParameters& p) { p.plate_mass = -2.0; })});
  bad.push_back({"radius", with([](PhysicalParameters& p) { p.radius = 0.0; })});
  bad.push_back({"radius", with([&](PhysicalParameters& p) { p.radius = std::numeric_limits<double>::infinity(); })});
  bad.push_back({"ball_mass", with([](PhysicalParameters& p) { p.radius = 1.0; })});  // 2 I1 + I3 = 7 > 3
  bad.push_back({"ball_mass", with([](PhysicalParameters& p) { p.ball_mass = 0.0; })});
  for (const Bad& b : bad) {
    const std::string m = Message(b.p);
    EXPECT_NE(m.find(std::string("physical.") + b.field + ": value"), std::string::npos) << m;
    EXPECT_FALSE(b.p.Validate().empty());
  }
  EXPECT_TRUE(Example().Validate().empty());
}

TEST(BallModel, InvalidDimensionlessValuesAreRejectedNamingTheField) {
  const auto message = [](auto&& f) { return plateball::testing::InvalidArgumentMessage(f, "no exception"); };
  for (double lambda : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_NE(message([&] { BallModel::FromLambda(lambda); }).find("lambda: value"), std::string::npos);
  EXPECT_NE(message([] { BallModel::FromAlphaBeta(0.0, 1.0); }).find("alpha: value"), std::string::npos);
  EXPECT_NE(message([] { BallModel::FromAlphaBeta(2.5, 1.0); }).find("alpha: value"), std::string::npos);
  EXPECT_NE(message([] { BallModel::FromAlphaBeta(1.0, -0.5); }).find("beta: value"), std::string::npos);
  EXPECT_NE(message([] { BallModel::EnergyToMu(Example(), -1.0); }).find("kinetic_energy: value"), std::string::npos);
}

}  // namespace
}  // namespace plateball
