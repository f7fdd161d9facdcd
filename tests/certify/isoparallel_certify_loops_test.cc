// The separatrix tail loop by loop (src/certify/loops.h): real tail elastica against
// their loop models, the model's core rolling against dopri5 on the separatrix and its closed-form
// chord, the run-length cap, the box bound against sampled model and real rollings, and the
// certificate against a target made from a tail path with two loops (it must not exclude it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "certify/loops.h"
#include "certify/support/dopri_rolling.h"
#include "certify/support/made_certify_target.h"
#include "certify/support/random_certify_box.h"
#include "certify/tails.h"
#include "elastica_closed_rolling.h"
#include "jacobi_elliptic.h"
#include "plateball/elastica.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"

using namespace plateball;
using namespace plateball::internal;
using plateball::testing::LogUniform;

namespace {

const PendulumRegime kRegimes[] = {PendulumRegime::kOscillating, PendulumRegime::kRotating};

double Angle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return LogSO3(a.transpose() * b).norm(); }

// The family's k_t per regime: k'_t = 1e-4 rotating, 1e-6 oscillating (its gap ~ k'^(2/3)).
double TailModulus(PendulumRegime regime) {
  const double kp = regime == PendulumRegime::kRotating ? 1e-4 : 1e-6;
  return std::sqrt(1.0 - kp * kp);
}

// A real tail elastica: k = 1 - delta, delta log-uniform down to 2e-16 (k' ~ 2e-8), |rate| in
// [0.5, 120] (either sign), phase uniform over one period of v; heading_w = pi/2 (model frame).
Elastica RandomTailElastica(PendulumRegime regime, std::mt19937* rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double k_t = TailModulus(regime);
  ElasticaParameters p;
  p.regime = regime;
  p.modulus = 1.0 - LogUniform(2e-16, 1.0 - k_t, rng);
  p.rate = LogUniform(0.5, 120.0, rng) * (unit(*rng) < 0.5 ? -1.0 : 1.0);
  p.phase = (unit(*rng) - 0.5) * 4.0 * CompleteEllipticK(p.modulus);
  p.heading_w = M_PI / 2;
  return Elastica(p);
}

double RealPathTolerance(PendulumRegime regime, double w2, double length) {
  return (LoopModelHeadingError(regime, TailModulus(regime), w2) +
          SeparatrixHeadingGapSup(PendulumRegime::kRotating, kLoopCoreModulus)) *
         length;
}

TEST(IsoparallelCertifyLoops, RealTailPathsStayWithinTheHeadingErrorOfTheirModel) {
  // Lemma (1): the model of a real path (LoopModelOf) rolls within eps L of it, chord too.
  std::mt19937 rng(15);
  for (const PendulumRegime regime : kRegimes) {
    const double w2 = LoopCoreHalfWidthFor(regime, TailModulus(regime));
    double worst = 0.0;
    for (int i = 0; i < 300; ++i) {
      const Elastica e = RandomTailElastica(regime, &rng);
      const double length = LogUniform(0.5, 18.0, &rng);
      const LoopModelPoint m = LoopModelOf(e, length, w2);
      const LoopModelRolling model = RollLoopModel(regime, m.sense, w2, m.x);
      const Eigen::Matrix3d real = ElasticaClosedRolling(e).Rolling(length);
      const double bound = RealPathTolerance(regime, w2, length);
      const double d = std::max(Angle(real, model.rolling), (e.Position(length) - model.chord).norm());
      EXPECT_LE(d, bound) << ToString(regime) << " " << e.parameters().modulus << " " << e.parameters().rate;
      worst = std::max(worst, d / bound);
    }
    std::printf("%s: W2 %.4g, eps %.3g, worst deviation / (eps L) %.3f\n",
                ToString(regime).c_str(),
                w2,
                LoopModelHeadingError(regime, TailModulus(regime), w2),
                worst);
  }
}

