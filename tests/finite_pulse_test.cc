// Finite pulses: the forced equations (the moment of the plate force about the lower contact) against
// the two-body Newton-Euler equations of ball and plate with an external plate force, the ideal
// impulse's jump of K against PlateImpulseFor's contact impulses, and the order with which a pulse of
// duration delta approaches the ideal impulse: centred O(delta^2), causal O(delta).
#include "plateball/finite_pulse.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "plateball/plate_impulse.h"
#include "support/test_support.h"

namespace plateball {
namespace {

using plateball::testing::PhysicalUnitsBall;

double Lambda(const PhysicalParameters& p) {
  const double m = p.EffectiveMass() * p.radius * p.radius;
  return (p.inertia_3 + m) / (p.inertia_1 + m);
}

Eigen::Vector2d KFromOmega(const PhysicalParameters& p, const Eigen::Vector3d& z, const Eigen::Vector2d& w) {
  return w + (Lambda(p) - 1.0) * (w.dot(z.head<2>())) * z.head<2>();
}

Eigen::Vector2d OmegaFromK(const PhysicalParameters& p, const Eigen::Vector3d& z, const Eigen::Vector2d& k) {
  const double lambda = Lambda(p);
  const double v0 = k.dot(z.head<2>()) / (z.z() * z.z() + lambda * z.head<2>().squaredNorm());
  return k - (lambda - 1.0) * v0 * z.head<2>();
}

// Newton-Euler of ball (about its centre) and plate with the force F on the plate; unknowns
// (omega'[3], Q[2], G[2], tau):  M_ball a = Q + G,  I omega' + (I3 - I1)(z.omega) omega x z =
// r e3 x Q - r e3 x G + tau e3,  M_plate 2 a = F - Q,  omega'_3 = 0, with a = r omega' x e3.
Eigen::Vector3d OmegaRateByNewtonEuler(const PhysicalParameters& p,
                                       const Eigen::Vector3d& z,
                                       const Eigen::Vector3d& w,
                                       const Eigen::Vector3d& f) {
  Eigen::Matrix3d cross_e3;  // w -> w x e3
  cross_e3 << 0, 1, 0, -1, 0, 0, 0, 0, 0;
  Eigen::Matrix<double, 3, 2> e3_cross;  // horizontal F -> e3 x F
  e3_cross << 0, -1, 1, 0, 0, 0;
  const Eigen::Matrix<double, 2, 3> a_of = p.radius * cross_e3.topRows<2>();
  const Eigen::Matrix3d inertia =
      p.inertia_1 * Eigen::Matrix3d::Identity() + (p.inertia_3 - p.inertia_1) * z * z.transpose();
  Eigen::Matrix<double, 8, 8> a = Eigen::Matrix<double, 8, 8>::Zero();
  Eigen::Matrix<double, 8, 1> b = Eigen::Matrix<double, 8, 1>::Zero();
  a.block<2, 3>(0, 0) = p.ball_mass * a_of;
  a.block<2, 2>(0, 3) = a.block<2, 2>(0, 5) = -Eigen::Matrix2d::Identity();
  a.block<3, 3>(2, 0) = inertia;
  a.block<3, 2>(2, 3) = -p.radius * e3_cross;
  a.block<3, 2>(2, 5) = p.radius * e3_cross;
  a(4, 7) = -1.0;
  b.segment<3>(2) = -(p.inertia_3 - p.inertia_1) * z.dot(w) * w.cross(z);
  a.block<2, 3>(5, 0) = 2.0 * p.plate_mass * a_of;
  a.block<2, 2>(5, 3) = Eigen::Matrix2d::Identity();
  b.segment<2>(5) = f.head<2>();
  a(7, 2) = 1.0;
  return a.colPivHouseholderQr().solve(b).head<3>();
}

TEST(FinitePulse, ForcedMotionMatchesTwoBodyNewtonEuler) {
  // Central difference over 2h = 2e-5 s: error ~ h^2 |omega'''| / 6 ~ 1e-9 relative here, plus the
  // integration tolerance 1e-12 / h ~ 1e-7 rad/s^2 against rates of ~1e2-1e3 rad/s^2.
  constexpr double kH = 1e-5, kRelative = 1e-6;
  const PhysicalParameters p = PhysicalUnitsBall();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 10; ++i) {
    PulsedState s;
    s.z = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const Eigen::Vector2d w0(5 * u(rng), 5 * u(rng));
    s.k = KFromOmega(p, s.z, w0);
    const Eigen::Vector3d force(u(rng), u(rng), 0.0);  // N
    const PulsedState mid = RunPulsed(p, s, 0.0, kH, {{0.0, kH, force * kH}});
    const PulsedState end = RunPulsed(p, s, 0.0, 2 * kH, {{0.0, 2 * kH, force * 2 * kH}});
    const Eigen::Vector2d rate = (OmegaFromK(p, end.z, end.k) - w0) / (2 * kH);
    const Eigen::Vector2d w_mid = OmegaFromK(p, mid.z, mid.k);
    const Eigen::Vector3d expected = OmegaRateByNewtonEuler(p, mid.z, {w_mid.x(), w_mid.y(), 0.0}, force);
    EXPECT_LT((rate - expected.head<2>()).norm(), kRelative * expected.norm()) << i;
    EXPECT_NEAR(expected.z(), 0.0, 1e-12 * expected.norm()) << i;
  }
}

TEST(FinitePulse, IdealImpulseJumpsKAsThePlateImpulseSays) {
  // Two derivations: PlateImpulseFor (contact impulses, Newton-Euler) and the moment about the lower
  // contact (MomentumRate). J applied at once must change K by K(omega + dw) - K(omega).
  constexpr double kRelative = 1e-12;  // a few roundings of quantities of similar size
  const PhysicalParameters p = PhysicalUnitsBall();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 10; ++i) {
    const Eigen::Vector3d z = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const Eigen::Vector2d w(u(rng), u(rng)), dw(u(rng), u(rng));
    const PlateImpulse j = PlateImpulseFor(p, z, {dw.x(), dw.y(), 0.0});
    const Eigen::Vector2d dk = KFromOmega(p, z, w + dw) - KFromOmega(p, z, w);
    EXPECT_LT((MomentumRate(p, j.plate) - dk).norm(), kRelative * dk.norm()) << i;
  }
}

