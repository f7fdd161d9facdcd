// The first-order part of the window certificate (src/certify/jacobian.h): the
// closed-form heading derivatives against central differences of the elastica's pendulum angle,
// the residual's Jacobian against central differences of the residual computed independently
// (dopri5 rollings of the closed-form tangent), and Newton's method recovering a made solution.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <boost/math/special_functions/ellint_1.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "certify/jacobian.h"
#include "certify/support/dopri_rolling.h"
#include "certify/window.h"
#include "elastica_rolling.h"
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
  return plateball::testing::DopriElasticaRolling(e, length, 1e-13);
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
    std::printf(
        "%s: worst |d theta/dk - central difference| / ((1 + |v|) / k'^3) = %.2e\n", ToString(regime).c_str(), worst);
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
    const CertifyTarget target =
        MadeTarget(regime, regime == PendulumRegime::kRotating ? kMadeRotating : kMadeOscillating);
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
                             << j.jacobian.col(c).transpose() << "\n"
                             << fd.transpose();
        worst = std::max(worst, err);
      }
    }
  }
  std::printf("worst relative |J - central difference of dopri5 residuals| = %.2e\n", worst);
}

namespace {

// A random point of a window reaching high rates and lengths: |rate| in [0.3, 1] rate_max (either
// sign), k' = 10^(-4.4 u) (k from 0 to the window's largest modulus), phase [-8, 8], L [0.5, 1]
// length_max.
CertifyPoint RandomFarPoint(std::mt19937& rng, double rate_max, double length_max) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double rate = (0.3 + 0.7 * uni(rng)) * rate_max * (uni(rng) < 0.5 ? -1.0 : 1.0);
  const double kp = std::pow(10.0, -4.4 * uni(rng));
  return {rate, std::sqrt((1.0 - kp) * (1.0 + kp)), 16.0 * uni(rng) - 8.0, length_max * (0.5 + 0.5 * uni(rng))};
}

CertifyBox PointBox(const CertifyPoint& x) {
  CertifyBox box;
  box.lo = box.hi = x;
  return box;
}

}  // namespace

// The residual the first-order tests use is within CertifyResidualError of the residual from an
// independent rolling, a sixth-order Magnus table at steps of 0.005 / |rate| (1024 per period; its
// own error measured ~1e-11 at rate 80 and length 60), at rates up to 80 and lengths up to 60 of
// both regimes, k' down to 4e-5; the error stays below a fifth of the bound. (With the Magnus
// table at steps of 0.05 that the residual used before, the error reached 5e-8 at rate 10.)
TEST(IsoparallelCertifyJacobian, ResidualIsWithinItsErrorBoundAtHighRatesAndLengths) {
  std::mt19937 rng(20261125);
  for (PendulumRegime regime : kBothRegimes) {
    const CertifyTarget target =
        MadeTarget(regime, regime == PendulumRegime::kRotating ? kMadeRotating : kMadeOscillating);
    double worst = 0.0;
    int points = 0;
    for (double rate_max : {1.5, 10.0, 30.0, 80.0}) {
      for (double length_max : {6.0, 20.0, 60.0}) {
        for (int trial = 0; trial < 6; ++trial) {
          const CertifyPoint x = RandomFarPoint(rng, rate_max, length_max);
          CertifyJacobian j;
          if (!EvaluateCertifyJacobian(target, regime, x, 0.05, &j)) continue;  // a residual near pi
          const Elastica e = CertifyElastica(regime, x);
          const ElasticaRollingTable fine(e, x[kCertifyLength], 1024, 0.005 / std::abs(x[kCertifyRate]), 40000000);
          ASSERT_TRUE(fine.Valid());
          const Eigen::Vector2d chord = e.Position(x[kCertifyLength]);
          Eigen::Vector4d f;
          f << chord.norm() - target.radius,
              RotationTrickResidual(
                  target.target, ChordTurn(target.goal_angle, chord), fine.Rolling(x[kCertifyLength]));
          const double ratio = (j.residual - f).lpNorm<Eigen::Infinity>() / CertifyResidualError(PointBox(x));
          EXPECT_LT(ratio, 0.2) << ToString(regime) << " rate " << x[0] << " k " << x[1] << " L " << x[3];
          worst = std::max(worst, ratio);
          ++points;
        }
      }
    }
    EXPECT_GE(points, 60) << ToString(regime);
    std::printf("%s: %d points, largest |residual - Magnus residual| / CertifyResidualError = %.3g\n",
                ToString(regime).c_str(),
                points,
                worst);
  }
}