// The model's heading at s (mod 2 pi, run direction pi), written out from the header's definition.
double ModelHeading(PendulumRegime regime, int sense, double w2, const CertifyPoint& x, double s) {
  const double b = x[kLoopRate], w = w2 / b, period = x[kLoopRun] + 2.0 * w;
  const double j = std::round((s - x[kLoopPhase]) / period), c = x[kLoopPhase] + j * period;
  if (std::abs(s - c) > w) return M_PI;
  const int sigma = regime == PendulumRegime::kRotating || std::fmod(std::abs(j), 2.0) == 0.0 ? sense : -sense;
  return sigma * 2.0 * std::atan(std::sinh(b * (s - c)));
}

double AngleDistance(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * M_PI)); }

TEST(IsoparallelCertifyLoops, RealTailHeadingsStayWithinEpsOfTheModelHeading) {
  // Lemma (1) pointwise: |theta(a s + u0) - model heading| <= eps = G_t + 2 asin(sech W2) on a fine
  // grid, half the paths at k = k_t, with the automatic W2 (spread = G_t) and W2 = 6 (spread >> G_t).
  std::mt19937 rng(14);
  for (const PendulumRegime regime : kRegimes) {
    const double k_t = TailModulus(regime);
    for (const double w2 : {LoopCoreHalfWidthFor(regime, k_t), 6.0}) {
      const double eps = LoopModelHeadingError(regime, k_t, w2);
      double worst = 0.0;
      for (int i = 0; i < 120; ++i) {
        Elastica e = RandomTailElastica(regime, &rng);
        if (i % 2 == 0) {
          ElasticaParameters p = e.parameters();
          p.modulus = k_t;
          e = Elastica(p);
        }
        const double length = 6.0;
        const LoopModelPoint m = LoopModelOf(e, length, w2);
        // Every path's capped model point lies in the searched domain (run cap = L, the smallest).
        const LoopModelPoint capped = CapLoopRun(m, length, w2);
        const CertifyBox point{capped.x, capped.x};
        ASSERT_FALSE(LoopBoxOutsideDomain(w2, 2.0 * (CompleteEllipticK(k_t) - w2), length, point));
        for (int n = 0; n <= 3000; ++n) {
          const double s = length * n / 3000.0;
          const double d = AngleDistance(e.PendulumAngle(s), ModelHeading(regime, m.sense, w2, m.x, s));
          ASSERT_LE(d, eps) << ToString(regime) << " k " << e.parameters().modulus << " rate " << e.parameters().rate
                            << " s " << s;
          worst = std::max(worst, d / eps);
        }
      }
      std::printf("%s, W2 %.4g: worst heading deviation / eps %.3f\n", ToString(regime).c_str(), w2, worst);
    }
  }
}

TEST(IsoparallelCertifyLoops, RealTailRollingsAgreeWithDopri) {
  // The closed-form real rollings of the tests above against dopri5 (a few, k' down to ~3e-8).
  std::mt19937 rng(16);
  for (const PendulumRegime regime : kRegimes) {
    for (int i = 0; i < 4; ++i) {
      const Elastica e = RandomTailElastica(regime, &rng);
      const double length = LogUniform(0.5, 3.0, &rng);
      EXPECT_LE(
          Angle(ElasticaClosedRolling(e).Rolling(length), plateball::testing::DopriElasticaRolling(e, length, 1e-12)),
          1e-10);  // observed <= 5e-12 (k' 3e-8 .. 4e-6, rates up to 111)
    }
  }
}

