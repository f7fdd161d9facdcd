// The first-order part of the window certificate (src/isoparallel_certify_jacobian.h): the
// closed-form heading derivatives against central differences of the elastica's pendulum angle,
// the residual's Jacobian against central differences of the residual computed independently
// (dopri5 rollings of the closed-form tangent), and Newton's method recovering a made solution.
#include "isoparallel_certify_jacobian.h"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <cstdio>
#include <random>

#include "plateball/elastica.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"
#include "rotation_trick.h"

using namespace plateball;
using namespace plateball::internal;

namespace {

const PendulumRegime kBothRegimes[] = {PendulumRegime::kOscillating, PendulumRegime::kRotating};

// Q(0, L) of the parameter point by dopri5 at 1e-13 of the closed-form tangent.
Eigen::Matrix3d DopriRolling(const Elastica& e, double length) {
  IntegrationOptions o;
  o.absolute_tolerance = 1e-13;
  o.relative_tolerance = 1e-13;
  return RollingReorientation([&e](double s) { return e.Tangent(s); }, 0.0, length, {}, o);
}

// F at x from the independent rolling.
Eigen::Vector4d DopriResidual(const CertifyTarget& target, PendulumRegime regime, const CertifyPoint& x) {
  const Elastica e = CertifyElastica(regime, x);
  const Eigen::Vector2d chord = e.Position(x[kCertifyLength]);
  Eigen::Vector4d f;
  f << chord.norm() - target.radius,
      RotationTrickResidual(target.target, ChordTurn(target.goal_angle, chord), DopriRolling(e, x[kCertifyLength]));
  return f;
}

// A target made from a chosen path, its goal turned by 0.3 from the path's chord: the path solves it.
CertifyTarget MadeTarget(PendulumRegime regime, const CertifyPoint& made) {
  const Elastica e = CertifyElastica(regime, made);
  const Eigen::Vector2d chord = e.Position(made[kCertifyLength]);
  CertifyTarget t;
  t.radius = chord.norm();
  t.goal_angle = std::atan2(chord.y(), chord.x()) + 0.3;
  const Eigen::Matrix3d b = RotationZ(0.3);
  t.target = b * DopriRolling(e, made[kCertifyLength]) * b.transpose();
  return t;
}

const CertifyPoint kMadeRotating = {0.6, 0.6, 0.7, 3.0};
const CertifyPoint kMadeOscillating = {1.1, 0.8, 1.8, 5.0};

}  // namespace

// theta, d theta/dv and d theta/dk at fixed v against the elastica's own pendulum angle and its
// central differences (step 1e-5 in v, 1e-6 in k), k from 0.0005 (the small-k series) to 0.95,
// |v| <= 30.
TEST(IsoparallelCertifyJacobian, HeadingDerivativesMatchCentralDifferences) {
  const auto theta = [](PendulumRegime regime, double k, double v) {
    ElasticaParameters p;
    p.regime = regime;
    p.rate = 1.0;
    p.modulus = k;
    return Elastica(p).PendulumAngle(v);
  };
  for (PendulumRegime regime : kBothRegimes) {
    double worst = 0.0;
    for (double k : {0.0005, 0.01, 0.1, 0.35, 0.6, 0.8, 0.9, 0.95}) {
      const double kp = std::sqrt(1 - k * k), scale = 1.0 / (kp * kp * kp);
      for (double v = -30.0; v <= 30.0; v += 0.0731) {
        const HeadingDerivatives d = HeadingDerivativesAt(regime, k, v);
        ASSERT_NEAR(d.theta, theta(regime, k, v), 1e-12 * (1 + std::abs(v))) << k << " " << v;
        const double dv = (theta(regime, k, v + 1e-5) - theta(regime, k, v - 1e-5)) / 2e-5;
        const double hk = std::min(1e-6, 0.5 * k);
        const double dk = (theta(regime, k + hk, v) - theta(regime, k - hk, v)) / (2 * hk);
        ASSERT_NEAR(d.dv, dv, 1e-8) << ToString(regime) << " k " << k << " v " << v;
        const double err = std::abs(d.dk - dk) / (scale * (1 + std::abs(v)));
        ASSERT_LT(err, 2e-8) << ToString(regime) << " k " << k << " v " << v << " " << d.dk << " " << dk;
        worst = std::max(worst, err);
      }
    }
    std::printf("%s: worst |d theta/dk - central difference| / ((1 + |v|) / k'^3) = %.2e\n", ToString(regime).c_str(),
                worst);
  }
}

