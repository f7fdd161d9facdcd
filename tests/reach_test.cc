#include "plateball/reach.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlopt.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "plateball/ball_state.h"
#include "plateball/free_motion.h"
#include "plateball/impulse_planner.h"
#include "plateball/partition.h"
#include "plateball/path.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "reach_internal.h"
#include "support/test_support.h"

using namespace plateball;

namespace {

// The brief's acceptance bound: the arrival point, recomputed by a direct integration that does
// not use periodicity, is within this of the target.
constexpr double kReachTolerance = 1e-10;
// Same solution found twice: s and t agree to this (refinement converges to ~1e-13).
constexpr double kDistinct = 1e-6;

// The paper's Figure 8 ball, as the paper gives it (theta0 = -pi/3).
ReachProblem Figure8(const Eigen::Vector2d& target) {
  ReachProblem p;
  p.model = BallModel::FromLambda(2.0);
  p.start = {-M_PI / 3, M_PI / 2, 0.0};
  p.mu = 1.0;
  p.target = target;
  return p;
}

// A light, slender ball (lambda = 0.05) lying almost on its side: its contact path has folds, so
// some targets are reached in several ways within five periods.
ReachProblem Slender(const Eigen::Vector2d& target) {
  ReachProblem p;
  p.model = BallModel::FromLambda(0.05);
  p.start = {1.5, 0.0, 0.0};
  p.mu = 1.0;
  p.target = target;
  return p;
}

FreeMotionStart StartAfterImpulse(const ReachProblem& p, double s) {
  FreeMotionStart st;
  AngleState a = p.start;
  a.psi += s;
  st.state = StateFromAngles(a, p.mu, p.model);
  st.x0 = p.x0;
  st.A0 = AlignOrientationToAxis(p.A0, st.state.z);
  return st;
}

// Independent check: direct integration from the state just after the impulse (no periodicity).
double DirectMiss(const ReachProblem& p, double s, double t) {
  const std::vector<MotionSample> out = IntegrateFreeMotion(p.model, StartAfterImpulse(p, s), {t});
  return (out[0].x - p.target).norm();
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// An independent, much denser scan: for `directions` values of s, IntegrateFreeMotion samples
// x_s(t) at `per_period` points per period over the horizon; the cells of the (s, t) grid whose
// piecewise-linear image contains the target are returned as their (s, t) centres.
struct DenseHit {
  double s, t;
};
std::vector<DenseHit> DenseScan(
    const ReachProblem& p, double horizon_periods, int directions, int per_period, double* best_distance = nullptr) {
  const double period = 2 * M_PI / std::sqrt(p.mu);
  const int m = static_cast<int>(std::ceil(horizon_periods * per_period));
  std::vector<double> times(static_cast<std::size_t>(m) + 1);
  for (int j = 0; j <= m; ++j)
    times[static_cast<std::size_t>(j)] = std::min(j * period / per_period, horizon_periods * period);
  std::vector<std::vector<Eigen::Vector2d>> x(static_cast<std::size_t>(directions));
  double best = 1e300;
  for (int i = 0; i < directions; ++i) {
    const auto samples = IntegrateFreeMotion(p.model, StartAfterImpulse(p, 2 * M_PI * i / directions), times);
    for (const auto& smp : samples) {
      x[static_cast<std::size_t>(i)].push_back(smp.x);
      best = std::min(best, (smp.x - p.target).norm());
    }
  }
  if (best_distance != nullptr) *best_distance = best;
  std::vector<DenseHit> hits;
  auto in_triangle = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const double area = Cross(b - a, c - a);
    if (area == 0) return false;
    const double l1 = Cross(b - p.target, c - p.target) / area, l2 = Cross(c - p.target, a - p.target) / area,
                 l3 = Cross(a - p.target, b - p.target) / area;
    return l1 >= 0 && l2 >= 0 && l3 >= 0;
  };
  for (int i = 0; i < directions; ++i)
    for (int j = 0; j < m; ++j) {
      const auto& c0 = x[static_cast<std::size_t>(i)];
      const auto& c1 = x[static_cast<std::size_t>((i + 1) % directions)];
      const std::size_t ju = static_cast<std::size_t>(j);
      if (in_triangle(c0[ju], c1[ju], c1[ju + 1]) || in_triangle(c0[ju], c1[ju + 1], c0[ju + 1]))
        hits.push_back({2 * M_PI * (i + 0.5) / directions, 0.5 * (times[ju] + times[ju + 1])});
    }
  return hits;
}

double AngleDistance(double a, double b) {
  const double d = std::abs(std::remainder(a - b, 2 * M_PI));
  return d;
}

void ExpectSolutionsValid(const ReachProblem& p, const ReachSummary& s, double horizon_periods) {
  const double period = 2 * M_PI / std::sqrt(p.mu);
  for (std::size_t k = 0; k < s.solutions.size(); ++k) {
    const ReachSolution& sol = s.solutions[k];
    EXPECT_GT(sol.t, 0.0);
    EXPECT_LE(sol.t, horizon_periods * period);
    EXPECT_GE(sol.delta_psi, 0.0);
    EXPECT_LT(sol.delta_psi, 2 * M_PI);
    EXPECT_LT(DirectMiss(p, sol.delta_psi, sol.t), kReachTolerance) << "solution " << k;
    EXPECT_LT((sol.end.x - p.target).norm(), kReachTolerance) << "solution " << k;
    EXPECT_NEAR(sol.end.energy, p.mu, 1e-10);
    EXPECT_TRUE(plateball::testing::IsRotationMatrix(sol.end.A, 1e-9));
    EXPECT_NEAR(sol.periods, sol.t / period, 1e-14);
    if (k > 0) {
      EXPECT_LE(s.solutions[k - 1].t, sol.t) << "sorted by t";
      EXPECT_TRUE(std::abs(s.solutions[k - 1].t - sol.t) > kDistinct ||
                  AngleDistance(s.solutions[k - 1].delta_psi, sol.delta_psi) > kDistinct)
          << "distinct";
    }
  }
}

// Every dense hit lies next to a reported solution, and every solution next to a dense hit.
void ExpectSameSolutionsAsDenseScan(const ReachProblem& p, const ReachSummary& s, int directions, int per_period) {
  const std::vector<DenseHit> hits = DenseScan(p, 5.0, directions, per_period);
  const double period = 2 * M_PI / std::sqrt(p.mu);
  const double ds = 2 * M_PI / directions, dt = period / per_period;
  for (const DenseHit& h : hits) {
    bool explained = false;
    for (const ReachSolution& sol : s.solutions)
      explained = explained || (AngleDistance(h.s, sol.delta_psi) <= 1.5 * ds && std::abs(h.t - sol.t) <= 1.5 * dt);
    EXPECT_TRUE(explained) << "dense scan hit at s = " << h.s << ", t = " << h.t << " not among the solutions";
  }
  for (const ReachSolution& sol : s.solutions) {
    bool seen = false;
    for (const DenseHit& h : hits)
      seen = seen || (AngleDistance(h.s, sol.delta_psi) <= 1.5 * ds && std::abs(h.t - sol.t) <= 1.5 * dt);
    EXPECT_TRUE(seen) << "solution s = " << sol.delta_psi << ", t = " << sol.t << " not seen by the dense scan";
  }
}

}  // namespace

