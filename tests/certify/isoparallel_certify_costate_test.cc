// The closed-form chord bound and the costate test of the certificate (src/certify/costate.h):
// the bounds against sampled maxima and central differences on random boxes (both regimes, k up
// to 0.95, rates 0.05..20), the costate's closed form and its transport by the rolling, the
// costate angle zero at known solutions and never excluding a box that holds one, and boxes
// decided by the new tests that the old ones leave undecided.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "certify/costate.h"
#include "certify/support/dopri_rolling.h"
#include "certify/support/made_certify_target.h"
#include "elastica_rolling.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_families.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "support/test_support.h"

using namespace plateball;
using namespace plateball::internal;

namespace {

const PendulumRegime kRegimes[] = {PendulumRegime::kOscillating, PendulumRegime::kRotating};

// A random box: centre rate 0.05..20 (either sign when rotating), k up to 0.95, phase -6..6,
// length 0.5..8; half-widths 1e-4..0.3 relative (log-uniform), inside k in [0, 0.95] and
// L > 0.1, rate of one sign.
CertifyBox RandomBox(PendulumRegime regime, std::mt19937* rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double rate = std::exp(std::log(0.05) + unit(*rng) * std::log(400.0)) *
                      (regime == PendulumRegime::kRotating && unit(*rng) < 0.5 ? -1.0 : 1.0);
  const CertifyPoint c = {rate, 0.95 * unit(*rng), -6.0 + 12.0 * unit(*rng), 0.5 + 7.5 * unit(*rng)};
  CertifyBox box;
  for (int i = 0; i < 4; ++i) {
    const double scale = i == kCertifyRate      ? std::abs(rate)
                         : i == kCertifyModulus ? 0.3
                         : i == kCertifyPhase   ? 1.0
                                                : 2.0;
    const double h = scale * std::exp(std::log(1e-4) + unit(*rng) * std::log(3e3));
    box.lo[i] = c[i] - h;
    box.hi[i] = c[i] + h;
  }
  box.lo[kCertifyModulus] = std::max(0.0, box.lo[kCertifyModulus]);
  box.hi[kCertifyModulus] = std::min(0.95, box.hi[kCertifyModulus]);
  box.lo[kCertifyLength] = std::max(0.1, box.lo[kCertifyLength]);
  if (rate > 0.0) box.lo[kCertifyRate] = std::max(0.01, box.lo[kCertifyRate]);
  if (rate < 0.0) box.hi[kCertifyRate] = std::min(-0.01, box.hi[kCertifyRate]);
  return box;
}

CertifyPoint RandomPointIn(const CertifyBox& box, std::mt19937* rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  CertifyPoint x;
  for (int i = 0; i < 4; ++i) {
    const double r = unit(*rng);  // a third of the coordinates on a face
    x[i] = r < 1.0 / 6 ? box.lo[i] : r < 1.0 / 3 ? box.hi[i] : box.lo[i] + (box.hi[i] - box.lo[i]) * unit(*rng);
  }
  return x;
}

Eigen::Vector2d Chord(PendulumRegime regime, const CertifyPoint& x) {
  return CertifyElastica(regime, x).Position(x[kCertifyLength]);
}

Eigen::Vector3d CostateAt(PendulumRegime regime, const CertifyPoint& x, bool at_end) {
  return ElasticaCostate(CertifyElastica(regime, x), at_end ? x[kCertifyLength] : 0.0);
}

// Central differences (step h relative to the box's scale) of f along each axis at x.
template <class F>
CertifyPoint CentralDifferenceNorms(const CertifyPoint& x, F&& f) {
  CertifyPoint d;
  for (int i = 0; i < 4; ++i) {
    const double h = 1e-6 * std::max(1.0, std::abs(x[i]));
    CertifyPoint a = x, b = x;
    a[i] += h;
    b[i] -= h;
    d[i] = (f(a) - f(b)).norm() / (2.0 * h);
  }
  return d;
}

Eigen::Matrix3d Dopri(const Elastica& e, double length) {
  return plateball::testing::DopriElasticaRolling(e, length, 1e-12);
}

CertifyBox BoxAround(const CertifyPoint& x, const CertifyPoint& offset, double h) {
  CertifyBox box;
  const CertifyPoint scale = {std::max(0.05, std::abs(x[kCertifyRate])), 0.2, 1.0, 1.0};
  for (int i = 0; i < 4; ++i) {
    box.lo[i] = x[i] - h * scale[i] * (1.0 + offset[i]);
    box.hi[i] = x[i] + h * scale[i] * (1.0 - offset[i]);
  }
  box.lo[kCertifyModulus] = std::max(0.0, box.lo[kCertifyModulus]);
  box.hi[kCertifyModulus] = std::min(0.99, box.hi[kCertifyModulus]);  // holds the k = 0.961 solution
  return box;
}

// Whether the costate test or TestBox with the split bounds (margin 1e-7) excludes the box.
bool SomeTestExcludes(const CertifyTarget& target, PendulumRegime regime, const CertifyBox& box) {
  const double d = RollingDeviationBound(regime, box);
  const double dc = std::min(d, ChordDeviationBound(regime, box));
  CertifyResidual centre;
  if (!EvaluateCertifyResidual(target, regime, box.Centre(), 0.05, &centre)) {
    ADD_FAILURE() << "centre residual not available";
    return true;
  }
  return CostateExcludes(target, regime, box, dc, 1e-7) || TestBox(centre, d, dc, 1e-7) != BoxVerdict::kUndecided;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

// |c(x) - c(centre)| never exceeds ChordDeviationBound at 8 points of each of 1,500 random boxes
// per regime, and the per-axis bounds never undershoot central differences at 2 points per box.
// The bound is compared with the rolling deviation bound D of certify/vocabulary.h.
TEST(IsoparallelCertifyCostate, ChordBoundsNeverUndershootSampledMaxima) {
  std::mt19937 rng(15);
  for (PendulumRegime regime : kRegimes) {
    std::vector<double> ratios;
    int sharper = 0, boxes = 1500;
    for (int b = 0; b < boxes; ++b) {
      const CertifyBox box = RandomBox(regime, &rng);
      const double bound = ChordDeviationBound(regime, box);
      const CertifyPoint d = ChordDerivativeBounds(regime, box);
      const Eigen::Vector2d centre = Chord(regime, box.Centre());
      double worst = 0.0;
      for (int j = 0; j < 8; ++j) worst = std::max(worst, (Chord(regime, RandomPointIn(box, &rng)) - centre).norm());
      ASSERT_LE(worst, bound * (1.0 + 1e-9) + 1e-12) << ToString(regime) << " box " << b;
      for (int j = 0; j < 2; ++j) {
        const CertifyPoint fd =
            CentralDifferenceNorms(RandomPointIn(box, &rng), [&](const CertifyPoint& x) { return Chord(regime, x); });
        for (int i = 0; i < 4; ++i) ASSERT_LE(fd[i], d[i] * (1.0 + 1e-6) + 1e-6) << ToString(regime) << " axis " << i;
      }
      if (worst > 1e-12) ratios.push_back(bound / worst);
      if (bound < RollingDeviationBound(regime, box)) ++sharper;
    }
    std::printf("%s: chord bound / largest sampled deviation median %.2f; below D in %d of %d boxes\n",
                ToString(regime).c_str(),
                Median(ratios),
                sharper,
                boxes);
    EXPECT_GT(sharper, boxes / 4) << ToString(regime);  // the new bound is the sharper one often
  }
}

// The costate's end values never move further than the derivative bounds allow, and its per-axis
// bounds never undershoot central differences, at both ends, on 1,500 random boxes per regime.
TEST(IsoparallelCertifyCostate, CostateBoundsNeverUndershootSampledMaxima) {
  std::mt19937 rng(16);
  for (PendulumRegime regime : kRegimes) {
    std::vector<double> ratios;
    for (int b = 0; b < 1500; ++b) {
      const CertifyBox box = RandomBox(regime, &rng);
      for (bool at_end : {false, true}) {
        const CertifyPoint d = CostateDerivativeBounds(regime, box, at_end);
        double bound = 0.0;
        for (int i = 0; i < 4; ++i) bound += box.HalfWidth(i) * d[i];
        const Eigen::Vector3d centre = CostateAt(regime, box.Centre(), at_end);
        double worst = 0.0;
        for (int j = 0; j < 6; ++j)
          worst = std::max(worst, (CostateAt(regime, RandomPointIn(box, &rng), at_end) - centre).norm());
        ASSERT_LE(worst, bound * (1.0 + 1e-9) + 1e-12) << ToString(regime) << " box " << b << " end " << at_end;
        const CertifyPoint fd = CentralDifferenceNorms(
            RandomPointIn(box, &rng), [&](const CertifyPoint& x) { return CostateAt(regime, x, at_end); });
        for (int i = 0; i < 4; ++i) ASSERT_LE(fd[i], d[i] * (1.0 + 1e-6) + 1e-6) << ToString(regime) << " axis " << i;
        if (worst > 1e-12) ratios.push_back(bound / worst);
      }
    }
    std::printf(
        "%s: costate bound / largest sampled deviation median %.2f\n", ToString(regime).c_str(), Median(ratios));
  }
}

// The costate test's lower bound on e_c over a box holds at sampled points (targets made from
// random rotations, the chord bound the smaller of D and the closed-form one), and the minimum of
// the centre's angle over the range of beta is a lower bound of a dense sampling (2,000 points)
// and at most 0.05 below it.
TEST(IsoparallelCertifyCostate, CostateLowerBoundHoldsOverTheBox) {
  std::mt19937 rng(17);
  for (PendulumRegime regime : kRegimes) {
    int positive = 0;
    for (int b = 0; b < 600; ++b) {
      const CertifyBox box = RandomBox(regime, &rng);
      CertifyTarget target;
      target.target = ExpSO3(Eigen::Vector3d(std::uniform_real_distribution<double>(-1.5, 1.5)(rng), 0.4, -0.8));
      target.goal_angle = std::uniform_real_distribution<double>(-3.0, 3.0)(rng);
      CostateAngle centre;
      ASSERT_TRUE(EvaluateCostateAngle(target, regime, box.Centre(), &centre));
      const double dc = std::min(RollingDeviationBound(regime, box), ChordDeviationBound(regime, box));
      const double turn = dc < centre.chord.norm() ? std::asin(dc / centre.chord.norm()) : M_PI;
      const double least = MinCostateAngleOverTurn(target, centre, turn);
      double dense = M_PI;
      for (int i = 0; i <= 2000; ++i)
        dense =
            std::min(dense, CostateAngleAt(target, centre, centre.beta + std::min(turn, M_PI) * (i / 1000.0 - 1.0)));
      ASSERT_LE(least, dense + 1e-12) << ToString(regime) << " box " << b;
      ASSERT_GE(least, dense - 0.05) << ToString(regime) << " box " << b;
      const double lower = least - CostateEndsDeviationBound(regime, box, centre, 1e-7);
      if (lower > 0.0) ++positive;
      for (int j = 0; j < 6; ++j) {
        CostateAngle at;
        ASSERT_TRUE(EvaluateCostateAngle(target, regime, RandomPointIn(box, &rng), &at));
        ASSERT_GE(at.angle, lower - 1e-9) << ToString(regime) << " box " << b;
      }
    }
    std::printf("%s: lower bound of e_c positive on %d of 600 boxes\n", ToString(regime).c_str(), positive);
    EXPECT_GT(positive, 30) << ToString(regime);  // the check is not empty
  }
}

// The costate in the certificate's frame is the closed form of the brief (oscillating
// sin theta = 2k sn dn, cos theta = 1 - 2k^2 sn^2, theta' = 2kb cn, G = b^2; rotating
// sin theta = 2 sn cn, cos theta = 1 - 2 sn^2, theta' = 2a dn, G = a^2 k^2), |v| is constant,
// and the rolling carries it: Q(0, s) v(0) = v(s) (Magnus table at fine steps and dopri5).
TEST(IsoparallelCertifyCostate, RollingCarriesTheCostate) {
  std::mt19937 rng(18);
  for (PendulumRegime regime : kRegimes) {
    const bool oscillating = regime == PendulumRegime::kOscillating;
    for (int trial = 0; trial < 12; ++trial) {
      const CertifyBox box = RandomBox(regime, &rng);
      CertifyPoint x = box.Centre();
      x[kCertifyLength] = std::min(x[kCertifyLength], 6.0);
      const Elastica e = CertifyElastica(regime, x);
      const double rate = x[kCertifyRate], k = x[kCertifyModulus], length = x[kCertifyLength];
      const ElasticaRollingTable table(e, length, 64, 0.005);
      ASSERT_TRUE(table.Valid());
      const Eigen::Vector3d v0 = ElasticaCostate(e, 0.0);
      for (double f : {0.0, 0.3, 0.77, 1.0}) {
        const double s = f * length;
        double sn = 0, cn = 0, dn = 0;
        sn = boost::math::jacobi_elliptic(k, rate * s + x[kCertifyPhase], &cn, &dn);
        const Eigen::Vector3d closed =
            oscillating ? Eigen::Vector3d(2 * k * sn * dn, rate * rate - (1 - 2 * k * k * sn * sn), 2 * k * rate * cn)
                        : Eigen::Vector3d(2 * sn * cn, rate * rate * k * k - (1 - 2 * sn * sn), 2 * rate * dn);
        const Eigen::Vector3d vs = ElasticaCostate(e, s);
        EXPECT_LT((vs - closed).norm(), 1e-11 * (1.0 + closed.norm())) << ToString(regime) << " " << s;
        EXPECT_NEAR(vs.norm(), v0.norm(), 1e-11 * (1.0 + v0.norm()));
        EXPECT_LT((table.Rolling(s) * v0 - vs).norm(), 1e-9 * (1.0 + v0.norm())) << ToString(regime) << " " << s;
      }
      EXPECT_LT((Dopri(e, length) * v0 - ElasticaCostate(e, length)).norm(), 1e-9 * (1.0 + v0.norm()));
    }
  }
}

// At every solution of the rotation problem the solver finds, and at made solutions of both
// regimes, e_c vanishes, and no box around it (nested, off-centre, half-widths 1e-5..0.3 of the
// axis scales) is excluded by the costate test or by the chord and rotation tests with the
// split bounds. A perturbed target is then excluded on the small boxes: the test can fail.
TEST(IsoparallelCertifyCostate, NeverExcludesABoxHoldingASolution) {
  const Problem file = ReadProblemFile(plateball::testing::SourcePath("problems/isoparallel_rotation.json"));
  const IsoparallelSetup setup = IsoparallelSetupFor(file);
  const IsoparallelSummary solved = SolveIsoparallel(setup.problem, setup.options);
  ASSERT_TRUE(solved.IsSolutionUsable());
  std::vector<std::pair<CertifyTarget, std::pair<PendulumRegime, CertifyPoint>>> cases;
  for (const IsoparallelSolution& s : solved.solutions)
    cases.push_back({CertifyTargetOf(setup.problem), {s.parameters.regime, CanonicalSolution(s.parameters, s.length)}});
  for (const auto& [regime, x] : {std::pair{PendulumRegime::kRotating, CertifyPoint{0.6, 0.6, 0.7, 3.0}},
                                  std::pair{PendulumRegime::kOscillating, CertifyPoint{1.1, 0.8, 1.8, 5.0}}})
    cases.push_back({plateball::testing::MadeCertifyTarget(regime, x), {regime, x}});
  ASSERT_GE(cases.size(), 10u);
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> offset(-0.9, 0.9);
  int boxes = 0, perturbed_excluded = 0;
  for (const auto& [target, solution] : cases) {
    const auto& [regime, x] = solution;
    CostateAngle at;
    ASSERT_TRUE(EvaluateCostateAngle(target, regime, x, &at));
    EXPECT_LT(at.angle, 2e-6) << ToString(regime) << " L " << x[kCertifyLength];
    for (double h : {1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.3}) {
      const CertifyBox box = BoxAround(x, {offset(rng), offset(rng), offset(rng), offset(rng)}, h);
      const double dc = std::min(RollingDeviationBound(regime, box), ChordDeviationBound(regime, box));
      EXPECT_FALSE(SomeTestExcludes(target, regime, box)) << ToString(regime) << " h " << h;
      ++boxes;
      if (h <= 1e-4) {  // the same box with the target turned by 0.01 rad holds no solution
        CertifyTarget turned = target;
        turned.target = ExpSO3(Eigen::Vector3d(0.0, 0.01, 0.0)) * target.target;
        perturbed_excluded += CostateExcludes(turned, regime, box, dc, 1e-7) ? 1 : 0;
      }
    }
  }
  std::printf("%d boxes around %zu solutions; %d of %zu small boxes excluded for the turned target\n",
              boxes,
              cases.size(),
              perturbed_excluded,
              2 * cases.size());
  EXPECT_GE(perturbed_excluded, static_cast<int>(cases.size()));
}

// Random boxes of both regimes, each with a made solution at a random point of it (a third of
// its coordinates on a face): neither the costate test nor TestBox with the split bounds ever
// excludes one, while the same boxes with the target turned by 0.05 rad are excluded often.
TEST(IsoparallelCertifyCostate, NeverExcludesARandomBoxAroundAMadeSolution) {
  std::mt19937 rng(21);
  for (PendulumRegime regime : kRegimes) {
    int turned_excluded = 0, boxes = 0;
    for (int b = 0; b < 150; ++b) {
      CertifyBox box = RandomBox(regime, &rng);
      box.hi[kCertifyLength] = std::min(box.hi[kCertifyLength], 6.0);
      box.lo[kCertifyLength] = std::min(box.lo[kCertifyLength], 5.5);
      box.hi[kCertifyRate] = std::clamp(box.hi[kCertifyRate], -5.0, 5.0);
      box.lo[kCertifyRate] = std::clamp(box.lo[kCertifyRate], -5.0, box.hi[kCertifyRate]);
      const CertifyPoint x = RandomPointIn(box, &rng);
      const CertifyTarget target = plateball::testing::MadeCertifyTarget(regime, x);
      const double dc = std::min(RollingDeviationBound(regime, box), ChordDeviationBound(regime, box));
      ASSERT_FALSE(SomeTestExcludes(target, regime, box)) << ToString(regime) << " box " << b;
      CertifyTarget turned = target;
      turned.target = ExpSO3(Eigen::Vector3d(0.05, 0.0, 0.0)) * target.target;
      turned_excluded += CostateExcludes(turned, regime, box, dc, 1e-7) ? 1 : 0;
      ++boxes;
    }
    std::printf("%s: %d boxes around made solutions; %d excluded for the turned target\n",
                ToString(regime).c_str(),
                boxes,
                turned_excluded);
    EXPECT_GT(turned_excluded, boxes / 10) << ToString(regime);
  }
}

// On the oscillating 1.0x window of the rotation problem, random boxes of the sizes where the
// window stalls (D 0.2..2): the costate test, and the chord test with the closed-form bound,
// each exclude boxes the old tests (TestBox with D for both) leave undecided.
TEST(IsoparallelCertifyCostate, ExcludesBoxesTheOldTestsLeaveUndecided) {
  const Problem file = ReadProblemFile(plateball::testing::SourcePath("problems/isoparallel_rotation.json"));
  const CertifyTarget target = CertifyTargetOf(IsoparallelSetupFor(file).problem);
  const PendulumRegime regime = PendulumRegime::kOscillating;
  std::mt19937 rng(20);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int undecided = 0, by_costate = 0, by_split = 0;
  for (int b = 0; b < 3000; ++b) {
    const CertifyPoint c = {2.0 * unit(rng), 0.95 * unit(rng), 11.6 * unit(rng), 2.24 + 3.75 * unit(rng)};
    const CertifyPoint h = {0.06 * unit(rng), 0.02 * unit(rng), 0.3 * unit(rng), 0.15 * unit(rng)};
    CertifyBox box;
    for (int i = 0; i < 4; ++i) {
      box.lo[i] = c[i] - h[i];
      box.hi[i] = c[i] + h[i];
    }
    if (box.lo[kCertifyModulus] < 0.0 || box.hi[kCertifyModulus] > 0.95) continue;
    const double d = RollingDeviationBound(regime, box);
    CertifyResidual centre;
    if (d < 0.2 || d > 2.0 || !EvaluateCertifyResidual(target, regime, box.Centre(), 0.05, &centre)) continue;
    if (TestBox(centre, d, 1e-7) != BoxVerdict::kUndecided) continue;
    ++undecided;
    const double dc = std::min(d, ChordDeviationBound(regime, box));
    by_split += TestBox(centre, d, dc, 1e-7) != BoxVerdict::kUndecided ? 1 : 0;
    by_costate += CostateExcludes(target, regime, box, dc, 1e-7) ? 1 : 0;
  }
  std::printf("%d boxes undecided by the old tests: %d decided with the closed-form chord bound, %d by the costate\n",
              undecided,
              by_split,
              by_costate);
  EXPECT_GT(undecided, 100);
  EXPECT_GT(by_split, 0);
  EXPECT_GT(by_costate, 0);
}
