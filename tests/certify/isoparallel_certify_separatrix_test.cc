// The separatrix tail (src/certify/separatrix.h): the run heading spread against the
// closed-form heading of real elastica with k in [0.95, 0.99999], the run distance against its
// defining inequality, the deviation bound of boxes reaching k = 1 against dopri5 rollings, and
// the tail certificate against a target built from a tail path (it must not exclude it).
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "certify/separatrix.h"
#include "certify/support/dopri_rolling.h"
#include "certify/tails.h"
#include "plateball/elastica.h"
#include "plateball/so3.h"

using namespace plateball;
using namespace plateball::internal;

namespace {

const PendulumRegime kRegimes[] = {PendulumRegime::kOscillating, PendulumRegime::kRotating};
const double kModuli[] = {0.95, 0.99, 0.999, 0.9999, 0.99999};

// The heading angle theta(v) (v = 0 a loop centre): rotating 2 am, oscillating 2 asin(k sn).
double Heading(PendulumRegime regime, double k, double v) {
  double cn = 0.0, dn = 0.0;
  const double sn = boost::math::jacobi_elliptic(k, v, &cn, &dn);
  return regime == PendulumRegime::kRotating
             ? 2.0 * std::atan2(sn, cn) + 4.0 * M_PI * std::floor(v / (4.0 * boost::math::ellint_1(k)) + 0.5)
             : 2.0 * std::asin(k * sn);
}

TEST(SeparatrixTail, RunHeadingSpreadBoundsTheRunsOfRealElastica) {
  // On [w, 2K - w] the heading's range has half-width <= the spread (w <= K); 2 asin(sech w) is
  // also the exact distance of the separatrix to pi, so the rotating bound is nearly attained.
  for (PendulumRegime regime : kRegimes) {
    for (double k : kModuli) {
      const double kk = boost::math::ellint_1(k);
      for (double w = 0.25; w <= kk; w += 0.25) {
        double lo = 1e300, hi = -1e300;
        for (int i = 0; i <= 400; ++i) {
          const double v = w + (2.0 * kk - 2.0 * w) * i / 400.0;
          const double t = Heading(regime, k, v);
          lo = std::min(lo, t);
          hi = std::max(hi, t);
        }
        const double spread = SeparatrixRunHeadingSpread(regime, w);
        EXPECT_LE(0.5 * (hi - lo), spread * (1.0 + 1e-12) + 1e-14) << ToString(regime) << " k " << k << " w " << w;
        if (regime == PendulumRegime::kRotating && k >= 0.99999 && w <= 3.0) {
          EXPECT_GT(0.5 * (hi - lo), 0.9 * spread) << "loose rotating spread at w " << w;
        }
      }
    }
  }
}

CertifyTarget RotationTarget() {
  CertifyTarget t;
  t.target = ExpSO3(1.2 * Eigen::Vector3d(1.0, 2.0, 0.5).normalized());
  t.radius = std::sqrt(5.0);
  t.goal_angle = std::atan2(1.0, 2.0);
  return t;
}

TEST(SeparatrixTail, RunDistanceIsTheSmallestExcludedDistance) {
  const CertifyTarget t = RotationTarget();
  const double delta = StraightResidual(t) - 1e-7;
  ASSERT_GT(delta, 0.1);
  for (PendulumRegime regime : kRegimes) {
    for (double cap : {2.5, 6.0, 18.0}) {
      const double w = SeparatrixRunDistance(t, regime, cap, 1e-7);
      ASSERT_TRUE(std::isfinite(w));
      EXPECT_LT(StraightRunDeviationBound(SeparatrixRunHeadingSpread(regime, w), cap, t.radius), delta);
      EXPECT_GE(StraightRunDeviationBound(SeparatrixRunHeadingSpread(regime, 0.999 * w), cap, t.radius), delta);
    }
  }
  CertifyTarget straight = t;
  straight.target = ExpSO3(Eigen::Vector3d(-1.0, 2.0, 0.0));  // exp(hat(e3 x (2, 1))): the straight rolling
  EXPECT_FALSE(std::isfinite(SeparatrixRunDistance(straight, PendulumRegime::kRotating, 6.0, 1e-7)));
}

struct Rolled {
  Eigen::Matrix3d q;
  Eigen::Vector2d chord;
};

Rolled Roll(PendulumRegime regime, const CertifyPoint& x) {
  const Elastica e = CertifyElastica(regime, x);
  return {plateball::testing::DopriElasticaRolling(e, x[kCertifyLength], 1e-11), e.Position(x[kCertifyLength])};
}

TEST(SeparatrixTail, DeviationBoundNeverUndershootsDopriUpToTheSeparatrix) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst_ratio = 1e300;
  for (PendulumRegime regime : kRegimes) {
    for (int trial = 0; trial < 24; ++trial) {
      const double k_lo = kModuli[trial % 5], k_hi = trial % 3 == 0 ? 1.0 : k_lo + (1.0 - k_lo) * u(rng);
      const double rate = -1.0 + 2.0 * u(rng), phase = -3.0 + 6.0 * u(rng), length = 0.5 + 2.5 * u(rng);
      CertifyBox box;
      box.lo = {rate - 0.02, k_lo, phase - 0.05, length - 0.02};
      box.hi = {rate + 0.02, k_hi, phase + 0.05, length + 0.02};
      const double d = SeparatrixDeviationBound(regime, box);
      const Rolled c = Roll(regime, box.Centre());
      double largest = 0.0;
      for (int j = 0; j < 6; ++j) {
        CertifyPoint p;
        for (int i = 0; i < 4; ++i) p[i] = box.lo[i] + (box.hi[i] - box.lo[i]) * u(rng);
        p[kCertifyModulus] = std::min(p[kCertifyModulus], 1.0 - 1e-10);  // a real elastica (k < 1)
        if (j == 0) p[kCertifyModulus] = k_hi < 1.0 ? k_hi : 1.0 - 1e-10;
        const Rolled r = Roll(regime, p);
        const double angle = RotationAngle(r.q, c.q);
        largest = std::max({largest, angle, (r.chord - c.chord).norm()});
        EXPECT_LE(angle, d * (1.0 + 1e-9) + 1e-9) << ToString(regime) << " trial " << trial;
        EXPECT_LE((r.chord - c.chord).norm(), d * (1.0 + 1e-9) + 1e-9) << ToString(regime) << " trial " << trial;
      }
      if (largest > 1e-6) worst_ratio = std::min(worst_ratio, d / largest);
    }
  }
  EXPECT_GE(worst_ratio, 1.0);
}