TEST(Reach, Figure8TargetsAreReachedByAnIndependentIntegration) {
  for (const Eigen::Vector2d& target : {Eigen::Vector2d(6, 0), Eigen::Vector2d(0, 10), Eigen::Vector2d(-12, 5)}) {
    const ReachProblem p = Figure8(target);
    const ReachSummary s = Reach(p);
    ASSERT_EQ(s.status, ReachStatus::kSolved) << s.BriefReport();
    ASSERT_TRUE(s.IsSolutionUsable());
    ExpectSolutionsValid(p, s, 5.0);
    // The impulse reported is the one applied: psi jumps by delta_psi at fixed (theta, phi).
    const ReachSolution& e = s.Earliest();
    EXPECT_NEAR(std::remainder(e.impulse.after.psi - e.impulse.before.psi - e.delta_psi, 2 * M_PI), 0.0, 1e-12);
    EXPECT_NEAR(e.impulse.mu_after, p.mu, 1e-12);
  }
}

TEST(Reach, StraightRollingTargetHasTheClosedFormSolution) {
  // Closed form: from Figure 8's state, delta_psi = pi gives w = phi - psi = -pi/2, so
  // omega = (-1, 0, 0) (section 2.1's omega_1, omega_2 with b = 1) and v0 = <omega, z> = 0 since
  // z = (0, -sqrt(3)/2, 1/2). Then K = (-1, 0), z turns about e1 keeping z_1 = 0, v0 stays 0 and
  // omega = K is constant: the ball rolls straight along +y at unit speed, x(t) = (0, t).
  const ReachSummary s = Reach(Figure8({0, 10}));
  ASSERT_EQ(s.status, ReachStatus::kSolved) << s.BriefReport();
  ASSERT_EQ(s.solutions.size(), 1u);
  EXPECT_NEAR(s.Earliest().delta_psi, M_PI, 1e-10);
  EXPECT_NEAR(s.Earliest().t, 10.0, 1e-10);
}

