// The certificate's bounds compared at a fixed number of periods (src/certify/periods.h):
// the heading's k-derivative at a fixed normalised phase against central differences (and the
// derivative at a fixed phase, whose secular part it leaves out, above it); the mapped points
// inside the mapped box with headings within h_k Mz at every arc length; the rolling and chord
// bounds never below sampled closed-form distances (and, as a planted error, the bound without its
// k share below them); never excluding a box that holds a solution; and the oscillating window
// resolving more volume with the same budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "certify/costate.h"
#include "certify/periods.h"
#include "certify/rolling.h"
#include "certify/window.h"
#include "elastica_closed_rolling.h"
#include "jacobi_elliptic.h"
#include "plateball/isoparallel.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"
#include "support/test_support.h"

using namespace plateball;
using namespace plateball::internal;

namespace {

const PendulumRegime kRegimes[] = {PendulumRegime::kOscillating, PendulumRegime::kRotating};

double Uniform(double lo, double hi, std::mt19937* rng) { return std::uniform_real_distribution<double>(lo, hi)(*rng); }

// The pendulum angle theta at phase v and modulus k (rate 1, s = 0).
double Theta(PendulumRegime regime, double k, double v) {
  return CertifyElastica(regime, {1.0, k, v, 1.0}).PendulumAngle(0.0);
}

// A box around a random centre: |rate| 0.2..3 (either sign when rotating), k up to 0.95, phase
// within half the window's period (|u0| <= 5.8), length 0.5..12; half-widths 1e-4..0.1 of each
// axis' scale (log-uniform). With `stalled`: the oscillating window's stalled region (rate within
// 0.1 of 1, L 2.5..3.4, k 0.5..0.95).
CertifyBox RandomBox(PendulumRegime regime, bool stalled, std::mt19937* rng) {
  const double sign = regime == PendulumRegime::kRotating && Uniform(0.0, 1.0, rng) < 0.5 ? -1.0 : 1.0;
  const CertifyPoint c = stalled ? CertifyPoint{Uniform(0.9, 1.1, rng),
                                                Uniform(0.5, 0.95, rng),
                                                Uniform(-5.8, 5.8, rng),
                                                Uniform(2.5, 3.4, rng)}
                                 : CertifyPoint{sign * Uniform(0.2, 3.0, rng),
                                                Uniform(0.05, 0.95, rng),
                                                Uniform(-5.8, 5.8, rng),
                                                Uniform(0.5, 12.0, rng)};
  const CertifyPoint scale = {std::abs(c[kCertifyRate]), 0.3, 1.0, 1.0};
  CertifyBox box;
  for (int i = 0; i < 4; ++i) {
    const double h = scale[i] * std::exp(Uniform(std::log(1e-4), std::log(0.1), rng));
    box.lo[i] = c[i] - h;
    box.hi[i] = c[i] + h;
  }
  box.lo[kCertifyModulus] = std::max(0.0, box.lo[kCertifyModulus]);
  box.hi[kCertifyModulus] = std::min(0.95, box.hi[kCertifyModulus]);
  box.lo[kCertifyLength] = std::max(0.1, box.lo[kCertifyLength]);
  return box;
}

// A point of the box: the first 16 at its corners, then uniform.
CertifyPoint PointOf(const CertifyBox& box, int j, std::mt19937* rng) {
  CertifyPoint x;
  for (int i = 0; i < 4; ++i)
    x[i] = j < 16 ? ((j >> i) & 1 ? box.hi[i] : box.lo[i]) : Uniform(box.lo[i], box.hi[i], rng);
  return x;
}

Eigen::Matrix3d Rolling(PendulumRegime regime, const CertifyPoint& x) {
  return ElasticaClosedRolling(CertifyElastica(regime, x)).Rolling(x[kCertifyLength]);
}

Eigen::Vector2d Chord(PendulumRegime regime, const CertifyPoint& x) {
  return CertifyElastica(regime, x).Position(x[kCertifyLength]);
}

// The geometric mean of the positive ratios added (1 for none).
struct RatioMean {
  double log_sum = 0.0;
  int count = 0;
  void Add(double ratio) { log_sum += std::log(ratio), ++count; }
  double Value() const { return count > 0 ? std::exp(log_sum / count) : 1.0; }
};

}  // namespace