// At high rates (|rate| up to 75, k up to 0.999, L up to 12) the Jacobian's columns agree with
// fourth-order central differences (Richardson) of the closed-form residual to within
// kJacobianMargin (1e-6) of the column, as the enclosure assumes: its steps shrink with the rate
// (CertifyJacobianStep). The difference steps follow each column's scale: 1e-3 / L in rate,
// 3e-2 k'^2 / (1 + |v|_max) in k, 1e-3 in phase, 1e-3 / (1 + |rate|) in length. (Steps of 0.05
// alone were off by 2e-3 of the column at rate 25.)
TEST(IsoparallelCertifyJacobian, JacobianHoldsItsMarginAtHighRates) {
  std::mt19937 rng(11);
  for (PendulumRegime regime : kBothRegimes) {
    const CertifyTarget target =
        MadeTarget(regime, regime == PendulumRegime::kRotating ? kMadeRotating : kMadeOscillating);
    double worst = 0.0;
    int points = 0;
    for (double rate_max : {10.0, 26.0, 75.0}) {
      for (int trial = 0; trial < 8; ++trial) {
        CertifyPoint x = RandomFarPoint(rng, rate_max, 12.0);
        x[kCertifyModulus] = std::min(x[kCertifyModulus], 0.999);
        CertifyJacobian j;
        if (!EvaluateCertifyJacobian(target, regime, x, 0.05, &j)) continue;
        const auto residual = [&](int axis, double d) {
          CertifyPoint y = x;
          y[axis] += d;
          CertifyJacobian f;
          EXPECT_TRUE(EvaluateCertifyJacobian(target, regime, y, 0.05, &f));
          return Eigen::Vector4d(f.residual);
        };
        for (int c = 0; c < 4; ++c) {
          const double kp2 = (1.0 - x[kCertifyModulus]) * (1.0 + x[kCertifyModulus]);
          const double v_max = std::abs(x[kCertifyPhase]) + std::abs(x[kCertifyRate]) * x[kCertifyLength];
          const double h = c == kCertifyRate      ? 1e-3 / x[kCertifyLength]
                           : c == kCertifyModulus ? 3e-2 * kp2 / (1.0 + v_max)
                           : c == kCertifyPhase   ? 1e-3
                                                  : 1e-3 / (1.0 + std::abs(x[kCertifyRate]));
          const Eigen::Vector4d fd =
              (8.0 * (residual(c, h) - residual(c, -h)) - (residual(c, 2 * h) - residual(c, -2 * h))) / (12.0 * h);
          const double err = (j.jacobian.col(c) - fd).lpNorm<Eigen::Infinity>() / (1.0 + fd.lpNorm<Eigen::Infinity>());
          EXPECT_LT(err, kJacobianMargin) << ToString(regime) << " rate " << x[0] << " k " << x[1] << " column " << c;
          worst = std::max(worst, err);
        }
        ++points;
      }
    }
    EXPECT_GE(points, 20) << ToString(regime);
    std::printf(
        "%s: %d points, worst relative |J - central difference| = %.2e\n", ToString(regime).c_str(), points, worst);
  }
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
    std::printf("%s made solution: singular values %.3g %.3g %.3g %.3g\n",
                ToString(regime).c_str(),
                sv[0],
                sv[1],
                sv[2],
                sv[3]);
    EXPECT_GT(sv[3], 1e-3);
  }
}