TEST(Reach, Figure8ProblemFileExpectedValuesHold) {
  const Problem problem = ReadProblemFile(plateball::testing::SourcePath("problems/figure8_reach.json"));
  ASSERT_TRUE(problem.reach.has_value());
  ASSERT_EQ(problem.reach->targets.size(), 3u);
  EXPECT_EQ(problem.initial.theta, -M_PI / 3);  // as the paper gives it
  ReachOptions o;
  o.horizon_periods = problem.reach->horizon_periods;
  o.integration = problem.integration;
  for (std::size_t k = 0; k < problem.reach->targets.size(); ++k) {
    ReachProblem rp;
    rp.model = problem.model;
    rp.start = problem.initial;
    rp.mu = problem.mu;
    rp.x0 = problem.x0;
    rp.A0 = problem.A0;
    rp.target = problem.reach->targets[k];
    const ReachSummary s = Reach(rp, o);
    ASSERT_TRUE(s.IsSolutionUsable()) << s.BriefReport();
    const std::string prefix = "target_" + std::to_string(k) + "_earliest_";
    for (const auto& [name, value] : problem.expected) {
      if (name == prefix + "delta_psi") {
        EXPECT_NEAR(s.Earliest().delta_psi, value.value, value.tolerance) << name;
      }
      if (name == prefix + "t") {
        EXPECT_NEAR(s.Earliest().t, value.value, value.tolerance) << name;
      }
    }
  }
  EXPECT_EQ(problem.expected.count("target_1_earliest_t"), 1u);
}

TEST(Reach, DenserIndependentScanFindsNoOtherSolutionForFigure8Targets) {
  for (const Eigen::Vector2d& target : {Eigen::Vector2d(6, 0), Eigen::Vector2d(0, 10), Eigen::Vector2d(-12, 5)}) {
    const ReachProblem p = Figure8(target);
    const ReachSummary s = Reach(p);
    ExpectSameSolutionsAsDenseScan(p, s, 1024, 128);  // 8x the default scan's directions, 2x its steps
  }
}

TEST(Reach, SeveralSolutionsAreSortedDistinctAndMatchADenserScan) {
  // Targets that the slender ball reaches three times within five periods (alternating signs of
  // the Jacobian determinant: the map (s, t) -> x folds over itself).
  for (const Eigen::Vector2d& target :
       {Eigen::Vector2d(-15, -1.5), Eigen::Vector2d(-13.5, -10.5), Eigen::Vector2d(-14.25, 1.5)}) {
    const ReachProblem p = Slender(target);
    const ReachSummary s = Reach(p);
    ASSERT_EQ(s.status, ReachStatus::kSolved) << s.BriefReport();
    EXPECT_EQ(s.solutions.size(), 3u) << s.BriefReport();
    ExpectSolutionsValid(p, s, 5.0);
    for (std::size_t k = 1; k < s.solutions.size(); ++k)
      EXPECT_LT(s.solutions[k - 1].jacobian_determinant * s.solutions[k].jacobian_determinant, 0.0);
    EXPECT_EQ(&s.Earliest(), &s.solutions.front());
    ExpectSameSolutionsAsDenseScan(p, s, 1024, 128);
  }
}