// A modulus for the bound tests: the first half uniform in [0.01, 0.95], the second with lambda =
// -ln k' uniform from k = 0.95 to 0.9999 (k' 0.312 .. 0.0141: the middle of the separatrix tail).
double SampleModulus(int j, std::mt19937* rng) {
  if (j % 2 == 0) return Uniform(0.01, 0.95, rng);
  const double lambda_lo = -0.5 * std::log(1.0 - 0.95 * 0.95), lambda_hi = -0.5 * std::log(1.0 - 0.9999 * 0.9999);
  const double kp = std::exp(-Uniform(lambda_lo, lambda_hi, rng));
  return std::sqrt(1.0 - kp * kp);
}

// |d theta/dk| at a fixed normalised phase z = v / K(k) (central differences, step k'^2 1e-6) never
// exceeds Mz at 8,000 points per regime, k up to 0.9999, |z| up to 40 periods; the largest ratio is
// printed for k <= 0.95 and above. At a fixed phase v instead, the secular term v K'/K takes the
// derivative above Mz at large |v| (the bound is specific to z).
TEST(IsoparallelCertifyPeriods, HeadingModulusBoundAtFixedPeriodsHolds) {
  std::mt19937 rng(1301);
  for (PendulumRegime regime : kRegimes) {
    double worst_ratio[2] = {0.0, 0.0};
    int fixed_phase_above = 0;
    for (int j = 0; j < 8000; ++j) {
      const double k = SampleModulus(j, &rng), z = Uniform(-40.0, 40.0, &rng), h = 1e-6 * (1.0 - k) * (1.0 + k);
      const double bound = HeadingModulusBoundAtFixedPeriods(regime, k - h, k + h);
      const auto at_z = [&](double kk) { return Theta(regime, kk, z * CompleteEllipticK(kk)); };
      const double dz = std::abs(at_z(k + h) - at_z(k - h)) / (2.0 * h);
      ASSERT_LE(dz, bound * (1.0 + 1e-6)) << ToString(regime) << " k " << k << " z " << z;
      double& worst = worst_ratio[k > 0.95 ? 1 : 0];
      worst = std::max(worst, dz / bound);
      const double v = z * CompleteEllipticK(k);
      const double dv = std::abs(Theta(regime, k + h, v) - Theta(regime, k - h, v)) / (2.0 * h);
      fixed_phase_above += dv > bound ? 1 : 0;
    }
    std::printf(
        "%s: largest |d theta/dk| at fixed z / Mz %.3f (k <= 0.95), %.3f (0.95 < k <= 0.9999); at fixed v "
        "above Mz at %d of 8000 points\n",
        ToString(regime).c_str(),
        worst_ratio[0],
        worst_ratio[1],
        fixed_phase_above);
    EXPECT_GT(worst_ratio[0], 0.05) << ToString(regime);  // the bound is not vacuous
    EXPECT_GT(worst_ratio[1], 0.05) << ToString(regime);
    EXPECT_GT(fixed_phase_above, 200) << ToString(regime);
  }
}