// The second-derivative bounds never undershoot central differences (step 1e-6) of the tested
// closed-form first derivatives, k in [0.02, 0.96], |v| <= 30 (both taken at the sample's own k
// and |v|: the bounds increase in both).
TEST(IsoparallelCertifyJacobian, HeadingSecondDerivativeBoundsNeverUndershoot) {
  const double h = 1e-6;
  for (PendulumRegime regime : kBothRegimes) {
    double tightest = 1e300;
    for (double k = 0.02; k <= 0.961; k += 0.06) {
      for (double v = -30.0; v <= 30.0; v += 0.0931) {
        const HeadingSecondBounds b = HeadingSecondDerivativeBounds(regime, k, std::abs(v));
        const HeadingDerivatives vp = HeadingDerivativesAt(regime, k, v + h),
                                 vm = HeadingDerivativesAt(regime, k, v - h);
        const HeadingDerivatives kp = HeadingDerivativesAt(regime, k + h, v),
                                 km = HeadingDerivativesAt(regime, k - h, v);
        const double vv = (vp.dv - vm.dv) / (2 * h), vk = (kp.dv - km.dv) / (2 * h), kk = (kp.dk - km.dk) / (2 * h);
        ASSERT_LE(std::abs(vv), b.vv * (1 + 1e-6) + 1e-6) << ToString(regime) << " k " << k << " v " << v;
        ASSERT_LE(std::abs(vk), b.vk * (1 + 1e-6) + 1e-6) << ToString(regime) << " k " << k << " v " << v;
        ASSERT_LE(std::abs(kk), b.kk * (1 + 1e-6) + 1e-5) << ToString(regime) << " k " << k << " v " << v;
        tightest = std::min(tightest, b.kk / std::max(std::abs(kk), 1e-300));
      }
    }
    std::printf("%s: smallest bound / |d2 theta/dk2| sampled = %.3g\n", ToString(regime).c_str(), tightest);
  }
}

// The enclosure's end terms hold over the box's whole range of lengths [L_lo, L_max], not only its
// last piece: boxes whose phase brings v = rate s + u0 near 0 at L_max (|v| falls along the range
// from ~rate (L_max - L_lo), 1.5 to 22, at L_lo), sampled at random (rate, k, u0, s) with the centre's theta at
// the same s. Where |v| falls, the sampled |d theta/dk| exceeds the bound at the last piece (what
// the sums once took) in most boxes.
TEST(IsoparallelCertifyJacobian, EndHeadingBoundsHoldOverTheWholeLengthRange) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (PendulumRegime regime : kBothRegimes) {
    int beyond_last_piece = 0;
    double worst_dk = 0.0;  // largest sampled |d theta/dk| / EndHeadingBounds::dk
    for (int trial = 0; trial < 100; ++trial) {
      const double rate = 1.0 + 2.0 * uni(rng), k = 0.4 + 0.5 * uni(rng), l_max = 3.0 + 5.0 * uni(rng);
      const double half[3] = {1e-3 + 0.05 * uni(rng), 1e-3 + 0.05 * uni(rng), 1e-3 + 0.05 * uni(rng)};
      CertifyBox box;
      box.lo = {rate - half[0], k - half[1], -rate * l_max - half[2], l_max * (0.1 + 0.4 * uni(rng))};
      box.hi = {rate + half[0], k + half[1], -rate * l_max + half[2], l_max};
      const EndHeadingBounds ends = EndHeadingBoundsOf(regime, box);
      const CertifyPoint c = box.Centre();
      const double last_piece =
          HeadingModulusBound(regime, box.hi[kCertifyModulus], ArgumentBoundOver(box, l_max - l_max / 64, l_max));
      double sampled_dk = 0.0;
      for (int m = 0; m < 256; ++m) {  // the 16 corners of (rate, k, u0, s) first, then interior points
        double t[4];
        for (int i = 0; i < 4; ++i) t[i] = m < 16 ? ((m >> i) & 1) : uni(rng);
        CertifyPoint x;
        for (int i = 0; i < 4; ++i) x[i] = box.lo[i] + t[i] * (box.hi[i] - box.lo[i]);
        const double s = x[kCertifyLength];
        const HeadingDerivatives h =
            HeadingDerivativesAt(regime, x[kCertifyModulus], x[kCertifyRate] * s + x[kCertifyPhase]);
        const HeadingDerivatives hc =
            HeadingDerivativesAt(regime, c[kCertifyModulus], c[kCertifyRate] * s + c[kCertifyPhase]);
        ASSERT_LE(std::abs(h.dk), ends.dk * (1 + 1e-12)) << ToString(regime) << " trial " << trial;
        ASSERT_LE(std::min(std::abs(h.theta - hc.theta), 2.0), ends.deviation * (1 + 1e-12))
            << ToString(regime) << " trial " << trial;
        sampled_dk = std::max(sampled_dk, std::abs(h.dk));
      }
      worst_dk = std::max(worst_dk, sampled_dk / ends.dk);
      if (sampled_dk > last_piece) ++beyond_last_piece;
    }
    std::printf("%s: sampled |d theta/dk| / end bound up to %.3g; beyond the last piece's bound in %d of 100 boxes\n",
                ToString(regime).c_str(),
                worst_dk,
                beyond_last_piece);
    EXPECT_GE(beyond_last_piece, 40) << ToString(regime);
    EXPECT_GT(worst_dk, 0.2) << ToString(regime);  // the bound is not vacuous
  }
}