TEST(Reach, EarliestSolutionIsTheDefaultAnswer) {
  const ReachProblem p = Slender({-15, -1.5});
  const ReachSummary s = Reach(p);
  ASSERT_GE(s.solutions.size(), 2u);
  double t_min = 1e300;
  for (const ReachSolution& sol : s.solutions) t_min = std::min(t_min, sol.t);
  EXPECT_EQ(s.Earliest().t, t_min);
  EXPECT_NE(s.BriefReport().find("earliest"), std::string::npos);
}

TEST(Reach, FirstGuessIsTheImpulseWhoseDriftPointsAtTheTarget) {
  for (const Eigen::Vector2d& target : {Eigen::Vector2d(6, 0), Eigen::Vector2d(0, 10), Eigen::Vector2d(-12, 5)}) {
    const ReachProblem p = Figure8(target);
    const ReachSummary s = Reach(p);
    AngleState a = p.start;
    a.psi += s.drift_guess_delta_psi;
    const Eigen::Vector2d drift = FreeMotion::FromAngles(p.model, a, p.mu).DriftPerPeriod();
    // Interpolated linearly between scan directions 2 pi / 128 apart: the angle error is second
    // order in that spacing.
    EXPECT_LT(std::abs(Cross(drift.normalized(), target.normalized())), 2e-3);
    EXPECT_GT(drift.dot(target), 0.0);
  }
  // Far away the periodic wiggle is negligible against the drift: the solution approaches the
  // first guess (the paper's argument), here within 1e-2 at 200 units.
  const ReachProblem far = Figure8({-160, 120});
  ReachOptions o;
  o.horizon_periods = 60;
  const ReachSummary s = Reach(far, o);
  ASSERT_EQ(s.status, ReachStatus::kSolved) << s.BriefReport();
  EXPECT_LT(AngleDistance(s.Earliest().delta_psi, s.drift_guess_delta_psi), 1e-2);
  // Both the solver (one period, repeated) and the direct integration carry the tolerance-level
  // error of each period into the drift, so over ~35 periods the bound grows with the periods.
  EXPECT_LT(DirectMiss(far, s.Earliest().delta_psi, s.Earliest().t), kReachTolerance * s.Earliest().periods);
}

TEST(Reach, UnreachableTargetReportsTheClosestApproach) {
  const ReachProblem p = Figure8({40, 0});
  const ReachSummary s = Reach(p);
  EXPECT_EQ(s.status, ReachStatus::kUnreachableWithinHorizon);
  EXPECT_FALSE(s.IsSolutionUsable());
  EXPECT_TRUE(s.solutions.empty());
  EXPECT_THROW(s.Earliest(), std::logic_error);
  const ClosestApproach& c = s.closest_approach;
  EXPECT_GT(c.distance, 1.0);
  EXPECT_LE(c.t, s.horizon);
  // The distance reported is the one at the (s, t) reported (independent integration), and no
  // point of a denser independent scan comes closer.
  EXPECT_NEAR(DirectMiss(p, c.delta_psi, c.t), c.distance, 1e-9);
  double dense_best = 0.0;
  DenseScan(p, 5.0, 512, 64, &dense_best);
  EXPECT_LE(c.distance, dense_best + 1e-9);
  EXPECT_NE(s.BriefReport().find("closest approach"), std::string::npos);
}

TEST(Reach, TooShortHorizonIsAStatusNotAnError) {
  const ReachProblem p = Figure8({6, 0});
  ReachOptions o;
  o.horizon_periods = 0.1;
  const ReachSummary s = Reach(p, o);
  EXPECT_EQ(s.status, ReachStatus::kUnreachableWithinHorizon) << s.BriefReport();
  EXPECT_LE(s.closest_approach.t, 0.1 * s.period + 1e-12);
  // For lambda >= 1 the contact point moves at speed |x'| = |omega| <= sqrt(mu) (eq. (9):
  // mu = |omega x z|^2 + lambda v0^2 >= |omega|^2), so it cannot get closer than
  // |target| - sqrt(mu) * horizon.
  EXPECT_GE(s.closest_approach.distance, 6.0 - 1.0 * 0.1 * s.period - 1e-12);
  EXPECT_NEAR(DirectMiss(p, s.closest_approach.delta_psi, s.closest_approach.t), s.closest_approach.distance, 1e-9);
}