TEST(IsoparallelCertifyLoops, CoreRollingAgreesWithDopriOnTheSeparatrixAndTheClosedFormChord) {
  // One core (a run longer than the path) at rates 0.5..30: dopri5 on the tangent of the heading
  // 2 gd(b (s - c)) and the closed-form chord x = -s + (2/b) tanh, y = -(2 sigma/b) sech (run direction pi).
  std::mt19937 rng(17);
  const double w2 = 9.0;
  for (int i = 0; i < 12; ++i) {
    const double b = LogUniform(0.5, 30.0, &rng), w = w2 / b;
    const double t0 = std::uniform_real_distribution<double>(-w, w)(rng);
    const double length = std::uniform_real_distribution<double>(0.2, 2.0)(rng) * w;
    const int sense = i % 2 == 0 ? 1 : -1;
    const LoopModelRolling m = RollLoopModel(PendulumRegime::kRotating, sense, w2, {b, 1e3, t0, length});
    const double s1 = std::max(0.0, t0 - w), s2 = std::min(length, t0 + w);  // the core part
    const auto heading = [&](double s) {
      if (s < s1 || s > s2) return M_PI;
      return sense * 2.0 * std::atan(std::sinh(b * (s - t0)));
    };
    IntegrationOptions o;
    o.absolute_tolerance = o.relative_tolerance = 1e-12;
    const auto tangent = [&](double s) { return Eigen::Vector2d(std::cos(heading(s)), std::sin(heading(s))); };
    Eigen::Matrix3d q = RollingReorientation(tangent, 0.0, s1, {}, o);
    q = RollingReorientation(tangent, s1, s2, {}, o) * q;
    q = RollingReorientation(tangent, s2, length, {}, o) * q;
    const double core_bound = SeparatrixHeadingGapSup(PendulumRegime::kRotating, kLoopCoreModulus) * (s2 - s1);
    EXPECT_LE(Angle(q, m.rolling), core_bound + 1e-9) << b << " " << t0 << " " << length;
    const auto x = [&](double s) {
      const double v = b * (s - t0);
      return Eigen::Vector2d(-s + 2.0 / b * std::tanh(v), -sense * 2.0 / b / std::cosh(v));
    };
    const Eigen::Vector2d chord = Eigen::Vector2d(-s1, 0.0) + (x(s2) - x(s1)) + Eigen::Vector2d(-(length - s2), 0.0);
    EXPECT_LE((chord - m.chord).norm(), core_bound + 1e-9) << b << " " << t0 << " " << length;
    EXPECT_LE(Angle(q, m.rolling), 1e-7);  // the actual core error is far below its bound
  }
}

TEST(IsoparallelCertifyLoops, RunsLongerThanThePathAreTheCappedRun) {
  // r >= L: at most one core meets [0, L]; the model at r equals the model at R = L with core 0
  // at the same place (or, when no core meets the path, at L + w).
  std::mt19937 rng(18);
  const double w2 = 9.0;
  for (const PendulumRegime regime : kRegimes) {
    for (int i = 0; i < 50; ++i) {
      const double b = LogUniform(0.5, 30.0, &rng), w = w2 / b, length = LogUniform(0.3, 6.0, &rng);
      const double r = length * LogUniform(1.0, 10.0, &rng);
      const double t0 = std::uniform_real_distribution<double>(-w, r + w)(rng);
      const int sense = i % 2 == 0 ? 1 : -1;
      const LoopModelRolling a = RollLoopModel(regime, sense, w2, {b, r, t0, length});
      const LoopModelPoint capped = CapLoopRun({sense, {b, r, t0, length}}, length, w2);
      ASSERT_EQ(capped.x[kLoopRun], length);
      const LoopModelRolling c = RollLoopModel(regime, sense, w2, capped.x);
      EXPECT_LE(Angle(a.rolling, c.rolling), 1e-12);
      EXPECT_LE((a.chord - c.chord).norm(), 1e-12);
    }
  }
}

// A random box of the loop window: centre rate in [0.5, 120], run in [0.02, 6], phase in
// [-w, run + w], L in [0.5, 18]; half-widths log-uniform fractions of each axis' scale.
CertifyBox RandomLoopBox(double w2, std::mt19937* rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double b = LogUniform(0.5, 120.0, rng), r = LogUniform(0.02, 6.0, rng), w = w2 / b;
  const CertifyPoint c = {b, r, -w + unit(*rng) * (r + 2.0 * w), 0.5 + 17.5 * unit(*rng)};
  const CertifyPoint scale = {b, r, r + 2.0 * w, 1.0};
  CertifyBox box;
  for (int i = 0; i < 4; ++i) {
    const double h = scale[i] * LogUniform(1e-5, 0.1, rng);
    box.lo[i] = c[i] - h;
    box.hi[i] = c[i] + h;
  }
  return box;
}