namespace {

// A random box of half-widths in [1e-4, scale] around a random point of the usual window.
CertifyBox RandomBox(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const CertifyPoint c = {-1.2 + 2.4 * uni(rng), 0.05 + 0.8 * uni(rng), 4 * uni(rng), 1.0 + 6.0 * uni(rng)};
  CertifyBox box;
  for (int i = 0; i < 4; ++i) {
    const double half = 1e-4 * std::pow(scale / 1e-4, uni(rng));
    box.lo[i] = c[i] - half;
    box.hi[i] = c[i] + half;
  }
  box.lo[kCertifyModulus] = std::max(box.lo[kCertifyModulus], 0.0);
  return box;
}

}  // namespace

// The enclosure never undershoots: at 8 random corners and 4 random points of random boxes (both
// regimes, half-widths 1e-4 .. 0.02), |J(x) - J(centre)| <= radius entrywise; the Jacobians are
// the tested ones (steps 0.02). Also prints how tight it is (radius / largest sampled deviation).
TEST(IsoparallelCertifyJacobian, EnclosureNeverUndershootsSampledJacobians) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (PendulumRegime regime : kBothRegimes) {
    const CertifyTarget target =
        MadeTarget(regime, regime == PendulumRegime::kRotating ? kMadeRotating : kMadeOscillating);
    int boxes = 0;
    std::vector<double> ratios;
    for (int trial = 0; trial < 100 && boxes < 12; ++trial) {
      const CertifyBox box = RandomBox(rng, 0.02);
      CertifyJacobian centre;
      Eigen::Matrix4d radius;
      if (!EvaluateCertifyJacobian(target, regime, box.Centre(), 0.02, &centre) ||
          !CertifyJacobianEnclosure(regime, box, centre, 1e-7, &radius))
        continue;
      ++boxes;
      double sampled = 0.0;
      for (int m = 0; m < 12; ++m) {  // 8 random corners, 4 random interior points
        CertifyPoint x;
        const int corner = static_cast<int>(16 * uni(rng));
        for (int i = 0; i < 4; ++i) {
          const double t = m < 8 ? ((corner >> i) & 1) : uni(rng);
          x[i] = box.lo[i] + t * (box.hi[i] - box.lo[i]);
        }
        CertifyJacobian j;
        if (!EvaluateCertifyJacobian(target, regime, x, 0.02, &j)) continue;
        const Eigen::Matrix4d dev = (j.jacobian - centre.jacobian).cwiseAbs();
        for (int r = 0; r < 4; ++r)
          for (int c = 0; c < 4; ++c)
            ASSERT_LE(dev(r, c), radius(r, c)) << ToString(regime) << " entry " << r << "," << c;
        sampled = std::max(sampled, (dev.array() / radius.array()).maxCoeff());
      }
      ratios.push_back(1.0 / std::max(sampled, 1e-300));
    }
    EXPECT_GE(boxes, 10) << ToString(regime);
    std::sort(ratios.begin(), ratios.end());
    std::printf("%s: %d boxes, radius / largest sampled deviation (entrywise worst): median %.3g, min %.3g\n",
                ToString(regime).c_str(),
                boxes,
                ratios[ratios.size() / 2],
                ratios.front());
  }
}

