// The actuator's impulse on the upper plate, checked by an independent route: the impulsive
// Newton-Euler equations of ball and plate solved for the ball's response to a given plate impulse,
// the work-energy balance of an impulse, and the homogeneous ball's closed form.
#include "plateball/plate_impulse.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "plateball/ball_state.h"
#include "plateball/impulse.h"
#include "support/test_support.h"

namespace plateball {
namespace {

using plateball::testing::PhysicalUnitsBall;

Eigen::Matrix3d Inertia(const PhysicalParameters& p, const Eigen::Vector3d& z) {
  return p.inertia_1 * Eigen::Matrix3d::Identity() + (p.inertia_3 - p.inertia_1) * z * z.transpose();
}

// Forward problem: the plate receives J; unknowns (delta_omega, Q, G, tau) from
//   M_ball dv = Q + G,  I dw = r e3 x Q - r e3 x G + tau e3,  M_plate dV = J - Q,  dw_3 = 0,
// with dv = r dw x e3 and dV = 2 dv (rolling at both contacts).
Eigen::Vector3d ResponseTo(const PhysicalParameters& p, const Eigen::Vector3d& z, const Eigen::Vector3d& j) {
  Eigen::Matrix3d cross_e3;  // w -> w x e3
  cross_e3 << 0, 1, 0, -1, 0, 0, 0, 0, 0;
  Eigen::Matrix<double, 3, 2> e3_cross;  // horizontal F -> e3 x F
  e3_cross << 0, -1, 1, 0, 0, 0;
  const Eigen::Matrix<double, 2, 3> dv = p.radius * cross_e3.topRows<2>();
  Eigen::Matrix<double, 8, 8> a = Eigen::Matrix<double, 8, 8>::Zero();
  Eigen::Matrix<double, 8, 1> b = Eigen::Matrix<double, 8, 1>::Zero();
  a.block<2, 3>(0, 0) = p.ball_mass * dv;
  a.block<2, 2>(0, 3) = a.block<2, 2>(0, 5) = -Eigen::Matrix2d::Identity();
  a.block<3, 3>(2, 0) = Inertia(p, z);
  a.block<3, 2>(2, 3) = -p.radius * e3_cross;
  a.block<3, 2>(2, 5) = p.radius * e3_cross;
  a(4, 7) = -1.0;
  a.block<2, 3>(5, 0) = 2.0 * p.plate_mass * dv;
  a.block<2, 2>(5, 3) = Eigen::Matrix2d::Identity();
  b.segment<2>(5) = j.head<2>();
  a(7, 2) = 1.0;
  return a.colPivHouseholderQr().solve(b).head<3>();
}

double KineticEnergy(const PhysicalParameters& p, const BallState& s) {
  const double v2 = p.radius * p.radius * (s.omega.x() * s.omega.x() + s.omega.y() * s.omega.y());
  return 0.5 * s.omega.dot(Inertia(p, s.z) * s.omega) + 0.5 * (p.ball_mass + 4.0 * p.plate_mass) * v2;
}

TEST(PlateImpulse, ForwardNewtonEulerOfThePlateImpulseGivesBackTheJump) {
  // Relative agreement: an 8 x 8 solve with condition ~1e4 in these units.
  constexpr double kAgreement = 1e-10;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const PhysicalParameters p = PhysicalUnitsBall();
  const BallModel model = BallModel::FromPhysical(p);
  for (int i = 0; i < 20; ++i) {
    const AngleState angles{1.5 * u(rng) + 1.6, 3.0 * u(rng), 3.0 * u(rng)};
    const Impulse imp = EnergyPreservingImpulse(angles, 4.0, 2.0 * u(rng), model);
    const PlateImpulse j = PlateImpulseFor(p, imp.state_before.z, imp.delta_omega);
    const Eigen::Vector3d back = ResponseTo(p, imp.state_before.z, j.plate);
    EXPECT_LT((back - imp.delta_omega).norm(), kAgreement * imp.delta_omega.norm()) << i;
    // Work-energy: an impulse J on a body whose velocity jumps from V- to V+ does work J . (V- + V+)/2.
    const Eigen::Vector3d v_before = 2.0 * p.radius * imp.state_before.omega.cross(Eigen::Vector3d::UnitZ());
    const Eigen::Vector3d v_after = 2.0 * p.radius * imp.state_after.omega.cross(Eigen::Vector3d::UnitZ());
    const double work = j.plate.dot(0.5 * (v_before + v_after));
    const double scale = KineticEnergy(p, imp.state_before);
    EXPECT_NEAR(work, KineticEnergy(p, imp.state_after) - scale, kAgreement * scale) << i;
    EXPECT_NEAR(work, 0.0, kAgreement * scale) << i;  // energy-preserving: the actuator does no net work
    EXPECT_LT((j.plate_velocity_change - (v_after - v_before)).norm(), kAgreement * j.plate_velocity_change.norm())
        << i;
  }
}

TEST(PlateImpulse, HomogeneousBallHasTheReducedMassAtThePlate) {
  // I = I0 everywhere: T = ((I0 + M r^2)/(4 r^2) + M_plate) V^2 / 2 in the plate's velocity V, so
  // J = ((I0 + M r^2)/(4 r^2) + M_plate) dV, and the ball's orientation does not matter.
  PhysicalParameters p = PhysicalUnitsBall();
  p.inertia_1 = p.inertia_3 = 0.4 * p.ball_mass * p.radius * p.radius;
  const double mass_at_plate =
      (p.inertia_1 + p.ball_mass * p.radius * p.radius) / (4 * p.radius * p.radius) + p.plate_mass;
  const Eigen::Vector3d dw(0.3, -1.2, 0.0);
  for (const Eigen::Vector3d& z : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.6, 0, 0.8)}) {
    const PlateImpulse j = PlateImpulseFor(p, z, dw);
    EXPECT_LT((j.plate - mass_at_plate * j.plate_velocity_change).norm(), 1e-15);
    EXPECT_NEAR(j.torsion, 0.0, 1e-20);
  }
}

