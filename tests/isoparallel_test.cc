// The isoparallel solver (section 2.2): the closed-form residuals against a fine table, the Figure 7
// problem, a non-trivial target, constructed problems with a known admissible path, the straight-line
// lower bound, families, twins, determinism and input errors (its tables and scan residuals:
// isoparallel_tables_test.cc).
#include "plateball/isoparallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "chord_residual.h"
#include "elastica_closed_rolling.h"
#include "elastica_rolling.h"
#include "isoparallel/twins.h"
#include "plateball/elastica.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/path.h"
#include "plateball/problem_io.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"
#include "rotation_trick.h"
#include "support/test_support.h"

using namespace plateball;

namespace {

// dopri5 at 1e-12 over lengths ~10-30 is accurate to ~1e-11; the solver's own tolerance is 1e-12.
constexpr double kVerifiedTol = 1e-9;
// Lengths agree to the shooting tolerance propagated through the crossing (~1e-12 / slope).
constexpr double kLengthTol = 1e-7;

IsoparallelProblem Figure7() {
  IsoparallelProblem p;
  p.goal = {3.0, 3.0};
  return p;
}

Eigen::Matrix3d ReferenceRolling(const Elastica& e, double length) {
  IntegrationOptions o;
  o.absolute_tolerance = 1e-14;
  o.relative_tolerance = 1e-14;
  return RollingReorientation([&e](double s) { return e.Tangent(s); }, 0.0, length, {}, o);
}

}  // namespace

// The polish and the twin searches take the rolling in closed form: their
// residuals, the rotation trick at the n-th crossing and the free-length one from s0 to s0 + L,
// agree with those of a fine Magnus table (400 steps per period, steps <= 0.01) at random
// parameters and targets, to well below the solver's 1e-12 tolerance.
TEST(Isoparallel, ClosedFormResidualsAgreeWithAFineTable) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0;
  for (int trial = 0; trial < 16; ++trial) {
    ElasticaParameters p;
    p.regime = trial % 2 == 0 ? PendulumRegime::kOscillating : PendulumRegime::kRotating;
    p.rate = (trial % 4 < 2 ? 1.0 : -1.0) * (0.2 + 1.5 * unit(rng));
    p.modulus = 0.95 * (2.0 * unit(rng) - 1.0);
    p.phase = 6.0 * unit(rng);
    const Elastica e(p);
    const Eigen::Matrix3d target = ExpSO3(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) * 2.0);
    const double radius = 0.5 + 2.0 * unit(rng), goal_angle = 6.0 * unit(rng);
    const internal::ElasticaClosedRolling closed(e);
    const internal::ElasticaRollingTable fine(e, 25.0, 400, 0.01);
    ASSERT_TRUE(fine.Valid());
    auto residual = [&](const Eigen::Matrix3d& q, const Eigen::Vector2d& chord) {
      return internal::RotationTrickResidual(target, internal::ChordTurn(goal_angle, chord), q);
    };
    for (double s : fine.Crossings(radius, 4)) {  // the crossing formulation
      const Eigen::Vector2d chord = e.Position(s);
      EXPECT_LT((residual(closed.Rolling(s), chord) - residual(fine.Rolling(s), chord)).norm(), 1e-11) << trial;
      ++compared;
    }
    const double s0 = 3.0 * unit(rng), length = 2.0 + 10.0 * unit(rng);  // the free-length residual
    const Eigen::Vector2d chord = e.Position(s0 + length) - e.Position(s0);
    const Eigen::Matrix3d by_table = fine.Rolling(s0 + length) * fine.Rolling(s0).transpose();
    EXPECT_LT((residual(closed.Rolling(s0, s0 + length), chord) - residual(by_table, chord)).norm(), 1e-11) << trial;
    ++compared;
  }
  EXPECT_GT(compared, 30);
}

TEST(Isoparallel, Figure7ShortestIsAVerifiedFamily) {
  const IsoparallelSummary s = SolveIsoparallel(Figure7());
  ASSERT_TRUE(s.IsSolutionUsable()) << s.FullReport();
  const IsoparallelSolution& best = s.Shortest();
  EXPECT_LT(best.orientation_residual, kVerifiedTol);
  EXPECT_LT(best.endpoint_error, kVerifiedTol);
  EXPECT_LT(best.shooting_residual, 1e-12);
  EXPECT_TRUE(best.family) << s.FullReport();
  // Every reported solution is verified, distinct, sorted and within the length cap.
  for (std::size_t i = 0; i < s.solutions.size(); ++i) {
    EXPECT_LT(s.solutions[i].orientation_residual, kVerifiedTol) << i;
    EXPECT_LT(s.solutions[i].endpoint_error, kVerifiedTol) << i;
    EXPECT_LE(s.solutions[i].length, 3.0 * best.length * (1 + 1e-12));
    if (i > 0) {
      EXPECT_GE(s.solutions[i].length, s.solutions[i - 1].length);
    }
  }
  // The family: the same pendulum orbit started at other phases is still a solution of the same
  // length, checked with dopri5 only (no solver code): rotate the plane so that the end lands on
  // the goal and compare the reorientation with the identity.
  const double u_period = 2.0 * M_PI;  // any shift works for a family; sample a few
  for (double shift : {0.4, 1.7, 3.3}) {
    ElasticaParameters p = best.parameters;
    p.phase += shift * u_period / (2 * M_PI);
    const Elastica e(p);
    EXPECT_NEAR(e.Position(best.length).norm(), std::sqrt(18.0), 1e-9);
    const Eigen::Matrix3d r = ReferenceRolling(e, best.length);
    // Conjugation by the plane rotation B keeps the identity the identity.
    EXPECT_LT(RotationAngle(r, Eigen::Matrix3d::Identity()), kVerifiedTol) << shift;
  }
}