namespace {

// The first-order verdict of the box of half-width `half` (every axis) centred at `centre`.
FirstOrderVerdict VerdictAround(PendulumRegime regime,
                                const CertifyTarget& target,
                                const CertifyPoint& centre,
                                double half) {
  CertifyBox box;
  for (int i = 0; i < 4; ++i) {
    box.lo[i] = centre[i] - half;
    box.hi[i] = centre[i] + half;
  }
  CertifyJacobian j;
  Eigen::Matrix4d radius;
  if (!EvaluateCertifyJacobian(target, regime, box.Centre(), 0.02, &j) ||
      !CertifyJacobianEnclosure(regime, box, j, 1e-8, &radius))
    return FirstOrderVerdict::kNotRun;
  return FirstOrderTest(box, j, radius, 1e-8);
}

}  // namespace

// Krawczyk around the made oscillating solution (residual margin 1e-8): a box of half-width 2e-7
// whose centre is off the solution by 6e-8 per axis is proved to hold exactly one solution (the
// modulus column varies fast: sup |d2 F/dk2| ~ 1e5 here, so the contraction needs tiny boxes); a
// box of half-width 1e-6 centred 4e-6 away per axis (no solution inside) is excluded; a box
// around it spanning a whole phase period (the same path
// twice: two solutions) is never called unique at any width from 1e-4 to 0.5.
TEST(IsoparallelCertifyJacobian, KrawczykProvesUniquenessAndRefusesTwinsAndEmptyBoxes) {
  const PendulumRegime regime = PendulumRegime::kOscillating;
  const CertifyTarget target = MadeTarget(regime, kMadeOscillating);
  CertifyPoint off = kMadeOscillating;
  for (int i = 0; i < 4; ++i) off[i] += 6e-8;
  EXPECT_EQ(VerdictAround(regime, target, off, 2e-7), FirstOrderVerdict::kUnique);
  CertifyPoint away = kMadeOscillating;
  for (int i = 0; i < 4; ++i) away[i] += 4e-6;
  EXPECT_EQ(VerdictAround(regime, target, away, 1e-6), FirstOrderVerdict::kExcluded);
  // Phase period 4K(0.8) = 8.63: the box [u0 - 0.3, u0 + 8.93] holds u0 and u0 + 4K.
  const double period = 4.0 * 2.2572053268208538;
  for (double half : {1e-4, 1e-3, 1e-2, 0.1, 0.5}) {
    CertifyBox box;
    for (int i = 0; i < 4; ++i) {
      box.lo[i] = kMadeOscillating[i] - half;
      box.hi[i] = kMadeOscillating[i] + half;
    }
    box.lo[kCertifyPhase] = kMadeOscillating[kCertifyPhase] - 0.3;
    box.hi[kCertifyPhase] = kMadeOscillating[kCertifyPhase] + period + 0.3;
    CertifyJacobian j;
    Eigen::Matrix4d radius;
    if (!EvaluateCertifyJacobian(target, regime, box.Centre(), 0.02, &j) ||
        !CertifyJacobianEnclosure(regime, box, j, 1e-8, &radius))
      continue;
    EXPECT_NE(FirstOrderTest(box, j, radius, 1e-8), FirstOrderVerdict::kUnique) << half;
  }
}