TEST(Reach, RepeatedCallsGiveIdenticalResults) {
  for (const Eigen::Vector2d& target : {Eigen::Vector2d(-12, 5), Eigen::Vector2d(40, 0)}) {
    ReachOptions o;
    const ReachSummary a = Reach(Figure8(target), o);
    const ReachSummary b = Reach(Figure8(target), o);
    ASSERT_EQ(a.solutions.size(), b.solutions.size());
    for (std::size_t k = 0; k < a.solutions.size(); ++k) {
      EXPECT_EQ(a.solutions[k].delta_psi, b.solutions[k].delta_psi);
      EXPECT_EQ(a.solutions[k].t, b.solutions[k].t);
    }
    EXPECT_EQ(a.closest_approach.distance, b.closest_approach.distance);
    EXPECT_EQ(a.closest_approach.delta_psi, b.closest_approach.delta_psi);
    EXPECT_EQ(a.BriefReport(), b.BriefReport());
  }
}

// A stochastic NLopt run (CRS2 draws its population from NLopt's process-global generator):
// its result depends on the generator's state, so it shows whether something reseeded it.
std::vector<double> NloptRandomProbe() {
  nlopt::opt probe(nlopt::GN_CRS2_LM, 2);
  probe.set_lower_bounds(std::vector<double>{-1.0, -1.0});
  probe.set_upper_bounds(std::vector<double>{1.0, 1.0});
  probe.set_min_objective([](unsigned, const double* x, double*, void*) { return std::sin(7 * x[0]) + x[1] * x[1]; },
                          nullptr);
  probe.set_maxeval(40);
  std::vector<double> x{0.3, 0.3};
  double f = 0.0;
  probe.optimize(x, f);
  x.push_back(f);
  return x;
}

TEST(Reach, LeavesNloptsGlobalRandomStateAloneAndDoesNotDependOnIt) {
  // DIRECT-L and BOBYQA are deterministic: Reach must not reseed the process-global generator
  // (it did, with nlopt::srand(seed), on every call; ReachOptions has no seed since), and the
  // generator's state changes nothing.
  nlopt::srand(12345);
  const std::vector<double> undisturbed = NloptRandomProbe();
  nlopt::srand(12345);
  const ReachSummary a = Reach(Figure8({-12, 5}));
  const std::vector<double> after_reach = NloptRandomProbe();
  EXPECT_EQ(undisturbed, after_reach) << "Reach touched NLopt's global random state";
  // Unreachable target too (that path runs BOBYQA).
  nlopt::srand(777);
  const std::vector<double> undisturbed2 = NloptRandomProbe();
  nlopt::srand(777);
  ReachProblem far = Figure8({500, 0});
  ReachOptions short_horizon;
  short_horizon.horizon_periods = 0.5;
  const ReachSummary u = Reach(far, short_horizon);
  ASSERT_EQ(u.status, ReachStatus::kUnreachableWithinHorizon);
  EXPECT_EQ(undisturbed2, NloptRandomProbe()) << "Reach touched NLopt's global random state";
  nlopt::srand(4242);
  const ReachSummary v = Reach(far, short_horizon);
  EXPECT_EQ(u.closest_approach.distance, v.closest_approach.distance);
  EXPECT_EQ(u.closest_approach.delta_psi, v.closest_approach.delta_psi);
  nlopt::srand(31337);
  const ReachSummary b = Reach(Figure8({-12, 5}));
  ASSERT_EQ(a.status, ReachStatus::kSolved);
  EXPECT_EQ(a.BriefReport(), b.BriefReport());
}