// VerifyRolling (Runge-Kutta-Fehlberg 7(8) at a tenth of the tolerances) against dopri5 at
// 1e-14 (rolling.h), on both regimes over several periods: the two integrators agree far below
// the 1e-9 that the solver's verification has to resolve.
TEST(Isoparallel, VerificationIntegratorAgreesWithDopri) {
  for (const auto& [G, k0] : {std::pair{0.62, 0.1}, std::pair{1.47, 1.5}, std::pair{0.14, 1.2}}) {
    IsoparallelSolution sol;
    sol.parameters = Elastica::FromInitialState(G, 0.4, 0.1, k0).parameters();
    sol.length = 3.7 * sol.Path().Period();
    const Eigen::Matrix3d ref = ReferenceRolling(sol.Path(), sol.length);
    EXPECT_LT(RotationAngle(VerifyRolling(sol), ref), 1e-11) << G << " " << k0;
    IntegrationOptions coarse;
    coarse.absolute_tolerance = coarse.relative_tolerance = 1e-6;  // the tolerances reach the check
    EXPECT_GT(RotationAngle(VerifyRolling(sol, coarse), ref), 1e-11) << G << " " << k0;
  }
}

// A rotating family and its mirror image (rate -> -rate) are verified once (isoparallel/verify.cc,
// MirrorImages): rolling along the mirror path directly, with dopri5, gives the same distance
// from the identity as the residual reported for it.
TEST(Isoparallel, MirrorImagesShareTheVerifiedResidual) {
  const IsoparallelSummary s = SolveIsoparallel(Figure7());
  ASSERT_TRUE(s.IsSolutionUsable());
  int mirrors = 0;
  for (const IsoparallelSolution& m : s.solutions) {
    if (!m.family || m.parameters.regime != PendulumRegime::kRotating || m.parameters.rate >= 0) continue;
    ++mirrors;
    const double direct = RotationAngle(ReferenceRolling(m.Path(), m.length), Eigen::Matrix3d::Identity());
    EXPECT_LT(direct, kVerifiedTol) << m.length;
    EXPECT_NEAR(m.orientation_residual, direct, 1e-11) << m.length;
    EXPECT_LT(m.orientation_error, kVerifiedTol) << m.length;
  }
  EXPECT_EQ(mirrors, 17) << "Figure 7: 17 rotating families, each with its mirror image";
}

// A family of m >= 2 periods is verified over one period and raised to the m-th power
// (VerifyRolling); dopri5 over the whole length agrees.
TEST(Isoparallel, FamilyVerificationOverOnePeriodAgreesWithTheWholeLength) {
  const IsoparallelSummary s = SolveIsoparallel(Figure7());
  ASSERT_TRUE(s.IsSolutionUsable());
  int checked = 0;
  for (const IsoparallelSolution& sol : s.solutions) {
    if (!sol.family || sol.periods < 2 || sol.parameters.rate < 0) continue;
    ++checked;
    EXPECT_LT(RotationAngle(VerifyRolling(sol), ReferenceRolling(sol.Path(), sol.length)), 1e-11) << sol.length;
  }
  EXPECT_GE(checked, 10);
}

TEST(Isoparallel, Figure7DenserIndependentSearchFindsNothingShorter) {
  const IsoparallelSummary s = SolveIsoparallel(Figure7());
  ASSERT_TRUE(s.IsSolutionUsable());
  const double shortest = s.Shortest().length;
  // Eight times the starts, another seed, every path up to the shortest length: nothing shorter.
  IsoparallelOptions dense;
  dense.enumerate_families = false;  // the multi-start shooting: an independent method
  dense.starts = 512;
  dense.seed = 987654321;
  dense.max_length = shortest * (1 + 1e-6);
  dense.length_cap_factor = 1.0;
  const IsoparallelSummary d = SolveIsoparallel(Figure7(), dense);
  ASSERT_TRUE(d.IsSolutionUsable()) << "the dense search must find the shortest again";
  EXPECT_NEAR(d.Shortest().length, shortest, kLengthTol);
  for (const IsoparallelSolution& sol : d.solutions) EXPECT_GE(sol.length, shortest - kLengthTol);
}

TEST(Isoparallel, RotationProblemDenserIndependentSearchFindsNothingShorter) {
  // A general target (shooting): the golden problem's shortest path, then the most starts allowed
  // (the same Halton sequence continued: 10,000 points) over paths up to 1.5x that length: nothing
  // shorter. (64 starts used to report 9.449 here: the multi-start is a sample.)
  const Problem p = ReadProblemFile(plateball::testing::SourcePath("problems/isoparallel_rotation.json"));
  const IsoparallelProblem q = IsoparallelSetupFor(p).problem;
  const IsoparallelSummary s = SolveIsoparallel(IsoparallelSetupFor(p).problem);
  ASSERT_TRUE(s.IsSolutionUsable());
  ASSERT_EQ(s.method, IsoparallelMethod::kShooting);
  const double shortest = s.Shortest().length;
  IsoparallelOptions dense;
  dense.starts = IsoparallelOptions::kMaxStarts;
  dense.max_length = 1.5 * shortest;
  dense.length_cap_factor = 1.0;
  const IsoparallelSummary d = SolveIsoparallel(q, dense);
  ASSERT_TRUE(d.IsSolutionUsable()) << "the dense search must find the shortest again";
  EXPECT_NEAR(d.Shortest().length, shortest, kLengthTol);
}