// A small window (0.0009 wide around the made oscillating solution, off-centre) certified
// with NO known solution: the first-order tests exclude the rest and prove exactly one solution,
// the made one (to 1e-8); without the first-order tests the same window stays undecided next to it.
// The first-order window options (no known list) over [centre - below, centre + above] on each
// axis, the phase's upper end `extra_phase` further; the window's result printed.
CertifyWindowOptions WindowAround(const CertifyPoint& centre, double below, double above, double extra_phase) {
  CertifyWindowOptions o;
  o.regime = PendulumRegime::kOscillating;
  for (int i = 0; i < 4; ++i) o.window.lo[i] = centre[i] - below, o.window.hi[i] = centre[i] + above;
  o.window.hi[kCertifyPhase] += extra_phase;
  o.max_boxes = 200000;
  o.first_order = true;
  return o;
}

CertifyWindowResult CertifyAndPrint(const CertifyTarget& target, const CertifyWindowOptions& o) {
  const CertifyWindowResult r = CertifyWindow(target, {}, o);
  std::printf("%s\n", r.message.c_str());
  return r;
}

TEST(IsoparallelCertifyJacobian, SmallWindowIsCertifiedWithoutKnownSolutions) {
  const CertifyTarget target = MadeTarget(PendulumRegime::kOscillating, kMadeOscillating);
  CertifyWindowOptions o = WindowAround(kMadeOscillating, 0.0005, 0.0004, 0.0);
  const CertifyWindowResult r = CertifyAndPrint(target, o);
  ASSERT_EQ(r.status, CertifyStatus::kCertified) << r.message;
  ASSERT_EQ(r.found.size(), 1u);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(r.found[0][i], kMadeOscillating[i], 1e-8) << i;
  EXPECT_EQ(r.found_known[0], -1);
  o.first_order = false;
  o.max_boxes = 5000;
  EXPECT_NE(CertifyWindow(target, {}, o).status, CertifyStatus::kCertified);
}

// The first-order options are range-checked by name.
TEST(IsoparallelCertifyJacobian, FirstOrderOptionsAreValidatedByName) {
  CertifyWindowOptions o;
  o.window.lo = {0.0, 0.0, 0.0, 1.0};
  o.window.hi = {1.0, 0.5, 1.0, 2.0};
  EXPECT_EQ(o.Validate(), "");
  o.first_order_deviation = -1.0;
  EXPECT_NE(o.Validate().find("first_order_deviation"), std::string::npos);
  o.first_order_deviation = 0.5;
  o.first_order_min_deviation = 0.0;
  EXPECT_NE(o.Validate().find("first_order_min_deviation"), std::string::npos);
  o.first_order_min_deviation = 1e-9;
  o.first_order_margin = std::nan("");
  EXPECT_NE(o.Validate().find("first_order_margin"), std::string::npos);
}