CertifyPoint RandomPointIn(const CertifyBox& box, std::mt19937* rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  CertifyPoint p;
  for (int i = 0; i < 4; ++i) {
    const double u = unit(*rng);  // a third of the coordinates at a face
    p[i] = u < 0.17 ? box.lo[i] : u > 0.83 ? box.hi[i] : box.lo[i] + unit(*rng) * (box.hi[i] - box.lo[i]);
  }
  return p;
}

TEST(IsoparallelCertifyLoops, DeviationBoundNeverUndershootsSampledModelRollings) {
  std::mt19937 rng(19);
  const double w2 = 9.0;
  std::vector<double> ratios;
  for (const PendulumRegime regime : kRegimes) {
    for (int i = 0; i < 300; ++i) {
      const CertifyBox box = RandomLoopBox(w2, &rng);
      const int sense = i % 2 == 0 ? 1 : -1;
      const double d = LoopModelDeviationBound(w2, box);
      const LoopModelRolling c = RollLoopModel(regime, sense, w2, box.Centre());
      double worst = 0.0;
      for (int k = 0; k < 8; ++k) {
        const LoopModelRolling p = RollLoopModel(regime, sense, w2, RandomPointIn(box, &rng));
        worst = std::max({worst, Angle(c.rolling, p.rolling), (c.chord - p.chord).norm()});
      }
      EXPECT_LE(worst, d) << ToString(regime) << " box " << i;
      if (d < 1.0 && worst > 0.0) ratios.push_back(d / worst);
    }
  }
  std::sort(ratios.begin(), ratios.end());
  std::printf("D / sampled deviation (D < 1): %zu boxes, best %.3g, median %.3g\n",
              ratios.size(),
              ratios.front(),
              ratios[ratios.size() / 2]);
}

TEST(IsoparallelCertifyLoops, BoxBoundCoversRealTailPaths) {
  // A real tail path's model point inside a random box: its real rolling is within D + eps L
  // (plus the core's gap) of the box centre's model rolling, chord too.
  std::mt19937 rng(20);
  for (const PendulumRegime regime : kRegimes) {
    const double w2 = LoopCoreHalfWidthFor(regime, TailModulus(regime));
    for (int i = 0; i < 150; ++i) {
      const Elastica e = RandomTailElastica(regime, &rng);
      const double length = LogUniform(0.5, 18.0, &rng);
      const LoopModelPoint m = LoopModelOf(e, length, w2);
      CertifyBox box;
      for (int a = 0; a < 4; ++a) {
        const double h = std::abs(m.x[a]) * LogUniform(1e-5, 0.05, &rng) + 1e-6;
        const double u = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        box.lo[a] = m.x[a] - 2.0 * h * u;
        box.hi[a] = box.lo[a] + 2.0 * h;
      }
      box.lo[kLoopRun] = std::max(box.lo[kLoopRun], 0.0);
      const double d = LoopModelDeviationBound(w2, box) + RealPathTolerance(regime, w2, box.hi[kLoopLength]);
      const LoopModelRolling c = RollLoopModel(regime, m.sense, w2, box.Centre());
      const double actual =
          std::max(Angle(ElasticaClosedRolling(e).Rolling(length), c.rolling), (e.Position(length) - c.chord).norm());
      EXPECT_LE(actual, d) << ToString(regime) << " path " << i;
    }
  }
}