// The default run lists every solution of the rotation problem up to 3x the shortest that the
// earlier free-length shooting found on the same target (up to the rounding of its quaternion)
// with 8192 deterministic starts and with 2 x 8192 seeded ones (seeds 15838 and 23757): 30
// lengths. That shooting's default missed 14.96695293 on the problem file's own target (a
// solution whose chord only touches the radius between two coarse nodes); the crossing-number
// shooting before it missed the second-shortest, 8.705293372.
TEST(Isoparallel, RotationProblemDefaultFindsTheShortestSolutionsOfADenseSearch) {
  const Problem p = ReadProblemFile(plateball::testing::SourcePath("problems/isoparallel_rotation.json"));
  const IsoparallelSetup setup = IsoparallelSetupFor(p);
  const IsoparallelSummary s = SolveIsoparallel(setup.problem, setup.options);
  ASSERT_TRUE(s.IsSolutionUsable());
  EXPECT_FALSE(s.complete) << "the shapes are a sample";
  const double dense[] = {5.99098308,  8.70529337,  9.44921909,  9.81333296,  10.47900244, 11.71805943,
                          12.09431027, 12.48093488, 13.02769409, 13.17011463, 13.24317304, 14.28911601,
                          14.60812893, 14.60932895, 14.66144140, 14.90515056, 14.96695293, 15.23031774,
                          15.41697748, 15.64807124, 15.89496912, 16.12105750, 16.47722091, 16.69125791,
                          17.03329722, 17.04646597, 17.13379688, 17.21725846, 17.70318783, 17.92376597};
  for (double length : dense) {
    bool found = false;
    for (const IsoparallelSolution& sol : s.solutions) found = found || std::abs(sol.length - length) < 1e-6;
    EXPECT_TRUE(found) << length << "\n" << s.FullReport();
  }
  for (const IsoparallelSolution& sol : s.solutions) {
    EXPECT_LT(sol.orientation_residual, kVerifiedTol);
    EXPECT_LT(sol.endpoint_error, kVerifiedTol);
  }
  EXPECT_GE(s.solutions.size(), 30u) << s.FullReport();
}

TEST(Isoparallel, NonTrivialTargetIsSolvedAndVerified) {
  IsoparallelProblem p;
  p.start = {0.5, -1.0};
  p.goal = {2.5, 0.0};
  p.start_orientation = ExpSO3({0.1, 0.2, -0.3});
  p.goal_orientation = ExpSO3({0.7, -0.4, 1.1}) * p.start_orientation;
  const IsoparallelSummary s = SolveIsoparallel(p);
  ASSERT_TRUE(s.IsSolutionUsable()) << s.FullReport();
  for (const IsoparallelSolution& sol : s.solutions) {
    EXPECT_LT(sol.orientation_residual, kVerifiedTol);
    EXPECT_LT(sol.endpoint_error, kVerifiedTol);
    EXPECT_GE(sol.length, (p.goal - p.start).norm());
    // Independent: roll along the path with dopri5 and compare the final orientation.
    const Eigen::Matrix3d a1 = ReferenceRolling(sol.Path(), sol.length) * p.start_orientation;
    EXPECT_LT(OperatorNormDistance(a1, p.goal_orientation), kVerifiedTol);
  }
}

// T4 of docs/paper_notes.md ("General targets", x1 = (3, 0), A1 = exp(hat(0.3, 0, 0))): 22.73757780
// and 22.75708870 are a pair born at a fold (k 0.8590 and 0.8617, starting phases 0.85 apart in u),
// each found by single search runs. The twin search from either member finds the other, verified
// by dopri5 (the members as SolveIsoparallel reports them, to 17 digits). Main's twin search (one
// start at x* - (2 s / c) v) found neither: its quadratic model along v predicts a step of -7.35
// from the first (the twin lies at +0.85) and -0.63 from the second, past its 0.5 step limit.
TEST(Isoparallel, TwinSearchCrossesAFoldFromEitherMemberOfThePair) {
  IsoparallelProblem p;
  p.goal = {3.0, 0.0};
  p.goal_orientation = ExpSO3({0.3, 0.0, 0.0});
  auto member = [](double length, double rate, double modulus, double phase, double heading_w) {
    IsoparallelSolution s;
    s.parameters.regime = PendulumRegime::kOscillating;
    s.parameters.rate = rate;
    s.parameters.modulus = modulus;
    s.parameters.phase = phase;
    s.parameters.heading_w = heading_w;
    s.length = length;
    return s;
  };
  const IsoparallelSolution pair[2] = {
      member(22.737577798620237, -1.5286829366546559, 0.85899531125445905, -1.8387075034296196, 1.6856087346221791),
      member(22.757088695348607, -1.5273138595051401, 0.86166377442390474, -9.5657745109515204, 1.6712142418525553)};
  for (int i = 0; i < 2; ++i) {
    const IsoparallelSolution &from = pair[i], &to = pair[1 - i];
    ASSERT_LT(OperatorNormDistance(ReferenceRolling(from.Path(), from.length), p.goal_orientation), kVerifiedTol);
    ASSERT_LT((from.PositionAt(from.length) - p.goal).norm(), kVerifiedTol);
    bool found = false;
    for (const IsoparallelSolution& twin : internal::IsoparallelTwins(p, from)) {
      if (std::abs(twin.length - to.length) > kLengthTol) continue;
      found = true;
      EXPECT_LT(OperatorNormDistance(ReferenceRolling(twin.Path(), twin.length), p.goal_orientation), kVerifiedTol);
      EXPECT_LT((twin.PositionAt(twin.length) - p.goal).norm(), kVerifiedTol);
    }
    EXPECT_TRUE(found) << "from " << from.length;
  }
}