TEST(SeparatrixTail, CertificateKeepsATailSolutionAndExcludesFarBoxes) {
  // A target made from a tail path (k = 0.99, inside the near-loop window): every box holding
  // the path must stay undecided, and the boxes the certificate excludes must hold none.
  for (PendulumRegime regime : kRegimes) {
    const CertifyPoint x = {0.3, 0.99, 0.4, 3.0};
    const Rolled r = Roll(regime, x);
    CertifyTarget t;
    t.target = r.q;
    t.radius = r.chord.norm();
    t.goal_angle = std::atan2(r.chord.y(), r.chord.x());
    for (double h : {0.2, 0.05, 0.01, 0.002}) {
      CertifyBox box;
      box.lo = {x[0] - h, x[1] - h, x[2] - h, x[3] - h};
      box.hi = {x[0] + h, 1.0, x[2] + h, x[3] + h};
      CertifyResidual centre;
      ASSERT_TRUE(EvaluateCertifyResidual(t, regime, box.Centre(), 0.05, &centre));
      EXPECT_EQ(TestBox(centre, SeparatrixDeviationBound(regime, box), 1e-7), BoxVerdict::kUndecided)
          << ToString(regime) << " h " << h;
    }
    SeparatrixTailOptions o;
    o.regime = regime;
    o.k_lo = 0.985;
    o.rate_max = 0.35;
    o.cap = 3.0 + 1e-3;
    o.length_lo = 3.0 - 1e-3;
    o.max_boxes = 20000;
    const SeparatrixTailResult result = CertifySeparatrixTail(t, o);
    EXPECT_NE(result.status, SeparatrixTailStatus::kExcluded) << ToString(regime);
    EXPECT_GT(result.excluded_by_chord + result.excluded_by_rotation, 0) << ToString(regime);
  }
}

TEST(SeparatrixTail, InvalidOptionsNameTheField) {
  SeparatrixTailOptions o;
  o.k_lo = 1.0;
  EXPECT_NE(o.Validate().find("k_lo: value 1"), std::string::npos);
  o = SeparatrixTailOptions();
  o.rate_max = std::nan("");
  EXPECT_NE(o.Validate().find("rate_max"), std::string::npos);
  o = SeparatrixTailOptions();
  o.length_lo = 2.0;
  EXPECT_NE(o.Validate().find("length_lo"), std::string::npos);
  EXPECT_EQ(CertifySeparatrixTail(CertifyTarget(), o).status, SeparatrixTailStatus::kInvalidInput);
}

}  // namespace