TEST(IsoparallelCertifyLoops, SlowPathsWithinOneCoreStayWithinTheLocalGap) {
  // A path that stays within V <= min(W2, K(k_t)) of one loop centre (a slow path: b L <= 2 V):
  // pointwise its heading is within min(gap's growing side at V, G_t) of the model's core, and
  // its rolling within D + LoopHeadingError::ForBox L of any box's centre model; at the coverage's
  // k'_t = 1e-2, half the paths at k_t itself (the largest gap), the rest up to k' ~ 2e-8.
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double kp = 1e-2, k_t = std::sqrt((1.0 - kp) * (1.0 + kp));
  for (const PendulumRegime regime : kRegimes) {
    const double w2 =
        regime == PendulumRegime::kOscillating ? CompleteEllipticK(k_t) : LoopCoreHalfWidthFor(regime, k_t);
    const LoopHeadingError heading(regime, k_t, w2);
    const double core_gap = SeparatrixHeadingGapSup(PendulumRegime::kRotating, kLoopCoreModulus);
    double worst_point = 0.0, worst_rolling = 0.0, largest_gain = 0.0;
    for (int i = 0; i < 200; ++i) {
      ElasticaParameters p;
      p.regime = regime;
      p.modulus = i % 2 == 0 ? k_t : 1.0 - LogUniform(2e-16, 1.0 - k_t, &rng);
      const double b = LogUniform(0.5, 5.0, &rng), v = (0.2 + 0.8 * unit(rng)) * std::min(w2, CompleteEllipticK(k_t));
      const double length = std::min(LogUniform(0.3, 2.0 * v / b, &rng), 2.0 * v / b);
      const double t0 = length - v / b + (2.0 * v / b - length) * unit(rng);  // max(|t0|, |L - t0|) <= v / b
      p.rate = unit(rng) < 0.5 ? -b : b;
      p.phase = -p.rate * t0;  // a loop centre (v = 0) at s = t0
      p.heading_w = M_PI / 2;
      const Elastica e(p);
      const LoopModelPoint m = LoopModelOf(e, length, w2);
      ASSERT_NEAR(m.x[kLoopPhase], t0, 1e-9 * (1.0 + std::abs(t0)));
      const double point_error = heading.ForBox(CertifyBox{m.x, m.x});
      ASSERT_LT(point_error, heading.Family()) << ToString(regime) << " path " << i;
      largest_gain = std::max(largest_gain, heading.Family() / point_error);
      for (int n = 0; n <= 2000; ++n) {
        const double s = length * n / 2000.0;
        const double d = AngleDistance(e.PendulumAngle(s), ModelHeading(regime, m.sense, w2, m.x, s));
        ASSERT_LE(d, point_error - core_gap + 1e-12) << ToString(regime) << " k " << p.modulus << " s " << s;
        if (i % 2 == 0) worst_point = std::max(worst_point, d / (point_error - core_gap));
      }
      CertifyBox box;
      for (int a = 0; a < 4; ++a) {
        const double h = std::abs(m.x[a]) * LogUniform(1e-6, 1e-2, &rng) + 1e-9;
        box.lo[a] = m.x[a] - 2.0 * h * unit(rng);
        box.hi[a] = box.lo[a] + 2.0 * h;
      }
      const LoopModelRolling c = RollLoopModel(regime, m.sense, w2, box.Centre());
      const double actual =
          std::max(Angle(ElasticaClosedRolling(e).Rolling(length), c.rolling), (e.Position(length) - c.chord).norm());
      const double d = LoopModelDeviationBound(w2, box) + heading.ForBox(box) * box.hi[kLoopLength];
      EXPECT_LE(actual, d) << ToString(regime) << " path " << i;
      worst_rolling = std::max(worst_rolling, actual / d);
    }
    // The local gap is nearly reached at k_t (the bound is not loose enough to hide an error).
    EXPECT_GT(worst_point, 0.3) << ToString(regime);
    std::printf(
        "%s: heading deviation / local gap at k_t, worst %.3f; rolling deviation / bound, worst %.3f; "
        "family eps / local eps up to %.3g\n",
        ToString(regime).c_str(),
        worst_point,
        worst_rolling,
        largest_gain);
  }
}