namespace {

// The epsilon function carried along the quadrature nodes by the addition theorem against
// Boost's incomplete integral at every node (HeadingDerivativesAt), both regimes, random moduli,
// rates (negative ones too), phases and lengths up to 40 (several restarts of the carried sum).
TEST(IsoparallelCertifyJacobian, HeadingAlongNodesMatchesBoostAtEveryNode) {
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (PendulumRegime regime : kBothRegimes)
    for (int trial = 0; trial < 12; ++trial) {
      const double k = trial == 0 ? 0.0005 : 0.95 * unit(rng), rate = 4.0 * unit(rng) - 1.0;
      const double phase = 6.0 * unit(rng) - 3.0, length = 1.0 + 39.0 * unit(rng);
      const CertifyQuadrature quad = CertifyQuadratureAlong(length, 0.05);
      ASSERT_EQ(quad.nodes.size(), 4u * static_cast<size_t>(quad.steps));
      const std::vector<HeadingDerivatives> along = HeadingDerivativesAtNodes(regime, k, rate, phase, quad);
      ASSERT_EQ(along.size(), quad.nodes.size());
      const double kp = std::sqrt(1.0 - k * k);
      for (size_t i = 0; i < quad.nodes.size(); ++i) {
        const double v = rate * quad.nodes[i] + phase;
        const HeadingDerivatives d = HeadingDerivativesAt(regime, k, v);
        const double scale = (1.0 + std::abs(v)) / (kp * kp * kp);
        const double err =
            std::max({std::abs(along[i].theta - d.theta), std::abs(along[i].dv - d.dv), std::abs(along[i].dk - d.dk)}) /
            scale;
        worst = std::max(worst, err);
      }
    }
  std::printf("carried epsilon vs Boost: worst error / ((1 + |v|) / k'^3) = %.3g\n", worst);
  EXPECT_LT(worst, 1e-13);
}

// The quadrature integrates polynomials of degree 7 exactly on every step.
TEST(IsoparallelCertifyJacobian, QuadratureIsGaussLegendreOnEqualSteps) {
  const CertifyQuadrature quad = CertifyQuadratureAlong(1.3, 0.05);
  EXPECT_EQ(quad.steps, 26);
  double sum = 0.0;
  for (size_t i = 0; i < quad.nodes.size(); ++i) sum += quad.weights[i] * std::pow(quad.nodes[i], 7);
  EXPECT_NEAR(sum, std::pow(1.3, 8) / 8.0, 1e-13);
}

}  // namespace

namespace {

// The made oscillating solution refined by Newton to |F| < 1e-12 (the target is made with dopri5
// rollings, so the zero of the Magnus residual is ~1e-9 away from kMadeOscillating).
CertifyPoint RefinedOscillating(const CertifyTarget& target) {
  CertifyPoint x = kMadeOscillating;
  EXPECT_TRUE(NewtonRefineCertify(target, PendulumRegime::kOscillating, 0.05, 1e-12, 30, &x));
  return x;
}

// A solution exactly on a face shared by two boxes lies in the interior of neither, so Krawczyk
// cannot prove it in either; the box of the same half-widths around its Newton point holds it
// inside and is proved.
TEST(IsoparallelCertifyJacobian, SolutionOnAFaceIsProvedAroundItsNewtonPoint) {
  const PendulumRegime regime = PendulumRegime::kOscillating;
  const CertifyTarget target = MadeTarget(regime, kMadeOscillating);
  const CertifyPoint x = RefinedOscillating(target);
  for (int axis = 0; axis < 4; ++axis)
    for (int side = 0; side < 2; ++side) {
      CertifyBox box;
      for (int i = 0; i < 4; ++i) box.lo[i] = x[i] - 2e-7, box.hi[i] = x[i] + 2e-7;
      (side == 0 ? box.hi[axis] : box.lo[axis]) = x[axis];  // the solution on this face
      CertifyJacobian centre;
      ASSERT_TRUE(EvaluateCertifyJacobian(target, regime, box.Centre(), 0.05, &centre));
      Eigen::Matrix4d radius;
      ASSERT_TRUE(CertifyJacobianEnclosure(regime, box, centre, 1e-8, &radius));
      EXPECT_EQ(FirstOrderTest(box, centre, radius, 1e-8), FirstOrderVerdict::kUndecided) << axis << side;
      CertifyBox proved;
      CertifyPoint solution{};
      ASSERT_TRUE(ProveAroundNewtonPoint(target, regime, box, centre, 0.05, 1e-8, &proved, &solution)) << axis << side;
      for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(solution[i], x[i], 1e-10);
        EXPECT_NEAR(proved.HalfWidth(i), box.HalfWidth(i), 1e-15);
        EXPECT_LT(proved.lo[i], x[i]);
        EXPECT_GT(proved.hi[i], x[i]);
      }
    }
  // A box the Newton step leaves (no solution near) proves nothing.
  CertifyBox away;
  for (int i = 0; i < 4; ++i) away.lo[i] = x[i] + 3e-6, away.hi[i] = x[i] + 4e-6;
  CertifyJacobian centre;
  ASSERT_TRUE(EvaluateCertifyJacobian(target, regime, away.Centre(), 0.05, &centre));
  CertifyBox proved;
  CertifyPoint solution{};
  EXPECT_FALSE(ProveAroundNewtonPoint(target, regime, away, centre, 0.05, 1e-8, &proved, &solution));
}