// The closed-form rolling takes |rate| <= 1e150 and finite rate s + phase (else it throws): the
// searches treat parameters beyond that as a failed evaluation, like an invalid table before it
// (a twin search from such a "solution" finds nothing and does not throw).
TEST(Isoparallel, ParametersBeyondTheClosedFormFailTheEvaluationWithoutThrowing) {
  IsoparallelProblem p;
  p.goal = {3.0, 0.0};
  p.goal_orientation = ExpSO3({0.3, 0.0, 0.0});
  for (const auto& [rate, length] : {std::pair{1e200, 5.0}, std::pair{1e100, 1e200}}) {
    IsoparallelSolution s;
    s.parameters.regime = PendulumRegime::kOscillating;
    s.parameters.rate = rate;
    s.parameters.modulus = 0.5;
    s.length = length;
    std::vector<IsoparallelSolution> twins;
    EXPECT_NO_THROW(twins = internal::IsoparallelTwins(p, s)) << rate;
    EXPECT_TRUE(twins.empty()) << rate;
  }
}

TEST(Isoparallel, ConstructedProblemFindsThePathOrAShorterOne) {
  // Pose the problem from a known elastica: its end point and its dopri5 reorientation. That path
  // is admissible, so the shortest solution can be no longer.
  const Elastica e = Elastica::FromInitialState(0.8, 0.3, 1.0, 0.9);
  const double length = 4.1;
  IsoparallelProblem p;
  p.goal = e.Position(length);
  p.goal_orientation = ReferenceRolling(e, length);
  const IsoparallelSummary s = SolveIsoparallel(p);
  ASSERT_TRUE(s.IsSolutionUsable()) << s.FullReport();
  EXPECT_LE(s.Shortest().length, length + kLengthTol) << s.FullReport();
  EXPECT_LT(s.Shortest().orientation_residual, kVerifiedTol);
}

TEST(Isoparallel, ConstructedShortNearlyStraightPathsAreTheShortest) {
  // Short arcs whose chord is 95-99.98% of their length, on targets near the straight rolling: the
  // polish ends where the Jacobian is nearly singular and needs more than the 12 Newton steps it
  // once had (each of the first three was lost then, and a path of length ~10 reported as the
  // shortest). The last two are arcs around a turning point of the heading (chord 99.98% and
  // 99.95%, 4.4e-4 and 1.5e-2 rad from the straight rolling): the residual is below 1e-8 along a
  // whole curve of parameters, no Newton polish reaches 1e-12 on it and both were lost until the
  // valley polish (a secant in the rate) was added; their parameters are not well determined
  // (the rate to ~1e-3), their lengths are.
  struct Made {
    PendulumRegime regime;
    double rate, modulus, phase, length;
  };
  for (const Made& m : {Made{PendulumRegime::kOscillating, 1.5, 0.3, 0.5, 1.2},
                        Made{PendulumRegime::kOscillating, 1.102, 0.089, 2.059, 1.088},
                        Made{PendulumRegime::kRotating, 0.604, 0.666, 0.081, 0.955},
                        Made{PendulumRegime::kOscillating, 1.558, 0.323, 4.424, 0.575},
                        Made{PendulumRegime::kOscillating, 0.434, 0.805, 5.917, 1.325}}) {
    ElasticaParameters q;
    q.regime = m.regime;
    q.rate = m.rate;
    q.modulus = m.modulus;
    q.phase = m.phase;
    const Elastica e(q);
    IsoparallelProblem p;
    p.goal = e.Position(m.length);
    p.goal_orientation = ReferenceRolling(e, m.length);
    const IsoparallelSummary s = SolveIsoparallel(p);
    ASSERT_TRUE(s.IsSolutionUsable()) << s.FullReport();
    EXPECT_NEAR(s.Shortest().length, m.length, 1e-9) << s.FullReport();
    EXPECT_EQ(s.Shortest().parameters.regime, m.regime);
    EXPECT_LT(s.Shortest().orientation_residual, kVerifiedTol);
  }
}

TEST(Isoparallel, ConstructedPathEndingNextToAChordTangencyIsTheShortest) {
  // |chord| of this path peaks 0.0015 before its end (d|chord|/ds = -0.004 there): the searches
  // that reach it end at residuals ~1e-4 on paths whose chord just misses the radius, with no
  // crossing to hand off, and it was lost (the shortest reported was 8.95, also with 10,000
  // shapes) until such runs were handed off at their own length (kTangentHandOff).
  ElasticaParameters q;
  q.regime = PendulumRegime::kOscillating;
  q.rate = 1.792;
  q.modulus = 0.931;
  q.phase = 0.295;
  const double length = 2.503;
  const Elastica e(q);
  const double chord = e.Position(length).norm();
  ASSERT_GT(chord, e.Position(length - 0.01).norm());  // past the chord's peak, not by much
  ASSERT_LT(chord, e.Position(length - 0.002).norm());
  IsoparallelProblem p;
  p.goal = e.Position(length);
  p.goal_orientation = ReferenceRolling(e, length);
  const IsoparallelSummary s = SolveIsoparallel(p);
  ASSERT_TRUE(s.IsSolutionUsable()) << s.FullReport();
  EXPECT_NEAR(s.Shortest().length, length, 1e-9) << s.FullReport();
  EXPECT_LT(s.Shortest().orientation_residual, kVerifiedTol);
  // It leaves the circle at s = 2.5000099 and ends where it re-enters (both between two of the
  // search's nodes, which see neither): the second crossing.
  EXPECT_EQ(s.Shortest().crossing, 2) << s.FullReport();
}