TEST(Reach, HugePsiIsReducedOnceAndReachesTheTarget) {
  // Psi = 1e6 said "unreachable" for (6, 0) while psi = 0.1 reaches it at t = 6. With
  // lambda = 1, K = omega_h is constant and |x'|^2 = mu (eq. (9)): the ball rolls straight at
  // speed sqrt(mu), so the earliest arrival at distance 6 is t = 6 / sqrt(mu) whatever psi is.
  for (double psi : {0.1, 1e6, -3.7e9}) {
    ReachProblem p;
    p.model = BallModel::FromLambda(1.0);
    p.start = {1.0, 0.4, psi};
    p.mu = 1.0;
    p.target = {6.0, 0.0};
    const ReachSummary s = Reach(p);
    ASSERT_EQ(s.status, ReachStatus::kSolved) << "psi = " << psi << ": " << s.BriefReport();
    EXPECT_NEAR(s.Earliest().t, 6.0, 1e-9) << psi;
    EXPECT_LT(s.Earliest().residual, 1e-11) << psi;
    // The arrival, recomputed from the reduced angle by an independent direct integration.
    ReachProblem reduced = p;
    reduced.start.psi = std::remainder(psi, 2 * M_PI);
    EXPECT_LT(DirectMiss(reduced, s.Earliest().delta_psi, s.Earliest().t), kReachTolerance) << psi;
  }
}

TEST(Reach, AngleBeyond1e15IsRejectedNamingTheField) {
  for (const char* field : {"theta", "phi", "psi"}) {
    ReachProblem p = Figure8({-12, 5});
    if (std::string(field) == "theta") p.start.theta = 2e15;
    if (std::string(field) == "phi") p.start.phi = -1e16;
    if (std::string(field) == "psi") p.start.psi = 1e300;
    try {
      Reach(p);
      FAIL() << "expected std::invalid_argument for " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("start.") + field + ": value"), std::string::npos) << e.what();
    }
  }
  ReachProblem ok = Figure8({-12, 5});
  ok.start.psi = 1e15;  // at the limit: accepted
  EXPECT_NO_THROW(Reach(ok));
}

TEST(Reach, NegativeThetaIsTheSamePhysicalStateAsItsCanonicalForm) {
  // (theta, phi, psi) ~ (-theta, phi + pi, psi): Figure 8's theta0 = -pi/3, phi0 = pi/2 is the
  // state theta = pi/3, phi = 3 pi/2, and gives the same solutions.
  ReachProblem canonical = Figure8({-12, 5});
  canonical.start = {M_PI / 3, 3 * M_PI / 2, 0.0};
  const ReachSummary a = Reach(Figure8({-12, 5}));
  const ReachSummary b = Reach(canonical);
  ASSERT_EQ(a.solutions.size(), b.solutions.size());
  for (std::size_t k = 0; k < a.solutions.size(); ++k) {
    EXPECT_NEAR(AngleDistance(a.solutions[k].delta_psi, b.solutions[k].delta_psi), 0.0, 1e-9);
    EXPECT_NEAR(a.solutions[k].t, b.solutions[k].t, 1e-9);
  }
}