// In lambda = -ln k' (dk = k'^2/k dlambda) the bound at fixed z is uniform up to the separatrix:
// Mz k'^2 / k <= 3.5 + 2 k'/k (rotating 1 + 2 E/k^2: 3.44 at k = 0.95, -> 3 at k = 1; oscillating
// adds 2 k'/k) from k' = 0.3 to k' = 1e-7; with |Z| <= k^2 K/2 alone it would grow like K.
TEST(IsoparallelCertifyPeriods, FixedPeriodsBoundIsUniformInLambda) {
  for (PendulumRegime regime : kRegimes)
    for (double kp = 0.3; kp > 1e-7; kp *= 0.5) {
      const double k = std::sqrt(1.0 - kp * kp);
      const double per_lambda = HeadingModulusBoundAtFixedPeriods(regime, k, k) * kp * kp / k;
      EXPECT_LE(per_lambda, 3.5 + 2.0 * kp / k) << ToString(regime) << " k' " << kp;
      EXPECT_GE(per_lambda, 2.0) << ToString(regime) << " k' " << kp;
    }
}

// Every point x of a box maps (rate rho, k_c, u0 rho, L; rho = K(k_c) / K(k)) into
// FixedPeriodsBox, and the two paths' headings stay within |k - k_c| Mz at every arc length.
TEST(IsoparallelCertifyPeriods, MappedPointsStayInTheBoxWithCloseHeadings) {
  std::mt19937 rng(1302);
  for (PendulumRegime regime : kRegimes)
    for (int b = 0; b < 300; ++b) {
      const CertifyBox box = RandomBox(regime, b % 3 == 0, &rng);
      const CertifyBox mapped = FixedPeriodsBox(box);
      const CertifyPoint c = box.Centre();
      ASSERT_EQ(mapped.lo[kCertifyModulus], c[kCertifyModulus]);
      ASSERT_EQ(mapped.hi[kCertifyModulus], c[kCertifyModulus]);
      const double mz = HeadingModulusBoundAtFixedPeriods(regime, box.lo[kCertifyModulus], box.hi[kCertifyModulus]);
      for (int j = 0; j < 20; ++j) {
        const CertifyPoint x = PointOf(box, j, &rng);
        const double rho = CompleteEllipticK(c[kCertifyModulus]) / CompleteEllipticK(x[kCertifyModulus]);
        const CertifyPoint y = {x[kCertifyRate] * rho, c[kCertifyModulus], x[kCertifyPhase] * rho, x[kCertifyLength]};
        for (int i = 0; i < 4; ++i) {
          ASSERT_GE(y[i], mapped.lo[i]) << ToString(regime) << " box " << b << " axis " << i;
          ASSERT_LE(y[i], mapped.hi[i]) << ToString(regime) << " box " << b << " axis " << i;
        }
        const Elastica ex = CertifyElastica(regime, x), ey = CertifyElastica(regime, y);
        const double limit = std::abs(x[kCertifyModulus] - c[kCertifyModulus]) * mz + 1e-12;
        for (double t : {0.0, 0.3, 0.7, 1.0}) {
          const double s = t * x[kCertifyLength];
          ASSERT_LE(std::abs(ex.PendulumAngle(s) - ey.PendulumAngle(s)), limit) << ToString(regime) << " box " << b;
        }
      }
    }
}