// The Jacobian (Magnus table + quadrature, steps 0.05) against central differences (step 1e-5)
// of the residual from dopri5 rollings, at the made solutions and at random points of both
// regimes (rate [-1.5, 1.5], k [0.05, 0.9], phase [0, 4], L [0.5, 8]); the residual itself too.
TEST(IsoparallelCertifyJacobian, JacobianMatchesCentralDifferencesOfDopriResiduals) {
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double h = 1e-5;
  double worst = 0.0;
  for (PendulumRegime regime : kBothRegimes) {
    const CertifyTarget target = MadeTarget(regime, regime == PendulumRegime::kRotating ? kMadeRotating : kMadeOscillating);
    for (int trial = 0; trial < 7; ++trial) {
      CertifyPoint x = regime == PendulumRegime::kRotating ? kMadeRotating : kMadeOscillating;
      if (trial > 0) x = {-1.5 + 3 * uni(rng), 0.05 + 0.85 * uni(rng), 4 * uni(rng), 0.5 + 7.5 * uni(rng)};
      CertifyJacobian j;
      if (!EvaluateCertifyJacobian(target, regime, x, 0.05, &j)) continue;  // e.g. a residual near pi
      const Eigen::Vector4d f = DopriResidual(target, regime, x);
      EXPECT_LT((j.residual - f).lpNorm<Eigen::Infinity>(), 1e-9) << ToString(regime) << " trial " << trial;
      for (int c = 0; c < 4; ++c) {
        CertifyPoint xp = x, xm = x;
        xp[c] += h;
        xm[c] -= h;
        const Eigen::Vector4d fd = (DopriResidual(target, regime, xp) - DopriResidual(target, regime, xm)) / (2 * h);
        const double err = (j.jacobian.col(c) - fd).lpNorm<Eigen::Infinity>() / (1 + fd.lpNorm<Eigen::Infinity>());
        EXPECT_LT(err, 2e-6) << ToString(regime) << " trial " << trial << " column " << c << "\n"
                             << j.jacobian.col(c).transpose() << "\n" << fd.transpose();
        worst = std::max(worst, err);
      }
    }
  }
  std::printf("worst relative |J - central difference of dopri5 residuals| = %.2e\n", worst);
}

// Newton's method from a start 0.02 off in every coordinate recovers the made solution to 1e-9,
// and the Jacobian there is well conditioned enough to be inverted (a regular root).
TEST(IsoparallelCertifyJacobian, NewtonRecoversMadeSolutions) {
  for (PendulumRegime regime : kBothRegimes) {
    const CertifyPoint made = regime == PendulumRegime::kRotating ? kMadeRotating : kMadeOscillating;
    const CertifyTarget target = MadeTarget(regime, made);
    CertifyPoint x = made;
    for (int i = 0; i < 4; ++i) x[i] += (i % 2 == 0 ? 0.02 : -0.02);
    ASSERT_TRUE(NewtonRefineCertify(target, regime, 0.02, 1e-11, 12, &x)) << ToString(regime);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(x[i], made[i], 1e-9) << ToString(regime) << " axis " << i;
    CertifyJacobian j;
    ASSERT_TRUE(EvaluateCertifyJacobian(target, regime, x, 0.02, &j));
    const Eigen::Vector4d sv = Eigen::JacobiSVD<Eigen::Matrix4d>(j.jacobian).singularValues();
    std::printf("%s made solution: singular values %.3g %.3g %.3g %.3g\n", ToString(regime).c_str(), sv[0], sv[1],
                sv[2], sv[3]);
    EXPECT_GT(sv[3], 1e-3);
  }
}