TEST(Isoparallel, StraightSegmentTargetGivesTheSegment) {
  // Rolling along the segment gives exp(hat(e3 x d)); no path is shorter than the chord.
  IsoparallelProblem p;
  p.goal = {1.2, -0.7};
  p.goal_orientation = RollAlongSegment(p.start, p.goal);
  IsoparallelOptions o;
  o.starts = 1024;  // the shortest only
  const IsoparallelSummary s = SolveIsoparallel(p, o);
  ASSERT_TRUE(s.IsSolutionUsable()) << s.FullReport();
  EXPECT_NEAR(s.Shortest().length, p.goal.norm(), kLengthTol);
  // Listed once: only a straight path is as short as its chord, but the shooting reaches it from
  // many starts as near-straight paths (modulus ~1e-6, any rate and phase; 12 copies with the
  // default starts before they were recognised as the segment).
  int copies = 0;
  for (const IsoparallelSolution& sol : s.solutions) {
    if (std::abs(sol.length - p.goal.norm()) > 1e-6) continue;
    ++copies;
    EXPECT_EQ(sol.parameters.rate, 0.0);  // reported as the segment itself
    EXPECT_LT(sol.orientation_residual, kVerifiedTol);
  }
  EXPECT_EQ(copies, 1) << s.FullReport();
}

TEST(Isoparallel, SameSeedGivesIdenticalResultsWithAnyThreadCount) {
  for (bool enumerate : {false, true}) {
    IsoparallelOptions o;
    o.starts = 24;
    o.enumerate_families = enumerate;
    const IsoparallelSummary a = SolveIsoparallel(Figure7(), o);
    o.threads = 2;
    const IsoparallelSummary b = SolveIsoparallel(Figure7(), o);
    EXPECT_EQ(a.method, enumerate ? IsoparallelMethod::kFamilyEnumeration : IsoparallelMethod::kShooting);
    ASSERT_EQ(a.solutions.size(), b.solutions.size());
    for (std::size_t i = 0; i < a.solutions.size(); ++i) {
      EXPECT_EQ(a.solutions[i].length, b.solutions[i].length);
      EXPECT_EQ(a.solutions[i].parameters.rate, b.solutions[i].parameters.rate);
      EXPECT_EQ(a.solutions[i].parameters.phase, b.solutions[i].parameters.phase);
      EXPECT_EQ(a.solutions[i].orientation_residual, b.solutions[i].orientation_residual);
    }
  }
}

// General targets: the starts are the unshifted Halton points, so every seed gives the same
// solutions, bit for bit. At the identity target the shooting (a comparison with the
// enumeration) still shifts its starts by the seed: there seeds 1 and 2 differ, so the check on
// the general target is not vacuous.
TEST(Isoparallel, GeneralTargetSolutionsDoNotDependOnTheSeed) {
  const Problem p = ReadProblemFile(plateball::testing::SourcePath("problems/isoparallel_rotation.json"));
  const IsoparallelSetup setup = IsoparallelSetupFor(p);
  IsoparallelOptions o = setup.options;
  o.starts = 96;
  o.seed = 1;
  const IsoparallelSummary a = SolveIsoparallel(setup.problem, o);
  ASSERT_TRUE(a.IsSolutionUsable());
  EXPECT_FALSE(a.seeded);
  for (std::uint64_t seed = 2; seed <= 8; ++seed) {
    o.seed = seed;
    const IsoparallelSummary b = SolveIsoparallel(setup.problem, o);
    ASSERT_EQ(a.solutions.size(), b.solutions.size()) << "seed " << seed;
    EXPECT_EQ(a.local_solves, b.local_solves) << "seed " << seed;
    for (std::size_t i = 0; i < a.solutions.size(); ++i) {
      const IsoparallelSolution &x = a.solutions[i], &y = b.solutions[i];
      EXPECT_EQ(x.length, y.length) << "seed " << seed;
      EXPECT_EQ(x.parameters.rate, y.parameters.rate) << "seed " << seed;
      EXPECT_EQ(x.parameters.modulus, y.parameters.modulus) << "seed " << seed;
      EXPECT_EQ(x.parameters.phase, y.parameters.phase) << "seed " << seed;
      EXPECT_EQ(x.parameters.heading_w, y.parameters.heading_w) << "seed " << seed;
      EXPECT_EQ(x.orientation_residual, y.orientation_residual) << "seed " << seed;
    }
  }
  // More shapes than one batch (the search length shrinks between batches): the same on 1 and
  // 2 threads.
  o.starts = 300;
  o.threads = 1;
  const IsoparallelSummary one = SolveIsoparallel(setup.problem, o);
  o.threads = 2;
  const IsoparallelSummary two = SolveIsoparallel(setup.problem, o);
  ASSERT_EQ(one.solutions.size(), two.solutions.size());
  EXPECT_EQ(one.local_solves, two.local_solves);
  for (std::size_t i = 0; i < one.solutions.size(); ++i) {
    EXPECT_EQ(one.solutions[i].length, two.solutions[i].length);
    EXPECT_EQ(one.solutions[i].parameters.phase, two.solutions[i].parameters.phase);
  }
  IsoparallelOptions identity;
  identity.enumerate_families = false;
  identity.starts = 24;
  const IsoparallelSummary c = SolveIsoparallel(Figure7(), identity);
  identity.seed = 2;
  const IsoparallelSummary d = SolveIsoparallel(Figure7(), identity);
  EXPECT_TRUE(c.seeded);
  EXPECT_NE(c.local_solves, d.local_solves) << "identity-target shooting: the seed shifts the starts";
}