// The rolling and chord bounds never undershoot the largest closed-form distance to the centre
// over 32 points (16 corners) of 600 random boxes per regime (a third in the oscillating window's
// stalled region); without its k share (a planted error) the rolling bound falls below a sampled
// distance on some oscillating boxes (the rotating ones' k share is small: none there).
TEST(IsoparallelCertifyPeriods, NeverUndershootsSampledRotationAndChordDistances) {
  std::mt19937 rng(1303);
  int planted_caught = 0;
  for (PendulumRegime regime : kRegimes) {
    RatioMean ratios, main_ratios;
    int sharper = 0, caught = 0;
    for (int b = 0; b < 600; ++b) {
      const CertifyBox box = RandomBox(regime, b % 3 == 0, &rng);
      const CertifyPoint c = box.Centre();
      const double bound = FixedPeriodsRollingDeviationBound(regime, box, 0.0, true, true);
      const double chord_bound = FixedPeriodsChordDeviationBound(regime, box);
      const double planted = bound - FixedPeriodsModulusShare(regime, box);
      ASSERT_FALSE(std::isnan(bound) || std::isnan(chord_bound)) << ToString(regime) << " box " << b;
      const Eigen::Matrix3d qc = Rolling(regime, c);
      const Eigen::Vector2d xc = Chord(regime, c);
      double worst = 0.0, worst_chord = 0.0;
      for (int j = 0; j < 32; ++j) {
        const CertifyPoint x = PointOf(box, j, &rng);
        worst = std::max(worst, RotationAngle(Rolling(regime, x), qc));
        worst_chord = std::max(worst_chord, (Chord(regime, x) - xc).norm());
      }
      ASSERT_LE(worst, bound * (1.0 + 1e-9) + 1e-9) << ToString(regime) << " box " << b;
      ASSERT_LE(worst_chord, chord_bound * (1.0 + 1e-9) + 1e-9) << ToString(regime) << " box " << b;
      caught += worst > planted * (1.0 + 1e-9) + 1e-9 ? 1 : 0;
      const double d = RollingDeviationBound(regime, box);
      const double existing =
          std::min({d, ClosedRollingDeviationBound(regime, box, 0.0), ChartRollingDeviationBound(regime, box, 0.0)});
      if (worst > 1e-12 && std::isfinite(bound)) ratios.Add(bound / worst);
      if (worst > 1e-12 && std::isfinite(existing)) main_ratios.Add(existing / worst);
      sharper += bound < existing ? 1 : 0;
    }
    std::printf(
        "%s: bound / largest sampled distance geometric mean %.2f (min(D, R, Rt): %.2f); below min(D, R, Rt) "
        "on %d of 600 boxes; without the k share below a sample on %d\n",
        ToString(regime).c_str(),
        ratios.Value(),
        main_ratios.Value(),
        sharper,
        caught);
    EXPECT_GT(sharper, 60) << ToString(regime);
    planted_caught += caught;
  }
  EXPECT_GT(planted_caught, 0);
}