struct OrderFit {
  double slope;
  std::vector<double> errors;
};

// Final-state error of one pulse of duration delta against the ideal impulse at t_k = 0.5 s, fitted
// as error ~ C delta^slope by least squares in log-log over delta = 0.04 ... 0.005 s.
OrderFit FitOrder(bool centred) {
  const PhysicalParameters p = PhysicalUnitsBall();
  PulsedState s;
  s.z = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  s.k = KFromOmega(p, s.z, {4.0, -2.0});
  constexpr double kT = 1.0, kTk = 0.5;
  const PlateImpulse j = PlateImpulseFor(p, RunPulsed(p, s, 0.0, kTk, {}).z, {-3.0, 2.5, 0.0});
  PulsedState ideal = RunPulsed(p, s, 0.0, kTk, {});
  ideal.k += MomentumRate(p, j.plate);
  ideal = RunPulsed(p, ideal, kTk, kT, {});
  OrderFit fit{0.0, {}};
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const std::vector<double> deltas{0.04, 0.02, 0.01, 0.005};
  for (const double delta : deltas) {
    const double start = centred ? kTk - 0.5 * delta : kTk;
    const PulsedState run = RunPulsed(p, s, 0.0, kT, {{start, delta, j.plate}});
    const double e = (run.z - ideal.z).norm() + (run.x - ideal.x).norm() / p.radius +
                     (OmegaFromK(p, run.z, run.k) - OmegaFromK(p, ideal.z, ideal.k)).norm();
    fit.errors.push_back(e);
    const double lx = std::log(delta), ly = std::log(e);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  const double n = static_cast<double>(deltas.size());
  fit.slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return fit;
}

TEST(FinitePulse, CentredPulsesConvergeQuadraticallyCausalLinearly) {
  // The centred pulse's first-order term cancels by symmetry about t_k; the causal one's does not.
  constexpr double kCentredSlope = 2.0, kCentredTolerance = 0.2, kCausalSlope = 1.0, kCausalTolerance = 0.1;
  const OrderFit centred = FitOrder(true), causal = FitOrder(false);
  EXPECT_NEAR(centred.slope, kCentredSlope, kCentredTolerance);
  EXPECT_NEAR(causal.slope, kCausalSlope, kCausalTolerance);
  for (std::size_t i = 0; i < centred.errors.size(); ++i) {
    std::printf("delta index %zu: centred %.3e causal %.3e\n", i, centred.errors[i], causal.errors[i]);
    EXPECT_LT(centred.errors[i], causal.errors[i]);
  }
  std::printf("slopes: centred %.4f causal %.4f\n", centred.slope, causal.slope);
}

TEST(FinitePulse, BadPulsesAreRejectedNamingTheField) {
  const auto message = [](auto&& f) { return plateball::testing::InvalidArgumentMessage(f, "no exception"); };
  const PhysicalParameters p = PhysicalUnitsBall();
  const PulsedState s;
  const Eigen::Vector3d j(0.01, 0, 0);
  EXPECT_NE(message([&] {
              RunPulsed(p, s, 0, 1, {{0.2, 0.3, j}, {0.4, 0.1, j}});
            }).find("pulses[1].start: value 0.4"),
            std::string::npos);
  EXPECT_NE(message([&] {
              RunPulsed(p, s, 0, 1, {{0.9, 0.3, j}});
            }).find("pulses[0].start: value 0.9"),
            std::string::npos);
  EXPECT_NE(message([&] {
              RunPulsed(p, s, 0, 1, {{0.1, 0.0, j}});
            }).find("pulses[0].duration: value 0"),
            std::string::npos);
  EXPECT_NE(message([&] {
              RunPulsed(p, s, 0, 1, {{0.1, 0.1, {NAN, 0, 0}}});
            }).find("pulses[0].impulse[0]"),
            std::string::npos);
}

}  // namespace
}  // namespace plateball