TEST(Isoparallel, InvalidInputNamesTheField) {
  IsoparallelProblem p;
  auto message = [](const IsoparallelProblem& q, const IsoparallelOptions& o) {
    try {
      SolveIsoparallel(q, o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message(p, {}).find("goal"), std::string::npos);  // start == goal
  p.goal = {1.0, std::nan("")};
  EXPECT_NE(message(p, {}).find("goal"), std::string::npos);
  p.goal = {1.0, 1.0};
  p.goal_orientation(0, 0) = 2.0;
  EXPECT_NE(message(p, {}).find("goal_orientation"), std::string::npos);
  p.goal_orientation.setIdentity();
  IsoparallelOptions o;
  o.starts = 0;
  EXPECT_NE(message(p, o).find("starts"), std::string::npos);
  o.starts = 8;
  o.length_cap_factor = 0.5;
  EXPECT_NE(message(p, o).find("length_cap_factor"), std::string::npos);
}

TEST(IsoparallelPlan, CustomCurveAgreesWithTheAnalyticCircle) {
  const SmoothCurve circle = SmoothCurve::Circle({1.0, 2.0}, 1.5, 0.2, 2.9);
  const SmoothCurve custom = SmoothCurve::Custom([&](double t) { return circle.Value(t); },
                                                 [&](double t) { return circle.Derivative(t); },
                                                 [&](double t) { return circle.SecondDerivative(t); },
                                                 0.2,
                                                 2.9);
  EXPECT_EQ(custom.kind(), CurveKind::kCustom);
  EXPECT_NEAR(custom.Length(), 1.5 * 2.7, 1e-12);  // radius times angle
  EXPECT_THROW(SmoothCurve::Custom(nullptr, nullptr, nullptr, 0.0, 1.0), std::invalid_argument);
}

TEST(IsoparallelPlan, Figure7ImpulsiveErrorIsWithinBoundAndShrinksWithMoreImpulses) {
  const IsoparallelSummary s = SolveIsoparallel(Figure7());
  ASSERT_TRUE(s.IsSolutionUsable());
  const Path path = OptimalPath(s.Shortest());
  EXPECT_NEAR(path.Length(), s.Shortest().length, 1e-9);
  EXPECT_LT((path.EndPoint() - Figure7().goal).norm(), 1e-9);
  const BallModel model = BallModel::FromLambda(2.0);
  const PlanSummary coarse = PlanOptimalPath({model, 0.0, 1.0, Eigen::Matrix3d::Identity(), s.Shortest(), 12});
  const PlanSummary fine = PlanOptimalPath({model, 0.0, 1.0, Eigen::Matrix3d::Identity(), s.Shortest(), 48});
  ASSERT_TRUE(coarse.IsSolutionUsable()) << coarse.message;
  ASSERT_TRUE(fine.IsSolutionUsable()) << fine.message;
  // The planner's reference (rolling along the optimal path) is the goal orientation, the identity.
  EXPECT_LT(OperatorNormDistance(coarse.A_planned, Eigen::Matrix3d::Identity()), 1e-9);
  const double e12 = OperatorNormDistance(Eigen::Matrix3d::Identity(), coarse.A_impulsive);
  const double e48 = OperatorNormDistance(Eigen::Matrix3d::Identity(), fine.A_impulsive);
  EXPECT_LE(e12, coarse.bounds.a_posteriori);
  EXPECT_LE(e48, fine.bounds.a_posteriori);
  EXPECT_LE(e12, coarse.bounds.theorem_2_6);
  // Theorem 2.6: O(n^-2); four times the impulses must at least quarter the error.
  EXPECT_LT(e48, e12 / 4.0) << e12 << " " << e48;
}

TEST(IsoparallelPlan, InitialAnglesComeFromTheStartOrientation) {
  const AngleState a = InitialAnglesFromOrientation(Eigen::Matrix3d::Identity(), 0.3);
  EXPECT_EQ(a.theta, 0.0);  // the pole
  EXPECT_EQ(a.psi, 0.3);
  const AngleState b = InitialAnglesFromOrientation(ExpSO3({M_PI / 2, 0.0, 0.0}), 0.0);  // z = (0, -1, 0)
  EXPECT_NEAR(b.theta, M_PI / 2, 1e-15);
  EXPECT_NEAR(b.phi, -M_PI / 2, 1e-15);
}

TEST(Isoparallel, ProblemFilesSolveToTheirExpectedValues) {
  for (const char* name : {"problems/figure7.json",
                           "problems/isoparallel_rotation.json",
                           "problems/isoparallel_t3.json",
                           "problems/isoparallel_t7.json",
                           "problems/isoparallel_t9.json",
                           "problems/isoparallel_t10.json"}) {
    const Problem p = ReadProblemFile(plateball::testing::SourcePath(name));
    ASSERT_TRUE(p.isoparallel.has_value()) << name;
    const IsoparallelSetup setup = IsoparallelSetupFor(p);  // what isoparallel_solve runs
    const IsoparallelSummary s = SolveIsoparallel(setup.problem, setup.options);
    ASSERT_TRUE(s.IsSolutionUsable()) << name;
    const IsoparallelPlanSetup plan_setup = IsoparallelPlanSetupFor(p, s.Shortest());
    const PlanSummary plan = PlanOptimalPath(plan_setup.problem, plan_setup.options);
    EXPECT_TRUE(plan.IsSolutionUsable()) << name << ": " << plan.BriefReport();
    EXPECT_EQ(plan.segments, p.isoparallel->impulses) << name;
    EXPECT_LT(s.Shortest().orientation_residual, kVerifiedTol) << name;
    if (p.expected.count("shortest_length")) {
      const ExpectedValue& e = p.expected.at("shortest_length");
      EXPECT_NEAR(s.Shortest().length, e.value, e.tolerance) << name;
    }
    if (p.expected.count("solution_count")) {
      const ExpectedValue& e = p.expected.at("solution_count");
      EXPECT_NEAR(static_cast<double>(s.solutions.size()), e.value, e.tolerance) << name;
    }
  }
}

// The file's integration section reaches the solver and the plan (figure7.json with
// max_steps 5 used to solve and plan); the failure is a status, with one thread or several.
TEST(Isoparallel, IntegrationSectionReachesSolverAsAFailureStatus) {
  Problem p = ReadProblemFile(plateball::testing::SourcePath("problems/figure7.json"));
  p.integration.max_steps = 5;
  for (int threads : {1, 3}) {
    IsoparallelSetup setup = IsoparallelSetupFor(p);
    EXPECT_EQ(setup.options.integration.max_steps, 5);
    setup.options.threads = threads;
    const IsoparallelSummary s = SolveIsoparallel(setup.problem, setup.options);
    EXPECT_EQ(s.status, IsoparallelStatus::kIntegrationFailure) << s.BriefReport();
    EXPECT_NE(s.message.find("max_steps"), std::string::npos) << s.message;
    EXPECT_TRUE(s.solutions.empty());
  }
  // The plan of a solution found with the default section fails the same way.
  const Problem fine = ReadProblemFile(plateball::testing::SourcePath("problems/figure7.json"));
  const IsoparallelSetup setup = IsoparallelSetupFor(fine);
  const IsoparallelSummary s = SolveIsoparallel(setup.problem, setup.options);
  ASSERT_TRUE(s.IsSolutionUsable());
  const IsoparallelPlanSetup plan_setup = IsoparallelPlanSetupFor(p, s.Shortest());
  const PlanSummary plan = PlanOptimalPath(plan_setup.problem, plan_setup.options);
  EXPECT_EQ(plan.status, PlanStatus::kIntegrationFailure) << plan.BriefReport();
}

// The reader fills the solver's options with the solver's ranges, naming the file and field.
TEST(Isoparallel, ReaderAndSolverShareOneThreadRange) {
  const std::string base = R"({"ball": {"lambda": 2}, "initial": {"theta": 0, "phi": 0, "psi": 0, "mu": 1},
    "isoparallel": {"start": [0, 0], "goal": [3, 3], "solver": {"threads": THREADS}}})";
  auto with = [&](const std::string& threads) {
    std::string t = base;
    t.replace(t.find("THREADS"), 7, threads);
    return t;
  };
  const Problem ok = ParseProblem(with("256"), "t.json");
  EXPECT_EQ(ok.isoparallel->solver.threads, IsoparallelOptions::kMaxThreads);
  EXPECT_EQ(IsoparallelSetupFor(ok).options.Validate(), "");
  try {
    ParseProblem(with("257"), "t.json");
    FAIL() << "threads 257 accepted";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("t.json"), std::string::npos) << m;
    EXPECT_NE(m.find("isoparallel.solver.threads"), std::string::npos) << m;
  }
}