// Boxes of half-widths 1e-5..0.3 around the rotation problem's solutions (the solver's) and
// around made solutions at random points of random boxes: the chord and rotation tests with the
// fixed-periods bounds never exclude one, while boxes around the solutions with the target turned
// by 0.01 rad often are.
TEST(IsoparallelCertifyPeriods, NeverExcludesABoxHoldingASolution) {
  struct Case {
    PendulumRegime regime;
    CertifyPoint solution;
    CertifyTarget target;
  };
  const auto made = [](PendulumRegime regime, const CertifyPoint& x) {  // a target x solves
    const Eigen::Vector2d chord = Chord(regime, x);
    CertifyTarget t;
    t.target = Rolling(regime, x), t.radius = chord.norm(), t.goal_angle = std::atan2(chord.y(), chord.x());
    return Case{regime, x, t};
  };
  const IsoparallelSetup setup =
      IsoparallelSetupFor(ReadProblemFile(plateball::testing::SourcePath("problems/isoparallel_rotation.json")));
  const IsoparallelSummary solved = SolveIsoparallel(setup.problem, setup.options);
  ASSERT_TRUE(solved.IsSolutionUsable());
  std::vector<Case> cases;
  for (const IsoparallelSolution& s : solved.solutions)
    cases.push_back({s.parameters.regime, CanonicalSolution(s.parameters, s.length), CertifyTargetOf(setup.problem)});
  std::mt19937 rng(1304);
  for (int j = 0; j < 16; ++j) {
    const PendulumRegime regime = kRegimes[j % 2];
    cases.push_back(made(regime, PointOf(RandomBox(regime, j % 4 < 2, &rng), 16, &rng)));
  }
  const auto verdict = [](const CertifyTarget& target, PendulumRegime regime, const CertifyBox& box) {
    CertifyWindowOptions options;
    options.regime = regime;
    CertifyResidual centre;
    if (!EvaluateCertifyResidual(target, regime, box.Centre(), 0.05, &centre)) return BoxVerdict::kNotRun;
    const double d = RollingDeviationBound(regime, box);
    return FixedPeriodsTest(options, box, centre, d, std::min(d, ChordDeviationBound(regime, box)));
  };
  int boxes = 0, turned_excluded = 0;
  for (const auto& [regime, x, target] : cases)
    for (double h : {1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.3}) {
      const CertifyPoint scale = {std::max(0.05, std::abs(x[kCertifyRate])), 0.2, 1.0, 1.0};
      CertifyBox box;
      for (int i = 0; i < 4; ++i) {  // the solution off-centre by up to 0.9 half-widths
        const double half = h * scale[i], centre = x[i] + half * Uniform(-0.9, 0.9, &rng);
        box.lo[i] = centre - half;
        box.hi[i] = centre + half;
      }
      box.lo[kCertifyModulus] = std::max(0.0, box.lo[kCertifyModulus]);
      box.hi[kCertifyModulus] = std::min(0.99, box.hi[kCertifyModulus]);
      ASSERT_EQ(verdict(target, regime, box), BoxVerdict::kUndecided) << ToString(regime) << " h " << h;
      ++boxes;
      CertifyTarget turned = target;
      turned.target = ExpSO3(Eigen::Vector3d(0.0, 0.01, 0.0)) * target.target;
      turned_excluded += verdict(turned, regime, box) == BoxVerdict::kExcludedByRotation ? 1 : 0;
    }
  for (PendulumRegime regime : kRegimes)
    for (int b = 0; b < 300; ++b) {
      const CertifyBox box = RandomBox(regime, b % 3 == 0, &rng);
      const Case c = made(regime, PointOf(box, b % 32, &rng));  // corners and inner points
      ASSERT_EQ(verdict(c.target, regime, box), BoxVerdict::kUndecided) << ToString(regime) << " box " << b;
      ++boxes;
    }
  std::printf(
      "%d boxes holding a solution, none excluded; %d of %zu boxes around %zu solutions excluded by rotation "
      "for the turned target\n",
      boxes,
      turned_excluded,
      6 * cases.size(),
      cases.size());
  EXPECT_GE(turned_excluded, static_cast<int>(cases.size()));
}

// The first 100,000 boxes of the rotation problem's oscillating 1.0x window (first-order tests, no
// known solutions, phase [-P/2, P/2]): with the fixed-periods bounds (tests and split axis) the
// window resolves more volume with the same budget, and boxes are excluded only thanks to them.
TEST(IsoparallelCertifyPeriods, ResolvesMoreOfTheOscillatingWindow) {
  const Problem file = ReadProblemFile(plateball::testing::SourcePath("problems/isoparallel_rotation.json"));
  const CertifyTarget target = CertifyTargetOf(IsoparallelSetupFor(file).problem);
  CertifyWindowOptions options;
  options.regime = PendulumRegime::kOscillating;
  const double period = PhasePeriod(options.regime, 0.95);
  options.window.lo = {0.0, 0.0, -0.5 * period, target.radius};
  options.window.hi = {2.0, 0.95, 0.5 * period, 5.9909830797497303 * (1.0 + 1e-4)};
  options.first_order = true;
  options.max_boxes = 100000;
  options.stop_at_unaccounted = false;
  const CertifyWindowResult with = CertifyWindow(target, {}, options);
  options.fixed_periods = false;
  const CertifyWindowResult without = CertifyWindow(target, {}, options);
  std::printf("100,000 boxes: %ld excluded only with the fixed-periods bounds; resolved volume %.6f (%.6f without)\n",
              with.excluded_by_fixed_periods,
              with.resolved_volume,
              without.resolved_volume);
  EXPECT_GT(with.excluded_by_fixed_periods, 100);
  EXPECT_EQ(without.excluded_by_fixed_periods, 0);
  EXPECT_GT(with.resolved_volume, without.resolved_volume);
  EXPECT_EQ(with.unaccounted + without.unaccounted, 0);
}
