// Exact arrival under a rig's limits (rig_limits.h): every result is checked by the independent
// replay (CheckRigLimits: FreeMotion sampled 64 times per arc, J by PlateImpulseFor) and by the
// arrival replay (ReplayExactArrival), not by the solver's own chain.
#include "plateball/rig_limits.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "plateball/exact_arrival.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/plate_impulse.h"
#include "plateball/problem_io.h"
#include "plateball/rig_reference.h"
#include "plateball/task_adapters.h"
#include "support/figure7_exact.h"
#include "support/test_support.h"

namespace plateball {
namespace {

constexpr double kPositionTol = 1e-12;  // the arrival tolerances of exact arrival
constexpr double kOrientationTol = 1e-10;

// Figure 7 (problems/figure7.json) along its shortest isoparallel path (tests/support).
const ExactArrivalProblem& Figure7() { return plateball::testing::Figure7ExactArrival(); }

const ExactArrivalSummary& FreeOptimum() {
  static const ExactArrivalSummary s = SolveExactArrival(Figure7());
  return s;
}

// Arrives (by independent re-integration) and meets every limit (by the independent check).
void ExpectArrivesWithinLimits(const ExactArrivalProblem& p, const ExactArrivalSummary& s) {
  ASSERT_EQ(s.status, ExactArrivalStatus::kArrived) << s.BriefReport();
  const ReplayResult replay = ReplayExactArrival(p, s.impulses);
  EXPECT_LE(replay.position_error, kPositionTol);
  EXPECT_LE(replay.orientation_error, kOrientationTol);
  const RigCheck check = CheckRigLimits(p, s);
  EXPECT_TRUE(check.passed) << (check.violations.empty() ? "" : check.violations.front());
  EXPECT_EQ(check.samples, 64 * p.impulses);
}

double SumPlateVelocityChange(const ExactArrivalSummary& s) {
  double sum = 0.0;
  for (const ExactImpulse& e : s.impulses) sum += e.plate_velocity_change.norm();
  return sum;
}

TEST(RigLimits, TheFreeOptimumLeavesTheDiskPlateAndTheConstrainedArrivalStaysOn) {
  ExactArrivalProblem p = Figure7();
  p.limits.plate = DiskShape{Eigen::Vector2d(1.5, 1.5), 3.0};
  EXPECT_FALSE(CheckRigLimits(p, FreeOptimum()).passed);  // the limit cuts the free optimum
  const ExactArrivalSummary s = SolveExactArrival(p);
  ExpectArrivesWithinLimits(p, s);
  EXPECT_TRUE(s.limits.constrained);
  EXPECT_EQ(s.limits.active, std::vector<std::string>{"plate"});
  EXPECT_GT(s.deviation, FreeOptimum().deviation);  // the limit costs deviation
}

TEST(RigLimits, AnObstacleOnTheFreeOptimumIsPassedAroundAndItsCostGrowsWithItsRadius) {
  ExactArrivalProblem p = Figure7();
  double previous = FreeOptimum().deviation;
  for (double radius : {0.1, 0.2, 0.3}) {
    p.limits.obstacles = {DiskShape{Eigen::Vector2d(0.0, 1.45), radius}};
    EXPECT_FALSE(CheckRigLimits(p, FreeOptimum()).passed) << radius;  // the free optimum crosses it
    const ExactArrivalSummary s = SolveExactArrival(p);
    ExpectArrivesWithinLimits(p, s);
    EXPECT_EQ(s.limits.active, std::vector<std::string>{"obstacles[0]"});
    EXPECT_GT(s.deviation, previous) << radius;
    previous = s.deviation;
  }
}

TEST(RigLimits, SlackLimitsChangeNothing) {
  ExactArrivalProblem p = Figure7();
  p.limits.plate = PolygonShape{{{-10, -10}, {10, -10}, {10, 10}, {-10, 10}}};
  p.limits.obstacles = {DiskShape{Eigen::Vector2d(8, -8), 0.5}};
  p.limits.stroke = Eigen::Vector2d(30, 30);
  p.limits.max_plate_velocity_change = 100;
  p.limits.min_interval = 0.1;
  const ExactArrivalSummary s = SolveExactArrival(p);
  const ExactArrivalSummary& free = FreeOptimum();
  EXPECT_FALSE(s.limits.constrained);
  ASSERT_EQ(s.impulses.size(), free.impulses.size());
  for (std::size_t k = 0; k < s.impulses.size(); ++k) {  // bit for bit
    EXPECT_EQ(s.impulses[k].delta_psi, free.impulses[k].delta_psi);
    EXPECT_EQ(s.impulses[k].duration, free.impulses[k].duration);
  }
  EXPECT_EQ(s.deviation, free.deviation);
  EXPECT_TRUE(CheckRigLimits(p, s).passed);
}

TEST(RigLimits, ImpulseTimesOnATickGridStillArriveExactly) {
  ExactArrivalProblem p = Figure7();
  p.limits.tick = 0.01;
  const ExactArrivalSummary s = SolveExactArrival(p);
  ExpectArrivesWithinLimits(p, s);
  for (const ExactImpulse& e : s.impulses) {
    ASSERT_GE(e.tick, 0);
    EXPECT_EQ(e.t_impulse, static_cast<double>(e.tick) * 0.01);  // exactly on the grid
  }
  // The grid moved the times: the free optimum's first flight 0.788545... is not a multiple of 0.01.
  EXPECT_NE(s.impulses[1].t_impulse, FreeOptimum().impulses[1].t_impulse);
}

TEST(RigLimits, TheGridHoldsAtAnotherEnergy) {
  ExactArrivalProblem p = Figure7();
  p.mu = 2.0;
  p.limits.tick = 0.005;
  p.limits.min_interval = 0.6;  // the free optimum's shortest flight at mu = 2 is 0.5576
  const ExactArrivalSummary s = SolveExactArrival(p);
  ExpectArrivesWithinLimits(p, s);
  for (std::size_t k = 0; k + 1 < s.impulses.size(); ++k) EXPECT_GE(s.impulses[k].duration, 0.6 * (1 - 1e-12));
}

TEST(RigLimits, TheShortestIntervalAndThePlateVelocityBoundAreMetAndReportedActive) {
  ExactArrivalProblem p = Figure7();
  double largest = 0.0;
  for (const ExactImpulse& e : FreeOptimum().impulses) largest = std::max(largest, e.plate_velocity_change.norm());
  p.limits.max_plate_velocity_change = 0.8 * largest;
  p.limits.min_interval = 0.85;  // the free optimum's shortest flight is 0.7885
  const ExactArrivalSummary s = SolveExactArrival(p);
  ExpectArrivesWithinLimits(p, s);
  EXPECT_NE(std::find(s.limits.active.begin(), s.limits.active.end(), "max_plate_velocity_change"),
            s.limits.active.end());
  EXPECT_NE(std::find(s.limits.active.begin(), s.limits.active.end(), "min_interval"), s.limits.active.end());
}

TEST(RigLimits, ThePlateImpulseBoundUsesTheEffectiveMassOfBallAndPlate) {
  ExactArrivalProblem p = Figure7();
  // A physical ball of the same lambda = 2 is not rigid; the bound only needs the masses.
  p.physical = PhysicalParameters{1.0, 1.0, 2.0, 1.0, 0.5};
  double largest = 0.0;  // the free optimum's largest |J|, from its replayed axis and delta omega
  for (const ExactImpulse& e : FreeOptimum().impulses)
    largest = std::max(
        largest,
        PlateImpulseFor(*p.physical, StateFromAngles(e.angles_before, p.mu, p.model).z, e.delta_omega).plate.norm());
  p.limits.max_plate_impulse = 0.8 * largest;
  const ExactArrivalSummary s = SolveExactArrival(p);
  ExpectArrivesWithinLimits(p, s);
  const RigCheck check = CheckRigLimits(p, s);
  ASSERT_EQ(check.margins.count("max_plate_impulse"), 1u);
  EXPECT_GE(check.margins.at("max_plate_impulse"), -1e-9);
}

TEST(RigLimits, TheObjectivesTradeTimeAndImpulseAgainstDeviation) {
  ExactArrivalProblem p = Figure7();
  p.limits.plate = DiskShape{Eigen::Vector2d(1.5, 1.5), 3.0};
  const ExactArrivalSummary by_deviation = SolveExactArrival(p);
  p.objective = ArrivalObjective::kTotalTime;
  const ExactArrivalSummary by_time = SolveExactArrival(p);
  ExpectArrivesWithinLimits(p, by_time);
  EXPECT_LT(by_time.total_time, by_deviation.total_time);
  p.objective = ArrivalObjective::kTotalImpulse;
  const ExactArrivalSummary by_impulse = SolveExactArrival(p);
  ExpectArrivesWithinLimits(p, by_impulse);
  EXPECT_LT(SumPlateVelocityChange(by_impulse), SumPlateVelocityChange(by_deviation));
}

TEST(RigLimits, LimitsThatCannotBeMetAreAStatusNamingThem) {
  ExactArrivalProblem p = Figure7();
  p.limits.max_plate_velocity_change = 0.05;  // the free optimum needs up to 1.9
  const ExactArrivalSummary s = SolveExactArrival(p);
  EXPECT_EQ(s.status, ExactArrivalStatus::kLimitsNotMet);
  EXPECT_FALSE(s.IsSolutionUsable());
  EXPECT_NE(std::find(s.limits.blocking.begin(), s.limits.blocking.end(), "max_plate_velocity_change"),
            s.limits.blocking.end());
  EXPECT_NE(s.message.find("max_plate_velocity_change"), std::string::npos) << s.message;
  // The closest arrival reported meets the limits.
  const RigCheck check = CheckRigLimits(p, s);
  EXPECT_TRUE(check.passed) << (check.violations.empty() ? "" : check.violations.front());
  EXPECT_GT(s.position_error + s.orientation_error, 1e-6);
}

TEST(RigLimits, BadLimitsNameTheField) {
  ExactArrivalProblem p = Figure7();
  const auto message = [&](const ExactArrivalProblem& q) {
    try {
      SolveExactArrival(q);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  ExactArrivalProblem q = p;
  q.limits.plate = DiskShape{Eigen::Vector2d(0, 0), -1.0};
  EXPECT_NE(message(q).find("rig.plate.radius: value -1"), std::string::npos) << message(q);
  q = p;
  q.limits.obstacles = {DiskShape{Eigen::Vector2d(3, 3), 0.5}};
  EXPECT_NE(message(q).find("x1: value (3, 3): lies inside rig.obstacles[0]"), std::string::npos) << message(q);
  q = p;
  q.limits.max_plate_impulse = 2.0;
  EXPECT_NE(message(q).find("rig.max_plate_impulse: value 2: needs ball.physical"), std::string::npos) << message(q);
  q = p;
  q.limits.stroke = Eigen::Vector2d(1.0, 10.0);
  EXPECT_NE(message(q).find("beyond rig.stroke"), std::string::npos) << message(q);
  q = p;
  q.impulses = 3;
  q.limits.tick = 0.01;
  EXPECT_NE(message(q).find("rig.tick: value 0.01: fixes the impulse times"), std::string::npos) << message(q);
}

const IsoparallelSummary& Figure7Solutions() { return plateball::testing::Figure7Isoparallel(); }

// The farthest point of a path from c, by 20000 samples per piece (not PathLimitBreaks' 2000).
double FarthestFrom(const Path& path, const Eigen::Vector2d& c) {
  double far = 0.0;
  for (const SmoothCurve& piece : path.pieces())
    for (int i = 0; i <= 20000; ++i)
      far = std::max(far, (piece.Value(piece.Begin() + (piece.End() - piece.Begin()) * i / 20000.0) - c).norm());
  return far;
}

TEST(RigReference, TheShortestIsoparallelPathIsKeptWhenItMeetsTheLimitsAndReportedWhenNot) {
  const IsoparallelSummary& solved = Figure7Solutions();
  ASSERT_TRUE(solved.IsSolutionUsable());
  const Eigen::Vector2d c(1.5, 1.5);
  const double far = FarthestFrom(OptimalPath(solved.Shortest()), c);  // 3.69 (the free optimum's reach)
  RigLimits roomy;
  roomy.plate = DiskShape{c, far + 0.01};
  ReferenceChoice choice = ChooseIsoparallelReference(solved, roomy, Eigen::Vector2d::Zero());
  EXPECT_EQ(choice.index, 0u);
  EXPECT_TRUE(choice.shortest_breaks.empty());
  RigLimits tight;
  tight.plate = DiskShape{c, far - 0.01};
  choice = ChooseIsoparallelReference(solved, tight, Eigen::Vector2d::Zero());
  EXPECT_EQ(choice.shortest_breaks, std::vector<std::string>{"plate"});
  if (choice.index > 0) {  // a longer solution inside: it really is inside, and no shorter one is
    EXPECT_TRUE(choice.chosen_breaks.empty());
    EXPECT_LT(FarthestFrom(OptimalPath(solved.solutions[choice.index]), c), far - 0.01);
    for (std::size_t k = 0; k < choice.index; ++k)
      EXPECT_GT(FarthestFrom(OptimalPath(solved.solutions[k]), c), far - 0.01 - 1e-6) << k;
  } else {  // none inside: every solution leaves the plate
    for (const IsoparallelSolution& sol : solved.solutions)
      EXPECT_GT(FarthestFrom(OptimalPath(sol), c), far - 0.01 - 1e-6);
  }
}

TEST(RigLimits, SignedDistancesOfTheShapes) {
  const PlateShape disk = DiskShape{Eigen::Vector2d(1, 1), 2};
  Eigen::Vector2d g;
  EXPECT_DOUBLE_EQ(SignedDistanceInside(disk, Eigen::Vector2d(1, 2), &g), 1.0);
  EXPECT_TRUE(g.isApprox(Eigen::Vector2d(0, -1)));
  const PlateShape square = PolygonShape{{{0, 0}, {0, 2}, {2, 2}, {2, 0}}};  // clockwise
  EXPECT_DOUBLE_EQ(SignedDistanceInside(square, Eigen::Vector2d(0.5, 1), &g), 0.5);
  EXPECT_TRUE(g.isApprox(Eigen::Vector2d(1, 0)));
  EXPECT_DOUBLE_EQ(SignedDistanceInside(square, Eigen::Vector2d(3, 3)), -std::sqrt(2.0));
  // The gradient is the derivative (central differences away from the medial axis).
  const Eigen::Vector2d x(0.3, 1.4), h(1e-6, 0), k(0, 1e-6);
  SignedDistanceInside(square, x, &g);
  EXPECT_NEAR(g.x(), (SignedDistanceInside(square, x + h) - SignedDistanceInside(square, x - h)) / 2e-6, 1e-8);
  EXPECT_NEAR(g.y(), (SignedDistanceInside(square, x + k) - SignedDistanceInside(square, x - k)) / 2e-6, 1e-8);
}

}  // namespace
}  // namespace plateball