// ---- search10: cheaper searches and merge, no solution lost ----

// The 31 lengths of problems/isoparallel_rotation.json up to 3x the shortest as main at 4a16fbe
// listed them (polished on the crossing formulation: the n-th crossing of the circle on a fine
// table, 3 unknowns; now the polish runs on the free-length formulation, and searches that stall
// stop early): the same 31 to 1e-9, each verified by an independent dopri5 rolling. A stop rule
// or a polish that dropped or moved one of them (14.60812893 and 14.60932895 are 1.2e-3 apart)
// fails here.
TEST(Isoparallel, RotationProblemKeepsEveryLengthOfTheCrossingPolish) {
  const Problem p = ReadProblemFile(plateball::testing::SourcePath("problems/isoparallel_rotation.json"));
  const IsoparallelSetup setup = IsoparallelSetupFor(p);
  const IsoparallelSummary s = SolveIsoparallel(setup.problem, setup.options);
  ASSERT_TRUE(s.IsSolutionUsable());
  const std::vector<double> crossing_polish = {
      5.9909830797,  8.7052933716,  9.4492190884,  9.8133329585,  10.4790024427, 11.7180594252, 12.0943102659,
      12.4809348826, 13.0276940919, 13.1701146349, 13.2431730363, 14.2891160078, 14.6081289291, 14.6093289477,
      14.6614414044, 14.9051505615, 14.9669529338, 15.2303177409, 15.4169774821, 15.6480712410, 15.8949691241,
      16.1210575023, 16.4772209098, 16.6912579126, 17.0332972183, 17.0464659669, 17.1337968844, 17.2172584639,
      17.7031878323, 17.7630272098, 17.9237659676};
  ASSERT_EQ(s.solutions.size(), crossing_polish.size()) << s.FullReport();
  for (std::size_t i = 0; i < s.solutions.size(); ++i) {
    const IsoparallelSolution& sol = s.solutions[i];
    EXPECT_NEAR(sol.length, crossing_polish[i], 1e-9) << i;
    const Eigen::Matrix3d a1 = ReferenceRolling(sol.Path(), sol.length) * setup.problem.start_orientation;
    EXPECT_LT(OperatorNormDistance(a1, setup.problem.goal_orientation), kVerifiedTol) << sol.length;
    EXPECT_LT((sol.PositionAt(sol.length) - setup.problem.goal).norm(), kVerifiedTol) << sol.length;
  }
}

