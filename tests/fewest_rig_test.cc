// The fewest-impulse search under a rig's limits (fewest_impulses.h, "Under a rig's limits"): every
// reached count is re-integrated independently (ReplayExactArrival) and checked against the limits
// by the independent replay (CheckRigLimits: FreeMotion, 64 samples per flight), not by the
// solver's chain.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "plateball/fewest_impulses.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "support/test_support.h"

namespace plateball {
namespace {

constexpr double kPositionTol = 1e-12;  // the arrival tolerances of the search
constexpr double kOrientationTol = 1e-10;

// problems/figure7_fewest.json: (0, 0) -> (3, 3) with the identity, lambda = 2, rolling from the
// vertical axis, stop at the goal. Without limits the fewest is 2 (two straight rolls of 2 pi).
const FewestImpulsesSetup& Figure7() {
  static const FewestImpulsesSetup setup =
      FewestImpulsesSetupFor(ReadProblemFile(plateball::testing::SourcePath("problems/figure7_fewest.json")));
  return setup;
}

const FewestImpulsesSummary& Unlimited() {
  static const FewestImpulsesSummary s = SolveFewestImpulses(Figure7().problem, Figure7().options);
  return s;
}

// The row arrives (by re-integration) and meets the limits (by the independent check, repeated here).
void ExpectReachedWithinLimits(const FewestImpulsesProblem& p, const FewestImpulsesCount& row) {
  ASSERT_TRUE(row.reached) << "n = " << row.impulses;
  const ExactArrivalProblem replay_problem = ReplayProblemFor(p, row.impulses);
  const ReplayResult replay = ReplayExactArrival(replay_problem, row.plan);
  EXPECT_LE(replay.position_error, kPositionTol) << "n = " << row.impulses;
  EXPECT_LE(replay.orientation_error, kOrientationTol) << "n = " << row.impulses;
  ExactArrivalSummary as_arrival;
  as_arrival.impulses = row.plan;
  as_arrival.stop = row.stop;
  const RigCheck check = CheckRigLimits(replay_problem, as_arrival);
  EXPECT_TRUE(check.passed) << "n = " << row.impulses << ": " << (check.violations.empty() ? "" : check.violations[0]);
  ASSERT_TRUE(row.check.has_value());
  EXPECT_TRUE(row.check->passed);
}

TEST(FewestRig, SlackLimitsGiveTheUnlimitedResultBitForBit) {
  FewestImpulsesProblem p = Figure7().problem;
  p.limits.plate = PolygonShape{{{-30, -30}, {30, -30}, {30, 30}, {-30, 30}}};
  p.limits.obstacles = {DiskShape{Eigen::Vector2d(25, -25), 0.5}};
  p.limits.stroke = Eigen::Vector2d(100, 100);
  p.limits.max_plate_velocity_change = 100;
  p.limits.min_interval = 1e-3;
  const FewestImpulsesSummary s = SolveFewestImpulses(p, Figure7().options);
  const FewestImpulsesSummary& free = Unlimited();
  EXPECT_EQ(s.status, free.status);
  EXPECT_EQ(s.message, free.message);
  EXPECT_EQ(s.fewest, free.fewest);
  EXPECT_EQ(s.rollouts, free.rollouts);
  EXPECT_EQ(s.searched, free.searched);
  EXPECT_EQ(s.constrained_solves, 0);
  ASSERT_EQ(s.counts.size(), free.counts.size());
  for (std::size_t i = 0; i < s.counts.size(); ++i) {
    const FewestImpulsesCount &a = s.counts[i], &b = free.counts[i];
    EXPECT_EQ(a.verdict, b.verdict);
    EXPECT_EQ(a.starts, b.starts);
    EXPECT_EQ(a.arrived, b.arrived);
    EXPECT_EQ(a.parameters, b.parameters);  // bit for bit
    EXPECT_EQ(a.total_time, b.total_time);
    EXPECT_EQ(a.path_length, b.path_length);
    EXPECT_EQ(a.total_impulse, b.total_impulse);
    EXPECT_EQ(a.deviation, b.deviation);
    ASSERT_EQ(a.plan.size(), b.plan.size());
    for (std::size_t k = 0; k < a.plan.size(); ++k) {
      EXPECT_EQ(a.plan[k].t_impulse, b.plan[k].t_impulse);
      EXPECT_EQ(a.plan[k].delta_psi, b.plan[k].delta_psi);
      EXPECT_EQ(a.plan[k].duration, b.plan[k].duration);
    }
    if (a.reached) ExpectReachedWithinLimits(p, a);
  }
}

TEST(FewestRig, TheParetoTableAddsTheTotalImpulseAndTheDeviation) {
  const FewestImpulsesSummary& s = Unlimited();
  ASSERT_TRUE(s.IsSolutionUsable());
  const FewestImpulsesCount& two = *s.Fewest();
  ASSERT_EQ(two.impulses, 2);
  // Sum of the plate velocity changes, recomputed from the impulse records (the stop included).
  double sum = two.stop ? two.stop->plate_velocity_change.norm() : 0.0;
  for (const ExactImpulse& e : two.plan) sum += e.plate_velocity_change.norm();
  EXPECT_DOUBLE_EQ(two.total_impulse, sum);
  // Two straight rolls of 2 pi: the one interior impulse point c has |c| = |(3, 3) - c| = 2 pi, so
  // its distance from the midpoint (1.5, 1.5) of the straight line, the deviation, is
  // sqrt(4 pi^2 - 4.5) (closed form).
  constexpr double kClosedFormTol = 1e-9;  // the arrival's 1e-12 and the replayed angles' 1e-10 rad, with margin
  EXPECT_NEAR(two.deviation, std::sqrt(4 * M_PI * M_PI - 4.5), kClosedFormTol);
}

TEST(FewestRig, AnObstacleOnTheFreeAnswerIsPassedAroundWithTheNextCount) {
  FewestImpulsesProblem p = Figure7().problem;
  FewestImpulsesOptions o = Figure7().options;
  o.max_impulses = 3;
  // On the first straight roll of the free answer (0, 0) -> c, c = (-2.68, 5.68): its midpoint.
  p.limits.obstacles = {DiskShape{Eigen::Vector2d(-1.34, 2.84), 0.3}};
  const FewestImpulsesCount& free_two = *Unlimited().Fewest();
  ExactArrivalSummary as_arrival;
  as_arrival.impulses = free_two.plan;
  EXPECT_FALSE(CheckRigLimits(ReplayProblemFor(p, 2), as_arrival).passed);  // the free answer crosses it
  const FewestImpulsesSummary s = SolveFewestImpulses(p, o);
  ASSERT_EQ(s.status, FewestImpulsesStatus::kFound) << s.BriefReport();
  EXPECT_EQ(s.fewest, 3);
  EXPECT_TRUE(s.minimal_for_generic_goal);  // n = 2 < 5/2 conditions: generically impossible
  EXPECT_FALSE(s.counts[1].reached);
  EXPECT_EQ(s.counts[1].verdict, FewestCountVerdict::kGenericallyImpossible);
  EXPECT_EQ(s.counts[1].blocking, std::vector<std::string>{"obstacles[0]"});
  ExpectReachedWithinLimits(p, *s.Fewest());
}

TEST(FewestRig, ImpulseTimesOnATickGridStillArriveExactly) {
  FewestImpulsesProblem p = Figure7().problem;
  FewestImpulsesOptions o = Figure7().options;
  o.max_impulses = 5;
  p.limits.tick = 0.01;
  const FewestImpulsesSummary s = SolveFewestImpulses(p, o);
  ASSERT_EQ(s.status, FewestImpulsesStatus::kFound) << s.BriefReport();
  // With the stop on the grid too, n turns are the only free unknowns: n < 5 reaches no generic goal.
  EXPECT_EQ(s.fewest, 5);
  for (int n = 1; n < 5; ++n)
    EXPECT_EQ(s.counts[static_cast<std::size_t>(n - 1)].verdict, FewestCountVerdict::kGenericallyImpossible);
  const FewestImpulsesCount& row = *s.Fewest();
  ExpectReachedWithinLimits(p, row);
  for (const ExactImpulse& e : row.plan) {
    ASSERT_GE(e.tick, 0);
    EXPECT_EQ(e.t_impulse, static_cast<double>(e.tick) * 0.01);  // exactly on the grid
  }
  ASSERT_TRUE(row.stop.has_value());
  EXPECT_EQ(row.stop->t_impulse, static_cast<double>(row.stop->tick) * 0.01);
}

TEST(FewestRig, LimitsNoArrivalMeetsAreAStatusNamingThem) {
  FewestImpulsesProblem p = Figure7().problem;
  FewestImpulsesOptions o = Figure7().options;
  o.max_impulses = 2;                         // n = 2 arrives without limits (two straight rolls)
  p.limits.max_plate_velocity_change = 0.05;  // the stop alone needs 2 |omega_h|
  const FewestImpulsesSummary s = SolveFewestImpulses(p, o);
  EXPECT_EQ(s.status, FewestImpulsesStatus::kLimitsNotMet);
  EXPECT_FALSE(s.IsSolutionUsable());
  EXPECT_EQ(s.fewest, 0);
  EXPECT_NE(std::find(s.blocking.begin(), s.blocking.end(), "max_plate_velocity_change"), s.blocking.end());
  EXPECT_NE(s.message.find("max_plate_velocity_change"), std::string::npos) << s.message;
  for (const FewestImpulsesCount& c : s.counts) EXPECT_NE(c.verdict, FewestCountVerdict::kReached);
}

}  // namespace
}  // namespace plateball