TEST(Reach, InvalidInputNamesTheField) {
  auto message_of = [](const ReachProblem& p, const ReachOptions& o) -> std::string {
    try {
      Reach(p, o);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no exception";
  };
  ReachProblem p = Figure8({6, 0});
  p.mu = -1;
  EXPECT_NE(message_of(p, {}).find("mu: value -1"), std::string::npos);
  p = Figure8({6, 0});
  p.target.x() = std::nan("");
  EXPECT_NE(message_of(p, {}).find("target[0]: value nan"), std::string::npos);
  p = Figure8({6, 0});
  p.start.theta = INFINITY;
  EXPECT_NE(message_of(p, {}).find("start.theta: value inf"), std::string::npos);
  ReachOptions o;
  o.horizon_periods = 0;
  EXPECT_NE(message_of(Figure8({6, 0}), o).find("horizon_periods"), std::string::npos);
  o = {};
  o.scan_directions = 2;
  EXPECT_NE(message_of(Figure8({6, 0}), o).find("scan_directions"), std::string::npos);
  o = {};
  o.integration.relative_tolerance = -1;
  EXPECT_NE(message_of(Figure8({6, 0}), o).find("relative_tolerance"), std::string::npos);
}

TEST(Reach, TargetAtTheStartIsAStatus) {
  const ReachSummary s = Reach(Figure8({0, 0}));
  EXPECT_EQ(s.status, ReachStatus::kTargetEqualsStart);
  EXPECT_FALSE(s.IsSolutionUsable());
  EXPECT_EQ(s.closest_approach.distance, 0.0);
}

TEST(Reach, TargetVeryCloseToTheStartIsReachedAlongTheVelocityEllipse) {
  // Lemma 2.1's local polar coordinates: a target at distance 1e-9 is reached at t ~ 1e-9 / |x'|
  // with |x'| between the ellipse's semi-axes a(theta) and b = sqrt(mu) ((27)).
  const ReachProblem p = Figure8({1e-9, 0});
  const ReachSummary s = Reach(p);
  ASSERT_EQ(s.status, ReachStatus::kSolved) << s.BriefReport();
  const double a = SemiAxisA(p.start.theta, p.mu, p.model.lambda()), b = std::sqrt(p.mu);
  // The residual is absolute (ReachOptions::tolerance), so t is known to residual / speed.
  const double slack = s.Earliest().residual / std::min(a, b) + 1e-18;
  EXPECT_GE(s.Earliest().t, 1e-9 / std::max(a, b) - slack);
  EXPECT_LE(s.Earliest().t, 1e-9 / std::min(a, b) + slack);
  EXPECT_LT(DirectMiss(p, s.Earliest().delta_psi, s.Earliest().t), kReachTolerance);
}

TEST(Reach, StatusNamesAreStable) {
  EXPECT_EQ(ToString(ReachStatus::kSolved), "solved");
  EXPECT_EQ(ToString(ReachStatus::kUnreachableWithinHorizon), "unreachable_within_horizon");
  EXPECT_EQ(ToString(ReachStatus::kNumericalFailure), "numerical_failure");
  EXPECT_EQ(ToString(ReachStatus::kTargetEqualsStart), "target_equals_start");
}

TEST(Reach, IntegrationStepBoundIsANumericalFailureStatus) {
  ReachOptions o;
  o.integration.max_steps = 3;  // far too few for one period at 1e-12
  const ReachSummary s = Reach(Figure8({6, 0}), o);
  EXPECT_EQ(s.status, ReachStatus::kNumericalFailure);
  EXPECT_NE(s.message.find("max_steps"), std::string::npos);
}

TEST(ReachInternal, ImpulseVelocityIsEqs25To28) {
  const BallModel model = BallModel::FromLambda(2.0);
  const double mu = 1.3;
  for (double theta : {-M_PI / 3, 0.4, 2.5})
    for (double s : {0.0, 0.7, 2.9, 5.1}) {
      const AngleState a{theta, M_PI / 2 + 0.3, 0.2 + s};
      double w[2];
      internal::OmegaHFromAngles(a.theta, a.phi, a.psi, mu, model.lambda(), w);
      // Against eqs. (12)-(18) (PhaseFromAngles): omega = v0 z - u.
      const BallState st = StateFromAngles(a, mu, model);
      EXPECT_NEAR(w[0], st.omega.x(), 1e-14);
      EXPECT_NEAR(w[1], st.omega.y(), 1e-14);
      // (27): |x'|^2 = a^2 cos^2(phi - psi) + b^2 sin^2(phi - psi).
      const double sa = SemiAxisA(theta, mu, model.lambda()), sb = std::sqrt(mu), wv = a.phi - a.psi;
      EXPECT_NEAR(w[0] * w[0] + w[1] * w[1],
                  sa * sa * std::cos(wv) * std::cos(wv) + sb * sb * std::sin(wv) * std::sin(wv),
                  1e-13);
      // (28): |d x'/ds|^2 = a^2 sin^2 + b^2 cos^2, checked with a central difference in psi.
      const double h = 1e-6;
      double wp[2], wm[2];
      internal::OmegaHFromAngles(a.theta, a.phi, a.psi + h, mu, model.lambda(), wp);
      internal::OmegaHFromAngles(a.theta, a.phi, a.psi - h, mu, model.lambda(), wm);
      const Eigen::Vector2d dw((wp[0] - wm[0]) / (2 * h), (wp[1] - wm[1]) / (2 * h));
      EXPECT_NEAR(
          dw.squaredNorm(), sa * sa * std::sin(wv) * std::sin(wv) + sb * sb * std::cos(wv) * std::cos(wv), 1e-8);
    }
}

TEST(ReachInternal, SensitivitiesMatchCentralDifferences) {
  const ReachProblem p = Figure8({0, 0});
  const double lambda = p.model.lambda(), period = 2 * M_PI;
  IntegrationOptions o;
  for (double s : {0.3, 2.0, 4.4})
    for (double t : {0.7, 7.9, 20.3}) {
      const auto d = internal::DirectionFor(p.start, p.mu, lambda, s);
      const internal::TightPoint tp = internal::EvaluateTight(d, lambda, period, t, true, o);
      const double h = 1e-5;
      auto x_at = [&](double ss, double tt) {
        return internal::EvaluateTight(internal::DirectionFor(p.start, p.mu, lambda, ss), lambda, period, tt, false, o)
            .x;
      };
      const Eigen::Vector2d fd_s = (x_at(s + h, t) - x_at(s - h, t)) / (2 * h);
      const Eigen::Vector2d fd_t = (x_at(s, t + h) - x_at(s, t - h)) / (2 * h);
      EXPECT_LT((tp.dx_ds - fd_s).norm(), 1e-6 * std::max(1.0, fd_s.norm()));
      EXPECT_LT((tp.velocity - fd_t).norm(), 1e-6);
      // And the position against the direct integration of the library's free motion.
      EXPECT_LT((p.x0 + tp.x - IntegrateFreeMotion(p.model, StartAfterImpulse(p, s), {t})[0].x).norm(), 1e-10);
    }
}

TEST(ReachPlannerFallback, CoarsePartitionOfALongPathStillGivesAPlan) {
  // The slender ball on a long straight path cut into 3 segments of 14 units: the local join
  // (Lemma 2.1) finds no solution on its local branch for such a segment.
  const ReachProblem start = Slender({0, 0});
  const Path path({SmoothCurve::Line({0, 0}, {30, 30})});
  const PlanProblem problem{
      start.model, start.start, start.mu, Eigen::Matrix3d::Identity(), path, {UniformParameter{3}}, {}};
  PlanOptions local_only;
  local_only.reach_fallback = false;
  const PlanSummary without = PlanImpulses(problem, local_only);
  EXPECT_EQ(without.status, PlanStatus::kSegmentBeyondLocalRadius) << without.BriefReport();

  const PlanSummary plan = PlanImpulses(problem);
  ASSERT_TRUE(plan.IsSolutionUsable()) << plan.BriefReport();
  ASSERT_EQ(plan.steps.size(), 3u);
  int global = 0;
  for (const PlanStep& s : plan.steps) {
    global += s.reached_globally ? 1 : 0;
    // The planner integrates each arc itself (independently of Reach): it passes every point.
    EXPECT_LT(s.pass_miss, kReachTolerance) << "segment " << s.global_index;
  }
  EXPECT_GE(global, 1);
  EXPECT_LE(plan.max_pass_miss, kReachTolerance);
  EXPECT_LE(plan.measured_error, plan.bounds.a_posteriori);
}

TEST(ReachInternal, LockstepTabulationEqualsOneDirectionAtATime) {
  const ReachProblem p = Figure8({0, 0});
  std::vector<internal::ReachDirection> d;
  for (int i = 0; i < 7; ++i) d.push_back(internal::DirectionFor(p.start, p.mu, p.model.lambda(), 0.9 * i));
  std::vector<internal::ScanPeriod> lockstep(d.size());
  internal::TabulatePeriods(d.data(), static_cast<int>(d.size()), p.model.lambda(), 2 * M_PI, 32, lockstep.data());
  for (std::size_t i = 0; i < d.size(); ++i) {
    internal::ScanPeriod one;
    internal::TabulatePeriod(d[i], p.model.lambda(), 2 * M_PI, 32, &one);
    ASSERT_EQ(one.x.size(), lockstep[i].x.size());
    for (std::size_t j = 0; j < one.x.size(); ++j) {
      EXPECT_LT((one.x[j] - lockstep[i].x[j]).norm(), 1e-14);
      EXPECT_LT((one.v[j] - lockstep[i].v[j]).norm(), 1e-14);
    }
    // And the cheap table is close to the tight integration (RK4, 32 steps: ~1e-4 per period).
    const FreeMotion m =
        FreeMotion::FromAngles(p.model, {p.start.theta, p.start.phi, p.start.psi + 0.9 * static_cast<double>(i)}, p.mu);
    EXPECT_LT((one.drift - m.DriftPerPeriod()).norm(), 1e-3);
  }
}
