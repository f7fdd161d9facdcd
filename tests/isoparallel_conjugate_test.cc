// Conjugate points of the isoparallel extremals (src/isoparallel_conjugate.h): the planar
// elastica against Sachkov's classical result, the plate-ball Jacobian against finite differences
// of the end map in closed form (a second computation: Elastica positions and the closed-form
// rolling, no ODE), and Figure 7's solutions.
#include "isoparallel_conjugate.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "elastica_closed_rolling.h"
#include "plateball/elastica.h"
#include "plateball/isoparallel.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"
#include "support/test_support.h"

namespace plateball::internal {
namespace {

// The first n zeros of the curvature after s = 0 (inflection points), by a scan and bisection.
std::vector<double> Inflections(const Elastica& e, int n, double s_max) {
  std::vector<double> out;
  const int steps = 4000;
  double s0 = 0.0, c0 = e.Curvature(0.0);
  for (int i = 1; i <= steps && static_cast<int>(out.size()) < n; ++i) {
    const double s1 = s_max * i / steps, c1 = e.Curvature(s1);
    if (c0 != 0.0 && c0 * c1 <= 0.0) {
      double lo = s0, hi = s1;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        (e.Curvature(mid) * c0 > 0 ? lo : hi) = mid;
      }
      out.push_back(0.5 * (lo + hi));
    }
    s0 = s1;
    c0 = c1;
  }
  return out;
}

// Sachkov (2008): an inflectional elastica has its first conjugate point between its first and
// third inflection points.
TEST(IsoparallelConjugate, InflectionalPlanarElasticaIsConjugateBetweenTheFirstAndThirdInflection) {
  int checked = 0;
  for (double k : {0.2, 0.5, 0.8, 0.95}) {
    for (double phase : {0.0, 0.4, 1.3, 2.9}) {
      for (double rate : {0.7, -1.6}) {
        const ElasticaParameters p{PendulumRegime::kOscillating, rate, k, phase, 0.3};
        const Elastica e(p);
        const std::vector<double> inflections = Inflections(e, 3, 2.0 * e.Period());
        ASSERT_EQ(inflections.size(), 3u);
        const ConjugateTime c =
            FirstConjugateTime(ConjugateProblem::kPlanarElastica, ExtremalDataOf(p), 2.0 * e.Period());
        ASSERT_TRUE(c.found) << "k " << k << " phase " << phase << " rate " << rate;
        EXPECT_GE(c.time, inflections[0]) << "k " << k << " phase " << phase << " rate " << rate;
        EXPECT_LE(c.time, inflections[2]) << "k " << k << " phase " << phase << " rate " << rate;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 32);
}

// Sachkov (2008): non-inflectional elasticae (the rotating pendulum, circles) have no conjugate
// points; checked over five curvature periods.
TEST(IsoparallelConjugate, NonInflectionalPlanarElasticaHasNoConjugatePoint) {
  for (double k : {0.0, 0.3, 0.7, 0.95}) {
    for (double phase : {0.0, 0.9}) {
      const ElasticaParameters p{PendulumRegime::kRotating, 1.1, k, phase, -0.4};
      const Elastica e(p);
      const ConjugateTime c =
          FirstConjugateTime(ConjugateProblem::kPlanarElastica, ExtremalDataOf(p), 5.0 * e.Period());
      EXPECT_FALSE(c.found) << "k " << k << " phase " << phase << " at " << c.time;
    }
  }
}

// The plate-ball end map in closed form: position by Elastica::Position, rolling by
// ElasticaClosedRolling, from (W1, W2, g0, kappa0) and s.
struct EndMap {
  Eigen::Vector2d x;
  Eigen::Matrix3d r;
};
EndMap ClosedEnd(const Eigen::Matrix<double, 5, 1>& q) {
  const Elastica e = Elastica::FromInitialState(std::hypot(q[0], q[1]), std::atan2(q[1], q[0]), q[2], q[3]);
  return {e.Position(q[4]), ElasticaClosedRolling(e).Rolling(0.0, q[4])};
}

// det of the unit-column Jacobian by central differences of the closed-form end map.
double FiniteDifferenceDeterminant(const ExtremalData& d, double s) {
  constexpr double kStep = 1e-5;  // central differences: truncation ~1e-10, round-off ~1e-11
  Eigen::Matrix<double, 5, 1> q;
  q << d.w[0], d.w[1], d.heading, d.curvature, s;
  Eigen::Matrix<double, 5, 5> m;
  for (int j = 0; j < 5; ++j) {
    Eigen::Matrix<double, 5, 1> a = q, b = q;
    a[j] += kStep;
    b[j] -= kStep;
    const EndMap ea = ClosedEnd(a), eb = ClosedEnd(b);
    Eigen::Matrix<double, 5, 1> c;
    c.head<2>() = (ea.x - eb.x) / (2 * kStep);
    c.tail<3>() = LogSO3(ea.r * eb.r.transpose()) / (2 * kStep);
    m.col(j) = c.normalized();
  }
  return m.determinant();
}

// The first sign change of the finite-difference determinant after `from`, by bisection.
double FiniteDifferenceRoot(const ExtremalData& d, double lo, double hi) {
  const double sign = FiniteDifferenceDeterminant(d, lo);
  for (int k = 0; k < 40; ++k) {
    const double mid = 0.5 * (lo + hi);
    (FiniteDifferenceDeterminant(d, mid) * sign > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(IsoparallelConjugate, PlateBallDeterminantAgreesWithFiniteDifferencesOfTheClosedForm) {
  constexpr double kDeterminantTolerance = 1e-5;  // relative: the differences' error ~1e-10 / |det| >= 1e-7
  constexpr double kRootTolerance = 1e-6;         // relative: the differences' error ~1e-10 over a slope ~1e-4
  const ElasticaParameters cases[] = {{PendulumRegime::kOscillating, 0.8, 0.6, 0.3, 0.2},
                                      {PendulumRegime::kOscillating, 1.3, 0.9, 1.1, -0.7},
                                      {PendulumRegime::kRotating, 0.9, 0.5, 0.2, 1.0},
                                      {PendulumRegime::kRotating, -2.0, 0.8, 0.7, 0.1}};
  int roots = 0;
  for (const ElasticaParameters& p : cases) {
    const ExtremalData d = ExtremalDataOf(p);
    const double s_max = 3.0 * Elastica(p).Period();
    for (double f : {0.37, 0.81, 1.66}) {
      const double s = f * Elastica(p).Period();
      const double a = ConjugateDeterminant(ConjugateProblem::kPlateBall, d, s), b = FiniteDifferenceDeterminant(d, s);
      EXPECT_NEAR(a, b, kDeterminantTolerance * std::abs(b) + 1e-10) << "s " << s;
    }
    const ConjugateTime c = FirstConjugateTime(ConjugateProblem::kPlateBall, d, s_max);
    if (!c.found) continue;
    const double h = 0.02 * c.time;
    EXPECT_NEAR(FiniteDifferenceRoot(d, c.time - h, c.time + h), c.time, kRootTolerance * c.time);
    ++roots;
  }
  EXPECT_GE(roots, 2);
}

// Figure 7 (identity target): every solution is a family, whose members at other phases reach the
// same state with the same length, so the end is a conjugate point of each: the conjugate time is
// at most the length, and the shortest (certified optimal, docs/paper_notes.md) has none before its end.
TEST(IsoparallelConjugate, Figure7FamiliesAreConjugateAtTheirEnd) {
  constexpr double kEndTolerance = 1e-6;  // relative: the bisection and the solver's length ~1e-10
  IsoparallelProblem p;
  p.goal = {3.0, 3.0};
  const IsoparallelSummary s = SolveIsoparallel(p);
  ASSERT_TRUE(s.IsSolutionUsable()) << s.BriefReport();
  ASSERT_EQ(s.solutions.size(), 47u);
  EXPECT_TRUE(s.solutions.front().locally_optimal);
  EXPECT_NEAR(
      s.solutions.front().conjugate_time, s.solutions.front().length, kEndTolerance * s.solutions.front().length);
  int at_end = 0, before = 0;
  for (const IsoparallelSolution& sol : s.solutions) {
    ASSERT_TRUE(sol.family);
    EXPECT_LE(sol.conjugate_time, sol.length * (1 + kEndTolerance));
    at_end += std::abs(sol.conjugate_time - sol.length) <= kEndTolerance * sol.length ? 1 : 0;
    before += sol.locally_optimal ? 0 : 1;
    EXPECT_EQ(sol.locally_optimal, sol.conjugate_time >= sol.length * (1 - kConjugateEndTolerance));
  }
  EXPECT_EQ(at_end + before, 47);
  // Mirror images of rotating families have equal lengths: Maxwell pairs.
  EXPECT_FALSE(s.maxwell_pairs.empty());
  for (const MaxwellPair& m : s.maxwell_pairs) {
    EXPECT_LT(m.first, m.second);
    EXPECT_NEAR(s.solutions[m.first].length, s.solutions[m.second].length, 1e-9 * s.solutions[m.first].length);
  }
}

// The rotation problem's shortest path is certified globally shortest (problems/
// isoparallel_rotation.json, the branch-and-bound certificate); a global minimiser satisfies
// Jacobi's condition, so its first conjugate point lies beyond its end (measured: 8.22 > 5.99).
TEST(IsoparallelConjugate, CertifiedShortestOfTheRotationProblemIsLocallyOptimal) {
  const IsoparallelSetup setup =
      IsoparallelSetupFor(ReadProblemFile(plateball::testing::SourcePath("problems/isoparallel_rotation.json")));
  const IsoparallelSummary s = SolveIsoparallel(setup.problem, setup.options);
  ASSERT_TRUE(s.IsSolutionUsable()) << s.BriefReport();
  const IsoparallelSolution& best = s.Shortest();
  EXPECT_NEAR(best.length, 5.99098308, 1e-7);
  EXPECT_TRUE(best.locally_optimal);
  EXPECT_GT(best.conjugate_time, best.length * 1.1);
  int local = 0;
  for (const IsoparallelSolution& sol : s.solutions) local += sol.locally_optimal ? 1 : 0;
  EXPECT_LT(local, static_cast<int>(s.solutions.size()));  // measured: 3 of 31
}

}  // namespace
}  // namespace plateball::internal