// Whole solves keep both members of T4's fold pair (22.73757780 and 22.75708870, 0.0195 apart:
// a stop rule with a radius beyond the pair's distance would drop one), and T6 (x1 = (2, -1),
// A1 = exp(hat(0.5, 0.5, 0.5))) lists 10.41197440, which main's polish on the crossing
// formulation did not reach from the same search result; each verified by an independent dopri5
// rolling.
TEST(Isoparallel, WholeSolvesKeepTheFoldPairAndTheFreeLengthPolishFindsMore) {
  struct Case {
    Eigen::Vector2d goal;
    Eigen::Vector3d w;
    std::vector<double> lengths;
  };
  const Case cases[] = {{{3.0, 0.0}, {0.3, 0.0, 0.0}, {22.7375777986, 22.7570886954}},
                        {{2.0, -1.0}, {0.5, 0.5, 0.5}, {10.4119744049}}};
  for (const Case& c : cases) {
    IsoparallelProblem p;
    p.goal = c.goal;
    p.goal_orientation = ExpSO3(c.w);
    const IsoparallelSummary s = SolveIsoparallel(p);
    ASSERT_TRUE(s.IsSolutionUsable()) << s.FullReport();
    for (double length : c.lengths) {
      const IsoparallelSolution* match = nullptr;
      for (const IsoparallelSolution& sol : s.solutions)
        if (std::abs(sol.length - length) < 1e-9) match = &sol;
      ASSERT_NE(match, nullptr) << length << "\n" << s.FullReport();
      const Eigen::Matrix3d a1 = ReferenceRolling(match->Path(), match->length);
      EXPECT_LT(OperatorNormDistance(a1, p.goal_orientation), kVerifiedTol) << length;
      EXPECT_LT((match->PositionAt(match->length) - p.goal).norm(), kVerifiedTol) << length;
    }
  }
}

// Elastica::WithRate (the searches' rate column: the path of another rate sharing k's AGM
// sequence, K, D and the values at s = 0) gives what the constructor gives for the same
// parameters, bit for bit: positions, tangents, curvatures, G, E, the period, the drift and the
// closed-form rolling built on it (and TangentAndCurvature, the phase and length columns' one
// Jacobi evaluation, Tangent's and Curvature's values); down to rate 0 (a straight line: infinite period, no drift,
// none kept from the curved path) and in both regimes. A non-finite rate is refused by name.
TEST(Isoparallel, ElasticaWithRateEqualsTheConstructedPath) {
  for (PendulumRegime regime : {PendulumRegime::kOscillating, PendulumRegime::kRotating}) {
    ElasticaParameters p;
    p.regime = regime;
    p.rate = 1.3;
    p.modulus = -0.7;
    p.phase = 2.9;
    p.heading_w = 0.4;
    const Elastica base(p);
    for (double rate : {1.3 + 1e-6, -0.45, 2.7, 0.0}) {
      ElasticaParameters q = p;
      q.rate = rate;
      const Elastica made(q), shared = base.WithRate(rate);
      EXPECT_EQ(shared.parameters().rate, rate);
      EXPECT_EQ(shared.G(), made.G()) << rate;
      EXPECT_EQ(shared.Energy(), made.Energy()) << rate;
      EXPECT_EQ(shared.Period(), made.Period()) << rate;
      EXPECT_EQ(shared.DriftPerPeriod(), made.DriftPerPeriod()) << rate;
      for (double s : {0.0, 1e-7, 0.02, 0.9, 7.5, -3.1}) {
        EXPECT_EQ(shared.Position(s), made.Position(s)) << rate << " " << s;
        EXPECT_EQ(shared.Tangent(s), made.Tangent(s)) << rate << " " << s;
        EXPECT_EQ(shared.Curvature(s), made.Curvature(s)) << rate << " " << s;
        Eigen::Vector2d tangent;
        double curvature = 0.0;
        shared.TangentAndCurvature(s, &tangent, &curvature);  // one Jacobi evaluation for both
        EXPECT_EQ(tangent, made.Tangent(s)) << rate << " " << s;
        EXPECT_EQ(curvature, made.Curvature(s)) << rate << " " << s;
      }
      if (rate == 0.0) {
        EXPECT_TRUE(std::isinf(shared.Period()));
        EXPECT_EQ(shared.DriftPerPeriod(), Eigen::Vector2d::Zero());
        continue;
      }
      const internal::ElasticaClosedRolling a(shared), b(made);
      EXPECT_EQ(a.Rolling(5.3), b.Rolling(5.3)) << rate;
    }
    EXPECT_THROW(base.WithRate(std::nan("")), std::invalid_argument);
  }
}
