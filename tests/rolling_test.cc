// Rolling kinematics (section 2.1, "Rolling and reorientations"): A' = hat(e3 x x') A.
// Expected values: the exact segment formula, the closed form on a circle (derived below), and
// invariance under reparametrisation; never the integration under test itself.
#include "plateball/rolling.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "plateball/so3.h"
#include "support/test_support.h"

namespace plateball {
namespace {

using testing::IsRotationMatrix;

// Integration at tolerances 1e-12 over paths of length O(10): global error ~1e-11.
constexpr double kAgreement = 1e-9;

// Rolling on the circle x(tau) = rho (cos tau, sin tau) from A0: omega = e3 x x' = Rz(tau) w0
// with w0 = (-rho, 0, 0). Writing A = Rz(tau) B, A' = hat(e3) A + Rz B' (Rz' = hat(e3) Rz) and
// hat(Rz w0) = Rz hat(w0) Rz^T give B' = hat(w0 - e3) B, so
// A(tau) = Rz(tau) exp(tau hat(w0 - e3)) A0 (docs/paper_notes.md has no correction here: this is
// the test's independent closed form).
Eigen::Matrix3d CircleOrientation(double rho, double tau, const Eigen::Matrix3d& a0) {
  const Eigen::Vector3d w0(-rho, 0.0, 0.0);
  return RotationZ(tau) * ExpSO3(tau * (w0 - Eigen::Vector3d::UnitZ())) * a0;
}

// Reorientation A(b) A(a)^-1 along the circle from its closed form.
Eigen::Matrix3d CircleReorientation(double rho, double a, double b) {
  return CircleOrientation(rho, b, Eigen::Matrix3d::Identity()) *
         CircleOrientation(rho, a, Eigen::Matrix3d::Identity()).transpose();
}

TEST(Rolling, CircleMatchesClosedForm) {
  for (double rho : {0.3, 1.0, 2.5})
    for (const auto& [a, b] :
         std::vector<std::pair<double, double>>{{0.0, 1.0}, {0.0, 2 * M_PI}, {-1.0, 4.0}, {2.0, 0.5}}) {
      const PlanarVelocity v = [rho](double tau) { return Eigen::Vector2d(-rho * std::sin(tau), rho * std::cos(tau)); };
      const Eigen::Matrix3d r = RollingReorientation(v, a, b);
      EXPECT_LT((r - CircleReorientation(rho, a, b)).norm(), kAgreement)
          << "rho " << rho << " [" << a << ", " << b << "]";
      EXPECT_TRUE(IsRotationMatrix(r));
    }
}

TEST(Rolling, ReorientationIsIndependentOfTheParametrisation) {
  // p(s) = (cos s + 0.3 s, sin 2s), s in [0, 2], traversed with s = tau, s = sigma^2 (sigma in
  // [0, sqrt 2], speed 0 at the start) and s = u + 0.5 sin u (u in [0, u1], non-uniform speed).
  auto dp = [](double s) { return Eigen::Vector2d(-std::sin(s) + 0.3, 2.0 * std::cos(2.0 * s)); };
  const Eigen::Matrix3d r1 = RollingReorientation(dp, 0.0, 2.0);
  const Eigen::Matrix3d r2 =
      RollingReorientation([&](double sg) { return Eigen::Vector2d(dp(sg * sg) * 2.0 * sg); }, 0.0, std::sqrt(2.0));
  // Solve u1 + 0.5 sin(u1) = 2 by Newton (g' = 1 + 0.5 cos u > 0).
  double u1 = 2.0;
  for (int i = 0; i < 50; ++i) u1 -= (u1 + 0.5 * std::sin(u1) - 2.0) / (1.0 + 0.5 * std::cos(u1));
  const Eigen::Matrix3d r3 = RollingReorientation(
      [&](double u) { return Eigen::Vector2d(dp(u + 0.5 * std::sin(u)) * (1.0 + 0.5 * std::cos(u))); }, 0.0, u1);
  EXPECT_LT((r1 - r2).norm(), kAgreement);
  EXPECT_LT((r1 - r3).norm(), kAgreement);
  // Reversed traversal gives the inverse rotation.
  EXPECT_LT((RollingReorientation(dp, 2.0, 0.0) - r1.transpose()).norm(), kAgreement);
}

TEST(Rolling, ArcLengthParametrisationOfTheCircleGivesTheSameRotation) {
  const double rho = 1.7, tau1 = 2.2;
  // Arc length sigma = rho tau: unit speed.
  const PlanarVelocity unit = [rho](double sg) { return Eigen::Vector2d(-std::sin(sg / rho), std::cos(sg / rho)); };
  EXPECT_LT((RollingReorientation(unit, 0.0, rho * tau1) - CircleReorientation(rho, 0.0, tau1)).norm(), kAgreement);
}

TEST(Rolling, SegmentFormulaMatchesIntegrationOnALine) {
  const Eigen::Vector2d p(0.5, -1.0), q(-2.0, 3.0);
  // Traversed with non-uniform speed: x(tau) = p + (q - p) (tau^3 + tau) / 2, tau in [0, 1].
  const PlanarVelocity v = [&](double tau) { return Eigen::Vector2d((q - p) * (3 * tau * tau + 1) / 2); };
  const Eigen::Matrix3d r = RollingReorientation(v, 0.0, 1.0);
  EXPECT_LT((r - RollAlongSegment(p, q)).norm(), kAgreement);
  // Rolling a distance 2 pi along e1 turns the ball once about e2 (omega = e3 x x' = e2 speed).
  EXPECT_LT((RollAlongSegment({0, 0}, {2 * M_PI, 0}) - Eigen::Matrix3d::Identity()).norm(), 1e-14);
  EXPECT_LT((RollAlongSegment({0, 0}, {M_PI / 2, 0}) - ExpSO3(Eigen::Vector3d(0, M_PI / 2, 0))).norm(), 1e-15);
  // Collinear pieces compose to the whole segment.
  EXPECT_LT((RollAlongPolyline({p, p + 0.25 * (q - p), p + 0.6 * (q - p), q}) - RollAlongSegment(p, q)).norm(), 1e-14);
}

TEST(Rolling, BreakpointsHandleACorner) {
  // An L-shaped path: (0,0) -> (1,0) -> (1,2), tau in [0, 3], velocity jumping at tau = 1.
  const PlanarVelocity v = [](double tau) { return tau < 1.0 ? Eigen::Vector2d(1.0, 0.0) : Eigen::Vector2d(0.0, 1.0); };
  const Eigen::Matrix3d expected = RollAlongPolyline({{0, 0}, {1, 0}, {1, 2}});
  EXPECT_LT((RollingReorientation(v, 0.0, 3.0, {1.0}) - expected).norm(), kAgreement);
  EXPECT_TRUE(IsRotationMatrix(expected));
}

TEST(Rolling, SamplesConvergeToTheExactCircle) {
  // Natural cubic spline through n samples of a half circle: measured errors 7.9e-4, 9.9e-5,
  // 1.2e-5, 1.5e-6, 1.9e-7 for n = 16 ... 256, i.e. order 3 (the natural end conditions limit
  // it). Asserted: every doubling divides the error by more than 6 (order > 2.5), and n = 256 is
  // within 1e-6 of the exact rotation.
  const double rho = 1.5, tau1 = M_PI;
  const Eigen::Matrix3d exact = CircleReorientation(rho, 0.0, tau1);
  double previous = 0.0;
  for (int n : {16, 32, 64, 128, 256}) {
    std::vector<Eigen::Vector2d> pts;
    for (int i = 0; i <= n; ++i) {
      const double tau = tau1 * i / n;
      pts.emplace_back(rho * std::cos(tau), rho * std::sin(tau));
    }
    const Eigen::Matrix3d r = RollAlongSamples(pts);
    EXPECT_TRUE(IsRotationMatrix(r));
    const double err = OperatorNormDistance(r, exact);
    if (previous > 0) {
      EXPECT_LT(err, previous / 6.0) << "n " << n;
    }
    previous = err;
    if (n == 256) {
      EXPECT_LT(err, 1e-6);
    }
  }
}

TEST(Rolling, InvalidInputIsRejectedNamingTheField) {
  const auto message = [](auto&& f) { return plateball::testing::InvalidArgumentMessage(f, "no exception"); };
  const PlanarVelocity v = [](double) { return Eigen::Vector2d(1.0, 0.0); };
  EXPECT_NE(message([&] { RollingReorientation(v, NAN, 1.0); }).find("a: value"), std::string::npos);
  EXPECT_NE(message([&] { RollingReorientation(PlanarVelocity(), 0.0, 1.0); }).find("velocity"), std::string::npos);
  EXPECT_NE(message([&] { RollAlongSamples({{0, 0}}); }).find("samples"), std::string::npos);
  EXPECT_NE(message([&] { RollAlongPolyline({{0, 0}, {NAN, 1}}); }).find("points[1]"), std::string::npos);
  // A velocity that turns non-finite is a runtime error, not a hang or a NaN rotation.
  const PlanarVelocity bad = [](double t) { return Eigen::Vector2d(t > 0.5 ? NAN : 1.0, 0.0); };
  EXPECT_THROW(RollingReorientation(bad, 0.0, 1.0), std::runtime_error);
}

}  // namespace
}  // namespace plateball