TEST(PlateImpulse, TheImpulseDependsOnTheOrientation) {
  // A non-homogeneous ball: the same plate velocity change needs different J for z vertical and tilted,
  // and a torsional impulse when z is tilted toward delta_omega.
  const PhysicalParameters p = PhysicalUnitsBall();
  const Eigen::Vector3d dw(1.0, 0.0, 0.0);
  const PlateImpulse up = PlateImpulseFor(p, Eigen::Vector3d::UnitZ(), dw);
  const Eigen::Vector3d tilted = Eigen::Vector3d(1, 0, 1).normalized();
  const PlateImpulse tilt = PlateImpulseFor(p, tilted, dw);
  EXPECT_EQ(up.plate_velocity_change, tilt.plate_velocity_change);
  // J_y = -(I dw)_x / (2r) - (M_ball r^2 dw_x)/(2r) - 2 r M_plate dw_x; (I dw)_x = I1 (up), (I1 + I3)/2 (tilted).
  const double r = p.radius;
  EXPECT_NEAR(up.plate.y(), -(p.inertia_1 + p.ball_mass * r * r) / (2 * r) - 2 * r * p.plate_mass, 1e-15);
  EXPECT_NEAR(tilt.plate.y(),
              -(0.5 * (p.inertia_1 + p.inertia_3) + p.ball_mass * r * r) / (2 * r) - 2 * r * p.plate_mass,
              1e-15);
  EXPECT_NEAR(tilt.torsion, 0.5 * (p.inertia_3 - p.inertia_1), 1e-18);
  EXPECT_NEAR(up.torsion, 0.0, 1e-20);
}

TEST(PlateImpulse, InvalidInputIsRejectedNamingTheField) {
  const auto message = [](auto&& f) { return plateball::testing::InvalidArgumentMessage(f, "no exception"); };
  const PhysicalParameters p = PhysicalUnitsBall();
  EXPECT_NE(message([&] { PlateImpulseFor(p, {0, 0, 2}, {1, 0, 0}); }).find("z: value 2"), std::string::npos);
  EXPECT_NE(message([&] {
              PlateImpulseFor(p, {0, 0, 1}, {1, 0, 0.5});
            }).find("delta_omega[2]: value 0.5"),
            std::string::npos);
  EXPECT_NE(message([&] { PlateImpulseFor(p, {0, 0, 1}, {NAN, 0, 0}); }).find("delta_omega: value"), std::string::npos);
  PhysicalParameters bad = p;
  bad.radius = -1.0;
  EXPECT_NE(message([&] { PlateImpulseFor(bad, {0, 0, 1}, {1, 0, 0}); }).find("physical.radius"), std::string::npos);
}

}  // namespace
}  // namespace plateball