// A phase window longer than the period 4K(k) holds the made path twice (phases one period
// apart): both copies are proved, and `found` lists the path once, in canonical form.
TEST(IsoparallelCertifyJacobian, FoundListsAPathOnceAcrossPhasePeriods) {
  const CertifyTarget target = MadeTarget(PendulumRegime::kOscillating, kMadeOscillating);
  const CertifyPoint x = RefinedOscillating(target);
  const double period = 4.0 * boost::math::ellint_1(x[kCertifyModulus]);
  const CertifyWindowResult r = CertifyAndPrint(target, WindowAround(x, 0.0002, 0.00015, period));
  ASSERT_EQ(r.status, CertifyStatus::kCertified) << r.message;
  ASSERT_EQ(r.found.size(), 1u);
  EXPECT_GE(r.found_repeated, 1);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(r.found[0][i], x[i], 1e-9) << i;
}

}  // namespace

namespace {

// The cheap check before the centre's Jacobian never refuses a box the enclosure accepts, and
// refuses the large boxes the enclosure refuses (random boxes of half-widths 1e-4..0.3 around
// points of both regimes; the chord and rotation from the zeroth-order residual).
TEST(IsoparallelCertifyJacobian, EnclosureAvailabilityAgreesWithTheEnclosure) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int accepted = 0, refused = 0;
  for (PendulumRegime regime : kBothRegimes) {
    const CertifyPoint made = regime == PendulumRegime::kRotating ? kMadeRotating : kMadeOscillating;
    const CertifyTarget target = MadeTarget(regime, made);
    for (int trial = 0; trial < 40; ++trial) {
      const double h = 1e-4 * std::pow(3000.0, unit(rng));
      CertifyBox box;
      for (int i = 0; i < 4; ++i) {
        const double c = made[i] + 4.0 * h * (unit(rng) - 0.5);
        box.lo[i] = c - h * (0.5 + unit(rng));
        box.hi[i] = c + h * (0.5 + unit(rng));
      }
      box.lo[kCertifyModulus] = std::max(box.lo[kCertifyModulus], 0.0);
      CertifyResidual zeroth;
      CertifyJacobian centre;
      if (!EvaluateCertifyResidual(target, regime, box.Centre(), 0.05, &zeroth) ||
          !EvaluateCertifyJacobian(target, regime, box.Centre(), 0.05, &centre))
        continue;  // an inadmissible centre (rotation residual near pi): no first-order tests at all
      Eigen::Matrix4d radius;
      const bool enclosure = CertifyJacobianEnclosure(regime, box, centre, 1e-8, &radius);
      const bool available = CertifyEnclosureAvailable(regime, box, zeroth.chord_norm, zeroth.rotation, 1e-8);
      EXPECT_TRUE(available || !enclosure) << trial;
      ++(enclosure ? accepted : refused);
    }
  }
  std::printf("enclosure available for %d boxes, refused for %d\n", accepted, refused);
  EXPECT_GT(accepted, 10);
  EXPECT_GT(refused, 10);
}

}  // namespace
