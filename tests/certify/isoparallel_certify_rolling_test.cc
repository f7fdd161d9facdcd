// The certificate's bound on the rolling's deviation from the closed-form rolling
// (src/certify/rolling.h): never below sampled rotation distances on random boxes of
// both regimes (k up to 0.95, |rate| 0.05..20, L up to 20, boxes across G = 1 included), the
// extreme sample checked by an independent Magnus rolling; the twist's per-axis bounds against
// central differences; boxes it decides that D leaves undecided; and never excluding a box that
// holds a known solution (the solver's, made ones).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include "certify/costate.h"
#include "certify/rolling.h"
#include "certify/support/random_certify_box.h"
#include "certify/window.h"
#include "elastica_closed_rolling.h"
#include "elastica_rolling.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_families.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"
#include "support/test_support.h"

using namespace plateball;
using namespace plateball::internal;

namespace {

const PendulumRegime kBothRegimes[] = {PendulumRegime::kOscillating, PendulumRegime::kRotating};

using plateball::testing::LogUniform;

// A random box: centre |rate| 0.05..20 (either sign when rotating), k up to 0.95, phase -6..6,
// length 0.5..20, half-widths 1e-4..0.3 of each axis' scale (log-uniform); with `across_unit`
// its rate range is widened to hold G = 1 (rate 1, or rate 1/k when rotating).
CertifyBox RandomRollingBox(PendulumRegime regime, bool across_unit, std::mt19937* rng) {
  const bool rotating = regime == PendulumRegime::kRotating;
  CertifyBox box =
      plateball::testing::RandomCertifyBox(regime, {0.05, 20.0, 0.1, 0.95, 0.5, 20.0, 2.0, 1e-4, 0.3}, rng);
  const double sign = box.Centre()[kCertifyRate] < 0.0 ? -1.0 : 1.0;
  box.lo[kCertifyModulus] = std::max(0.0, box.lo[kCertifyModulus]);
  box.hi[kCertifyModulus] = std::min(0.95, box.hi[kCertifyModulus]);
  box.lo[kCertifyLength] = std::max(0.1, box.lo[kCertifyLength]);
  if (across_unit) {  // G = 1 at |rate| = 1 (oscillating) or |rate| k = 1 (rotating)
    const double unit_rate = rotating ? 1.0 / box.Centre()[kCertifyModulus] : 1.0;
    box.lo[kCertifyRate] = sign * unit_rate * (1.0 - LogUniform(1e-6, 0.1, rng));
    box.hi[kCertifyRate] = sign * unit_rate * (1.0 + LogUniform(1e-6, 0.1, rng));
    if (sign < 0.0) std::swap(box.lo[kCertifyRate], box.hi[kCertifyRate]);
  } else if (sign > 0.0) {
    box.lo[kCertifyRate] = std::max(0.01, box.lo[kCertifyRate]);
  } else {
    box.hi[kCertifyRate] = std::min(-0.01, box.hi[kCertifyRate]);
  }
  return box;
}

CertifyPoint PointIn(const CertifyBox& box, std::mt19937* rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  CertifyPoint x;
  for (int i = 0; i < 4; ++i) {  // a third of the coordinates on a face
    const double r = unit(*rng);
    x[i] = r < 1.0 / 6 ? box.lo[i] : r < 1.0 / 3 ? box.hi[i] : box.lo[i] + (box.hi[i] - box.lo[i]) * unit(*rng);
  }
  return x;
}

Eigen::Matrix3d ClosedRolling(PendulumRegime regime, const CertifyPoint& x) {
  return ElasticaClosedRolling(CertifyElastica(regime, x)).Rolling(x[kCertifyLength]);
}

// The independent rolling: sixth-order Magnus steps (<= 0.002 long, >= 512 per period).
Eigen::Matrix3d MagnusRolling(PendulumRegime regime, const CertifyPoint& x) {
  const Elastica e = CertifyElastica(regime, x);  // the table keeps a reference: it must outlive it
  const ElasticaRollingTable table(e, x[kCertifyLength], 512, 0.002, 2000000);
  EXPECT_TRUE(table.Valid());
  return table.Rolling(x[kCertifyLength]);
}

// The largest dist(Q(x), Q(centre)) (closed form) over 8 points x of the box (PointIn), and
// the point where it is reached.
double LargestSampledDistance(PendulumRegime regime, const CertifyBox& box, std::mt19937* rng, CertifyPoint* worst_x) {
  const Eigen::Matrix3d qc = ClosedRolling(regime, box.Centre());
  double worst = -1.0;
  for (int j = 0; j < 8; ++j) {
    const CertifyPoint x = PointIn(box, rng);
    const double dist = RotationAngle(ClosedRolling(regime, x), qc);
    if (dist > worst) worst = dist, *worst_x = x;
  }
  return worst;
}

// |f(x + h e_i) - f(x - h e_i)| / (2h), h = step max(1, |x_i|).
double CentralDifference(const std::function<double(const CertifyPoint&)>& f,
                         const CertifyPoint& x,
                         int i,
                         double step) {
  const double h = step * std::max(1.0, std::abs(x[i]));
  CertifyPoint p = x, m = x;
  p[i] += h;
  m[i] -= h;
  return std::abs(f(p) - f(m)) / (2.0 * h);
}

// Whether the rotation test excludes the box with min(D, the closed-form bounds of both charts)
// (margin 1e-7).
BoxVerdict VerdictWithClosedForm(const CertifyTarget& target,
                                 PendulumRegime regime,
                                 const CertifyBox& box,
                                 bool closed_form) {
  const double d = RollingDeviationBound(regime, box);
  const double rolling =
      closed_form
          ? std::min({d, ClosedRollingDeviationBound(regime, box, 1e-7), ChartRollingDeviationBound(regime, box, 1e-7)})
          : d;
  CertifyResidual centre;
  if (!EvaluateCertifyResidual(target, regime, box.Centre(), 0.05, &centre)) {
    ADD_FAILURE() << "centre residual not available";
    return BoxVerdict::kExcludedByChord;
  }
  return TestBox(centre, rolling, std::min(d, ChordDeviationBound(regime, box)), 1e-7);
}

// A target whose solution is the path x (its rolling by the Magnus table).
CertifyTarget TargetSolvedBy(PendulumRegime regime, const CertifyPoint& x) {
  const Eigen::Vector2d chord = CertifyElastica(regime, x).Position(x[kCertifyLength]);
  CertifyTarget t;
  t.target = MagnusRolling(regime, x);
  t.radius = chord.norm();
  t.goal_angle = std::atan2(chord.y(), chord.x());
  return t;
}

// Psit = int_0^L phi ds of the theta/2 chart by composite 5-point Gauss-Legendre quadrature
// (pieces <= 0.1 long in w = rate s + u0; phi is smooth with |phi_w| bounded, so the error is far below 1e-12).
double ChartTwistByQuadrature(PendulumRegime regime, const CertifyPoint& x) {
  static const double kNode[5] = {
      0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
  static const double kWeight[5] = {
      0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891, 0.2369268850561891};
  const double len = x[kCertifyLength];
  const int pieces = std::max(1, static_cast<int>(std::ceil(len * std::max(1.0, std::abs(x[kCertifyRate])) / 0.1)));
  const double h = len / pieces;
  const Elastica path = CertifyElastica(regime, x);
  double sum = 0.0;
  for (int p = 0; p < pieces; ++p)
    for (int j = 0; j < 5; ++j) sum += 0.5 * h * kWeight[j] * ChartTwistRate(path, (p + 0.5) * h + 0.5 * h * kNode[j]);
  return sum;
}

// Q(0, L) from the theta/2 chart: Ft(L) Rz(Psit) Ft(0)^T.
Eigen::Matrix3d ChartRolling(PendulumRegime regime, const CertifyPoint& x) {
  const double twist = ChartTwistByQuadrature(regime, x);
  Eigen::Matrix3d rz = Eigen::Matrix3d::Identity();
  rz.topLeftCorner<2, 2>() << std::cos(twist), -std::sin(twist), std::sin(twist), std::cos(twist);
  const Elastica path = CertifyElastica(regime, x);
  return ChartFrame(path, x[kCertifyLength]).frame * rz * ChartFrame(path, 0.0).frame.transpose();
}

// The geometric mean of positive ratios (1 for none).
double GeometricMean(const std::vector<double>& v) {
  double log_sum = 0.0;
  for (double x : v) log_sum += std::log(x);
  return v.empty() ? 1.0 : std::exp(log_sum / static_cast<double>(v.size()));
}

}  // namespace

// dist(Q(x), Q(centre)) never exceeds the bound at 8 points of each of 1,200 random boxes per
// regime (a fifth of them across G = 1: there the bound is +infinity or valid), and at the
// farthest sample the distance by an independent Magnus rolling agrees and stays below it too.
TEST(IsoparallelCertifyRolling, BoundNeverUndershootsSampledRotationDistances) {
  std::mt19937 rng(1515);
  for (PendulumRegime regime : kBothRegimes) {
    std::vector<double> ratios;
    int finite = 0, sharper = 0, across_infinite = 0;
    const int boxes = 1200;
    for (int b = 0; b < boxes; ++b) {
      const bool across = b % 5 == 0;
      const CertifyBox box = RandomRollingBox(regime, across, &rng);
      const double bound = ClosedRollingDeviationBound(regime, box, 0.0);
      ASSERT_FALSE(std::isnan(bound)) << ToString(regime) << " box " << b;
      if (across && std::isinf(bound)) ++across_infinite;
      if (std::isinf(bound)) continue;
      ++finite;
      const CertifyPoint c = box.Centre();
      CertifyPoint worst_x{};
      const double worst = LargestSampledDistance(regime, box, &rng, &worst_x);
      ASSERT_LE(worst, bound * (1.0 + 1e-9) + 1e-9) << ToString(regime) << " box " << b;
      const double magnus = RotationAngle(MagnusRolling(regime, worst_x), MagnusRolling(regime, c));
      ASSERT_NEAR(magnus, worst, 1e-7) << ToString(regime) << " box " << b;
      ASSERT_LE(magnus, bound + 1e-7) << ToString(regime) << " box " << b;
      if (worst > 1e-12) ratios.push_back(bound / worst);
      if (bound < RollingDeviationBound(regime, box)) ++sharper;
    }
    std::printf(
        "%s: %d of %d boxes finite (%d of %d across G = 1 infinite); bound / largest sampled distance "
        "geometric mean %.2f; below D in %d\n",
        ToString(regime).c_str(),
        finite,
        boxes,
        across_infinite,
        boxes / 5,
        GeometricMean(ratios),
        sharper);
    EXPECT_GT(finite, boxes / 2) << ToString(regime);
    EXPECT_GT(sharper, finite / 10) << ToString(regime);
  }
}

// The twist's per-axis bounds never undershoot central differences of Psi = psi(L) - psi(0) at 2
// points of each of 1,000 random boxes per regime, nor the frames' move its sampled angles.
TEST(IsoparallelCertifyRolling, TwistAndFrameBoundsNeverUndershoot) {
  std::mt19937 rng(1516);
  for (PendulumRegime regime : kBothRegimes) {
    int tested = 0;
    for (int b = 0; b < 1000; ++b) {
      const CertifyBox box = RandomRollingBox(regime, false, &rng);
      const CertifyPoint d = TwistDerivativeBounds(regime, box);
      if (!std::isfinite(d[0])) continue;
      ++tested;
      const auto twist = [&](const CertifyPoint& x) {
        return ElasticaClosedRolling(CertifyElastica(regime, x)).Twist(x[kCertifyLength]);
      };
      for (int j = 0; j < 2; ++j) {
        const CertifyPoint x = PointIn(box, &rng);
        for (int i = 0; i < 4; ++i) {
          const double fd = CentralDifference(twist, x, i, 1e-6);
          ASSERT_LE(fd, d[i] * (1.0 + 1e-6) + 1e-4) << ToString(regime) << " box " << b << " axis " << i;
        }
        const CertifyPoint c = box.Centre();
        for (bool at_end : {false, true}) {
          const double s_x = at_end ? x[kCertifyLength] : 0.0, s_c = at_end ? c[kCertifyLength] : 0.0;
          const Eigen::Matrix3d fx = ElasticaClosedRolling(CertifyElastica(regime, x)).Frame(s_x);
          const Eigen::Vector3d vc = ElasticaCostate(CertifyElastica(regime, c), s_c);
          const Eigen::Matrix3d fc = ElasticaClosedRolling(CertifyElastica(regime, c)).Frame(s_c);
          const double bound =
              FrameDeviationAngle(CostateDeviationBound(regime, box, at_end), vc.norm(), vc.head<2>().norm());
          ASSERT_LE(RotationAngle(fx, fc), bound + 1e-9) << ToString(regime) << " box " << b;
        }
      }
    }
    EXPECT_GT(tested, 500) << ToString(regime);
  }
}

// The first 250,000 boxes of the rotation problem's rotating 1.0x window (rate up to 13.41, k up
// to 0.95, one phase period, L from |x1 - x0| to the shortest solution's 9.4492): with the
// closed-form bound the rotation test excludes boxes the test with D alone leaves undecided, the
// theta/2 chart's bound more, and the window resolves more volume with the same budget each time.
TEST(IsoparallelCertifyRolling, DecidesBoxesDLeavesUndecided) {
  const Problem file = ReadProblemFile(plateball::testing::SourcePath("problems/isoparallel_rotation.json"));
  const CertifyTarget target = CertifyTargetOf(IsoparallelSetupFor(file).problem);
  CertifyWindowOptions options;
  options.regime = PendulumRegime::kRotating;
  options.window.lo = {-13.41, 0.0, 0.0, target.radius};
  options.window.hi = {13.41, 0.95, PhasePeriod(PendulumRegime::kRotating, 0.95), 9.4492190883751181};
  options.max_boxes = 250000;
  options.stop_at_unaccounted = false;
  const CertifyWindowResult with = CertifyWindow(target, {}, options);
  options.chart_rolling = false;
  const CertifyWindowResult costate_chart = CertifyWindow(target, {}, options);
  options.closed_rolling = false;
  const CertifyWindowResult without = CertifyWindow(target, {}, options);
  std::printf(
      "250,000 boxes: %ld excluded by rotation only with the closed-form bound, %ld more only with the "
      "theta/2 chart's; resolved volume %.15f (%.15f without the theta/2 chart, %.15f with D alone)\n",
      with.excluded_by_closed_rolling,
      with.excluded_by_chart_rolling,
      with.resolved_volume,
      costate_chart.resolved_volume,
      without.resolved_volume);
  EXPECT_GT(with.excluded_by_closed_rolling, 50);
  EXPECT_GT(with.excluded_by_chart_rolling, 50);
  EXPECT_EQ(costate_chart.excluded_by_chart_rolling, 0);
  EXPECT_EQ(without.excluded_by_closed_rolling, 0);
  EXPECT_GT(costate_chart.resolved_volume, without.resolved_volume);
  EXPECT_GT(with.resolved_volume, costate_chart.resolved_volume);
}

// Boxes of half-widths 1e-5..0.3 around the rotation problem's solutions (the solver's) and
// around made solutions, and random boxes with a made solution at a random point of them (a third
// of its coordinates on a face): the rotation test with min(D, the closed-form bound) never
// excludes one, while boxes around the solutions with the target turned by 0.01 rad often are.
TEST(IsoparallelCertifyRolling, NeverExcludesABoxHoldingASolution) {
  struct Case {
    CertifyTarget target;
    PendulumRegime regime;
    CertifyPoint solution;
  };
  std::vector<Case> cases;
  {
    const IsoparallelSetup setup =
        IsoparallelSetupFor(ReadProblemFile(plateball::testing::SourcePath("problems/isoparallel_rotation.json")));
    const IsoparallelSummary solved = SolveIsoparallel(setup.problem, setup.options);
    ASSERT_TRUE(solved.IsSolutionUsable());
    for (const IsoparallelSolution& s : solved.solutions)
      cases.push_back({CertifyTargetOf(setup.problem), s.parameters.regime, CanonicalSolution(s.parameters, s.length)});
  }
  ASSERT_GE(cases.size(), 8u);
  std::mt19937 rng(1518);
  std::uniform_real_distribution<double> offset(-0.9, 0.9);
  for (PendulumRegime regime : kBothRegimes)
    for (int j = 0; j < 4; ++j) {
      const CertifyPoint x = PointIn(RandomRollingBox(regime, false, &rng), &rng);
      cases.push_back({TargetSolvedBy(regime, x), regime, x});
    }
  int boxes = 0, turned_excluded = 0;
  for (const auto& [target, regime, x] : cases) {
    for (double h : {1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.3}) {
      CertifyBox box;
      const CertifyPoint scale = {std::max(0.05, std::abs(x[kCertifyRate])), 0.2, 1.0, 1.0};
      for (int i = 0; i < 4; ++i) {
        const double o = offset(rng);
        box.lo[i] = x[i] - h * scale[i] * (1.0 + o);
        box.hi[i] = x[i] + h * scale[i] * (1.0 - o);
      }
      box.lo[kCertifyModulus] = std::max(0.0, box.lo[kCertifyModulus]);
      box.hi[kCertifyModulus] = std::min(0.99, box.hi[kCertifyModulus]);
      ASSERT_EQ(VerdictWithClosedForm(target, regime, box, true), BoxVerdict::kUndecided)
          << ToString(regime) << " h " << h << " L " << x[kCertifyLength];
      ++boxes;
      CertifyTarget turned = target;
      turned.target = ExpSO3(Eigen::Vector3d(0.0, 0.01, 0.0)) * target.target;
      turned_excluded += VerdictWithClosedForm(turned, regime, box, true) != BoxVerdict::kUndecided ? 1 : 0;
    }
  }
  for (PendulumRegime regime : kBothRegimes)
    for (int b = 0; b < 300; ++b) {
      const CertifyBox box = RandomRollingBox(regime, b % 5 == 0, &rng);
      const CertifyPoint x = PointIn(box, &rng);
      ASSERT_EQ(VerdictWithClosedForm(TargetSolvedBy(regime, x), regime, box, true), BoxVerdict::kUndecided)
          << ToString(regime) << " box " << b;
      ++boxes;
    }
  std::printf(
      "%d boxes holding a solution, none excluded; %d of %zu boxes around %zu solutions excluded for the "
      "turned target\n",
      boxes,
      turned_excluded,
      6 * cases.size(),
      cases.size());
  EXPECT_GE(turned_excluded, static_cast<int>(cases.size()));
}

// ---------------------------------------------------------------------------------------------
// The theta/2 chart (certify/rolling.h, ChartRollingDeviationBound): smooth and
// finite through G = 1.

// Q(0, L) = Ft(L) Rz(int phi) Ft(0)^T, the chart's frames and twist rate against the closed-form
// rolling (the costate chart and Legendre's Pi, an independent evaluation) at random points of both
// regimes and at G = 1 exactly, 1 +- 1e-12, 1e-8, 1e-4 (there the costate chart's frame turns by pi
// in a layer of width |1 - G| and its bounds are infinite).
TEST(IsoparallelCertifyRolling, ChartFrameAndTwistReproduceTheClosedForm) {
  std::mt19937 rng(1520);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  int points = 0;
  for (PendulumRegime regime : kBothRegimes) {
    const bool rotating = regime == PendulumRegime::kRotating;
    for (int j = 0; j < 60; ++j) {
      const double k = 0.05 + 0.9 * unit(rng);
      double rate = LogUniform(0.1, 5.0, &rng);
      if (j % 2 == 0) {  // G = 1 + offset: rate 1 (oscillating) or 1/k (rotating)
        const double offsets[] = {0.0, 1e-12, -1e-12, 1e-8, -1e-8, 1e-4, -1e-4};
        rate = (rotating ? 1.0 / k : 1.0) * std::sqrt(1.0 + offsets[(j / 2) % 7]);
      }
      if (rotating && unit(rng) < 0.5) rate = -rate;
      const CertifyPoint x = {rate, k, -6.0 + 12.0 * unit(rng), 0.2 + 8.0 * unit(rng)};
      const Elastica path = CertifyElastica(regime, x);
      const ChartFrameAt f0 = ChartFrame(path, 0.0), f1 = ChartFrame(path, x[kCertifyLength]);
      ASSERT_NEAR((f0.frame.transpose() * f0.frame - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
      ASSERT_GT(f0.projection, 0.0);
      ASSERT_GT(f1.projection, 0.0);
      const double error = (ChartRolling(regime, x) - ClosedRolling(regime, x)).cwiseAbs().maxCoeff();
      ASSERT_LT(error, 1e-10) << ToString(regime) << " point " << j << " rate " << rate << " k " << k;
      worst = std::max(worst, error);
      ++points;
    }
  }
  std::printf(
      "%d points: largest entry difference between the theta/2 chart and the closed form %.2e\n", points, worst);
}

// The chart's bound is never below the largest of 8 sampled dist(Q(x), Q(centre)) (closed form)
// on 1,200 random boxes per regime, half of them across G = 1, where it stays finite; the extreme
// sample is checked by an independent Magnus rolling.
TEST(IsoparallelCertifyRolling, ChartBoundNeverUndershootsSampledRotationDistancesAcrossUnitG) {
  std::mt19937 rng(1521);
  for (PendulumRegime regime : kBothRegimes) {
    std::vector<double> ratios, across_ratios, costate_ratios;
    int finite = 0, across_finite = 0, sharper = 0;
    const int boxes = 1200;
    for (int b = 0; b < boxes; ++b) {
      const bool across = b % 2 == 0;
      const CertifyBox box = RandomRollingBox(regime, across, &rng);
      const double bound = ChartRollingDeviationBound(regime, box, 0.0);
      ASSERT_FALSE(std::isnan(bound)) << ToString(regime) << " box " << b;
      if (std::isinf(bound)) continue;
      ++finite;
      across_finite += across ? 1 : 0;
      const CertifyPoint c = box.Centre();
      CertifyPoint worst_x{};
      const double worst = LargestSampledDistance(regime, box, &rng, &worst_x);
      ASSERT_LE(worst, bound * (1.0 + 1e-9) + 1e-9) << ToString(regime) << " box " << b;
      if (b % 4 == 0) {  // the Magnus table is slow at long lengths: a quarter of the boxes
        const double magnus = RotationAngle(MagnusRolling(regime, worst_x), MagnusRolling(regime, c));
        ASSERT_NEAR(magnus, worst, 1e-7) << ToString(regime) << " box " << b;
      }
      if (worst > 1e-12 && bound < M_PI) (across ? across_ratios : ratios).push_back(bound / worst);
      const double costate_chart = ClosedRollingDeviationBound(regime, box, 0.0);
      if (worst > 1e-12 && costate_chart < M_PI) costate_ratios.push_back(costate_chart / worst);
      if (bound < std::min(costate_chart, RollingDeviationBound(regime, box))) ++sharper;
    }
    std::printf(
        "%s: %d of %d boxes finite (%d of %d across G = 1); bound / largest sampled distance geometric "
        "mean %.2f (%zu boxes), across G = 1 %.2f (%zu), costate chart %.2f (%zu); below D and the costate "
        "chart's in %d\n",
        ToString(regime).c_str(),
        finite,
        boxes,
        across_finite,
        boxes / 2,
        GeometricMean(ratios),
        ratios.size(),
        GeometricMean(across_ratios),
        across_ratios.size(),
        GeometricMean(costate_ratios),
        costate_ratios.size(),
        sharper);
    EXPECT_EQ(across_finite, boxes / 2) << ToString(regime);
    EXPECT_GT(sharper, boxes / 10) << ToString(regime);
  }
}

// The chart twist's per-axis bounds never undershoot central differences of Psit (by quadrature),
// nor the chart frames' bound the sampled frame angles, on random boxes half across G = 1.
TEST(IsoparallelCertifyRolling, ChartTwistAndFrameBoundsNeverUndershoot) {
  std::mt19937 rng(1522);
  for (PendulumRegime regime : kBothRegimes) {
    int tested = 0;
    double tightest = INFINITY;
    for (int b = 0; b < 100; ++b) {
      const CertifyBox box = RandomRollingBox(regime, b % 2 == 0, &rng);
      const CertifyPoint d = ChartTwistDerivativeBounds(regime, box);
      ASSERT_TRUE(std::isfinite(d[0])) << ToString(regime) << " box " << b;
      ++tested;
      const auto chart_twist = [regime](const CertifyPoint& x) { return ChartTwistByQuadrature(regime, x); };
      const CertifyPoint c = box.Centre();
      for (int j = 0; j < 2; ++j) {
        const CertifyPoint x = PointIn(box, &rng);
        for (int i = 0; i < 4; ++i) {
          const double fd = CentralDifference(chart_twist, x, i, 1e-5);
          ASSERT_LE(fd, d[i] * (1.0 + 1e-6) + 1e-5)
              << ToString(regime) << " box " << b << " axis " << i << " rate " << x[0] << " k " << x[1];
          if (fd > 1e-3) tightest = std::min(tightest, d[i] / fd);
        }
        for (bool at_end : {false, true}) {
          const double s_x = at_end ? x[kCertifyLength] : 0.0, s_c = at_end ? c[kCertifyLength] : 0.0;
          const ChartFrameAt fx = ChartFrame(CertifyElastica(regime, x), s_x);
          const ChartFrameAt fc = ChartFrame(CertifyElastica(regime, c), s_c);
          const double bound = ChartFrameDeviationAngle(CostateDeviationBound(regime, box, at_end),
                                                        fc.costate_norm,
                                                        HalfHeadingDeviationBound(regime, box, at_end),
                                                        fc.projection);
          ASSERT_LE(RotationAngle(fx.frame, fc.frame), bound + 1e-9) << ToString(regime) << " box " << b;
          const double half = 0.5 * std::abs(CertifyElastica(regime, x).PendulumAngle(s_x) -
                                             CertifyElastica(regime, c).PendulumAngle(s_c));
          ASSERT_LE(half, HalfHeadingDeviationBound(regime, box, at_end) + 1e-9) << ToString(regime) << " box " << b;
        }
      }
    }
    std::printf("%s: %d boxes; smallest bound / central difference of the twist %.2f\n",
                ToString(regime).c_str(),
                tested,
                tightest);
  }
}