// Boxes around the model point of a made tail solution (the target built from the real path x
// by dopri5) with two cores on the path: never excluded by TestBox with D + eps L.
void ExpectNestedBoxesKept(PendulumRegime regime, const CertifyPoint& x, double k_t, std::mt19937* rng) {
  const CertifyTarget target = plateball::testing::MadeCertifyTarget(regime, x);
  const double w2 = LoopCoreHalfWidthFor(regime, k_t);
  const LoopModelPoint m = LoopModelOf(CertifyElastica(regime, x), x[kCertifyLength], w2);
  ASSERT_LT(m.x[kLoopRun] + 2.0 * w2 / m.x[kLoopRate], x[kCertifyLength]);  // two cores meet the path
  const double eps =
      LoopModelHeadingError(regime, k_t, w2) + SeparatrixHeadingGapSup(PendulumRegime::kRotating, kLoopCoreModulus);
  for (int i = 0; i < 40; ++i) {
    CertifyBox box;
    for (int a = 0; a < 4; ++a) {
      const double h = LogUniform(1e-6, 0.05, rng), u = std::uniform_real_distribution<double>(0.0, 1.0)(*rng);
      box.lo[a] = m.x[a] - 2.0 * h * u;
      box.hi[a] = box.lo[a] + 2.0 * h;
    }
    CertifyResidual centre;
    ASSERT_TRUE(EvaluateLoopModelResidual(target, regime, m.sense, w2, box.Centre(), &centre));
    const double d = LoopModelDeviationBound(w2, box) + eps * box.hi[kLoopLength];
    EXPECT_EQ(TestBox(centre, d, 1e-7), BoxVerdict::kUndecided) << ToString(regime) << " box " << i;
  }
}

TEST(IsoparallelCertifyLoops, MadeTailSolutionWithTwoLoopsIsNeverExcluded) {
  // Paths with two loops on [0, 7.5]: at k' = 1e-3 = k'_t (K = 8.3), |rate| 4 (P = 4.1), where
  // the model's own distance to the path matters (without the eps L term boxes are excluded),
  // oscillating with a negative rate (mirrored cores) and rotating; and rotating at k' ~ 1.4e-6
  // (K ~ 14.8), rate 6 (P = 4.9), the target of the certificate run below.
  std::mt19937 rng(21);
  const double k3 = std::sqrt(1.0 - 9e-4);
  ExpectNestedBoxesKept(PendulumRegime::kOscillating, {-2.0, k3, 1.0, 7.5}, k3, &rng);
  ExpectNestedBoxesKept(PendulumRegime::kRotating, {2.0, k3, -3.0, 7.5}, k3, &rng);
  const CertifyPoint x = {6.0, 1.0 - 1e-12, -3.0, 7.5};
  const PendulumRegime regime = PendulumRegime::kRotating;
  const double k_t = 1.0 - 1e-9;
  ExpectNestedBoxesKept(regime, x, k_t, &rng);
  const CertifyTarget target = plateball::testing::MadeCertifyTarget(regime, x);
  // The certificate over a small window around it: not excluded, while it excludes boxes.
  LoopFamilyOptions o;
  o.regime = regime;
  o.k_t = k_t;
  o.rate_lo = 5.99;
  o.rate_max = 6.01;
  o.length_lo = 7.49;
  o.cap = 7.5;
  o.max_boxes = 20000;
  o.accept_deviation = 2e-3;
  const LoopFamilyResult r = CertifyLoopFamily(target, o);
  EXPECT_NE(r.status, LoopFamilyStatus::kExcluded) << ToString(r.status);
  std::printf("made target: %s, %ld boxes, %ld undecided\n", ToString(r.status).c_str(), r.boxes, r.undecided);
  EXPECT_GT(r.excluded_by_chord + r.excluded_by_rotation, 0);
}

TEST(IsoparallelCertifyLoops, ValidationNamesTheFieldAndValue) {
  LoopFamilyOptions o;
  o.k_t = 1.0;
  EXPECT_NE(o.Validate().find("k_t"), std::string::npos);
  o = LoopFamilyOptions();
  o.rate_max = 0.25;
  EXPECT_NE(o.Validate().find("rate_max"), std::string::npos);
  EXPECT_NE(o.Validate().find("0.25"), std::string::npos);
  o = LoopFamilyOptions();
  o.core_half_width = 1e3;
  EXPECT_NE(o.Validate().find("core_half_width"), std::string::npos);
  EXPECT_EQ(CertifyLoopFamily(CertifyTarget(), o).status, LoopFamilyStatus::kInvalidInput);
  EXPECT_EQ(ToString(LoopFamilyStatus::kExcluded), "excluded");
  EXPECT_EQ(LoopFamilyOptions().Validate(), "");
}

}  // namespace
