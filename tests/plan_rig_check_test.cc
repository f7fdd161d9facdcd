// CheckPlanRigLimits (plan_rig_check.h): a path-following plan against a rig's limits. The check
// replays each flight with FreeMotion; the expectations come from elsewhere: the planner's own
// impulse records (plate velocity changes, flight times, impulse times) and a dense independent
// integration of the trajectory (IntegrateFreeMotion at 2,000 points per flight).
#include "plateball/plan_rig_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "check.h"
#include "plateball/free_motion.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"

namespace plateball {
namespace {

// problems/circle.json: the circle of radius 2 about (-2, 0) from the origin, 64 impulses.
struct CirclePlan {
  PlanSetup setup;
  PlanSummary plan;
};

const CirclePlan& Circle() {
  static const CirclePlan c = [] {
    CirclePlan r;
    r.setup = PlanSetupFor(ReadProblemFile(std::string(PLATEBALL_SOURCE_DIR) + "/problems/circle.json"));
    r.plan = PlanImpulses(r.setup.problem, r.setup.options);
    return r;
  }();
  return c;
}

const Eigen::Vector2d kCentre(-2.0, 0.0);

// The smallest and largest distances from the circle's centre along the impulsive trajectory,
// densely sampled by an independent integrator (the planner's own arcs, as `plan --svg` draws them).
struct Reach {
  double least = INFINITY, most = 0.0;
};
Reach DenseDistances(const CirclePlan& c) {
  Reach r;
  Eigen::Vector2d x = c.setup.problem.path.StartPoint();
  Eigen::Matrix3d a = c.plan.A0;
  for (const PlanStep& s : c.plan.steps) {
    std::vector<double> times;
    for (int i = 0; i <= 2000; ++i) times.push_back(s.duration * i / 2000);
    for (const MotionSample& q : IntegrateFreeMotion(c.setup.problem.model,
                                                     FreeMotionStart{s.impulse.state_after, x, a},
                                                     times,
                                                     IntegrationOptions{1e-12, 1e-12, 2000000})) {
      r.least = std::min(r.least, (q.x - kCentre).norm());
      r.most = std::max(r.most, (q.x - kCentre).norm());
    }
    x = s.x_end;
    a = s.A_impulsive;
  }
  return r;
}

RigLimits PlateAndObstacle(double plate_radius, double obstacle_radius) {
  RigLimits l;
  l.plate = DiskShape{kCentre, plate_radius};
  l.obstacles = {DiskShape{kCentre, obstacle_radius}};
  return l;
}

// The flights bow inwards between the pass points on the circle: the farthest points are the pass
// points (sampled exactly, each flight's last sample), the nearest lie inside the flights.
constexpr double kBowFraction = 1e-3;  // 64 samples find the inward bow's depth to (pi/128)^2/2 of it

TEST(PlanRigCheck, APlateAndAnObstacleClearOfTheTrajectoryAreMetWithTheDenseMargins) {
  const CirclePlan& c = Circle();
  ASSERT_TRUE(c.plan.IsSolutionUsable()) << c.plan.BriefReport();
  const Reach r = DenseDistances(c);
  EXPECT_NEAR(r.most, 2.0, 1e-9) << "the pass points lie on the circle";
  const double bow = 2.0 - r.least;
  EXPECT_GT(bow, 1e-4) << "the flights bow inwards";
  const RigCheck check = CheckPlanRigLimits(c.setup.problem, c.plan, PlateAndObstacle(3.0, 1.5), std::nullopt);
  EXPECT_TRUE(check.passed);
  EXPECT_EQ(check.samples, 64 * static_cast<int>(c.plan.steps.size()));
  EXPECT_NEAR(check.margins.at("plate"), 3.0 - r.most, 1e-9);
  // Sampling sees at most the dense depth of the bow, and nearly all of it.
  EXPECT_GE(check.margins.at("obstacles[0]"), r.least - 1.5 - 1e-12);
  EXPECT_LE(check.margins.at("obstacles[0]"), r.least - 1.5 + kBowFraction * bow);
}

TEST(PlanRigCheck, AnObstacleInsideTheBowIsExceededAtAFlight) {
  const CirclePlan& c = Circle();
  const Reach r = DenseDistances(c);
  const double radius = 2.0 - 0.5 * (2.0 - r.least);  // inside the bow, inside the pass points
  const RigCheck check = CheckPlanRigLimits(c.setup.problem, c.plan, PlateAndObstacle(3.0, radius), std::nullopt);
  EXPECT_FALSE(check.passed);
  ASSERT_EQ(check.violations.size(), 1u);
  EXPECT_EQ(check.violations[0].rfind("obstacles[0] exceeded by ", 0), 0u) << check.violations[0];
  EXPECT_NE(check.violations[0].find(" at flight "), std::string::npos) << check.violations[0];
  EXPECT_NEAR(check.margins.at("obstacles[0]"), r.least - radius, kBowFraction * (2.0 - r.least));
  // The line gives the largest excess (the deepest sample of the bow), not the first sample's.
  EXPECT_NE(
      check.violations[0].find("exceeded by " + internal::FormatNumber(-check.margins.at("obstacles[0]")) + " at"),
      std::string::npos)
      << check.violations[0];
  // A plate smaller than the circle: every pass point is 0.1 outside (to the replay's ~1e-13).
  const RigCheck small = CheckPlanRigLimits(c.setup.problem, c.plan, PlateAndObstacle(1.9, 0.5), std::nullopt);
  ASSERT_EQ(small.violations.size(), 1u);
  EXPECT_EQ(small.violations[0].rfind("plate exceeded by 0.1", 0), 0u) << small.violations[0];
  EXPECT_NEAR(small.margins.at("plate"), -0.1, 1e-9);
}

TEST(PlanRigCheck, ImpulseBoundAndShortestIntervalAgainstThePlannersRecords) {
  const CirclePlan& c = Circle();
  double dv = 0.0, shortest = INFINITY;
  for (std::size_t k = 0; k < c.plan.steps.size(); ++k) {
    dv = std::max(dv, c.plan.steps[k].plate_velocity_change.norm());
    if (k + 1 < c.plan.steps.size()) shortest = std::min(shortest, c.plan.steps[k].duration);
  }
  RigLimits l;
  l.max_plate_velocity_change = 2.0 * dv;
  l.min_interval = 0.5 * shortest;
  RigCheck check = CheckPlanRigLimits(c.setup.problem, c.plan, l, std::nullopt);
  EXPECT_TRUE(check.passed);
  // No energy changes: the actuation is the planner's delta omega (its plate velocity change).
  EXPECT_NEAR(check.margins.at("max_plate_velocity_change"), dv, 1e-12 * dv);
  EXPECT_NEAR(check.margins.at("min_interval"), 0.5 * shortest, 1e-12 * shortest);
  l.max_plate_velocity_change = 0.5 * dv;
  l.min_interval = 1.5 * shortest;
  check = CheckPlanRigLimits(c.setup.problem, c.plan, l, std::nullopt);
  EXPECT_FALSE(check.passed);
  EXPECT_EQ(check.violations.size(), 2u);
  EXPECT_NEAR(check.margins.at("max_plate_velocity_change"), -0.5 * dv, 1e-12 * dv);
  EXPECT_NEAR(check.margins.at("min_interval"), -0.5 * shortest, 1e-12 * shortest);
}

TEST(PlanRigCheck, ImpulseTimesOffTheTickAreExceededExactlyOnItAreMet) {
  const CirclePlan& c = Circle();
  RigLimits l;
  l.tick = 1e-3;  // the planner's times are sums of real flight times: not on a millisecond grid
  RigCheck check = CheckPlanRigLimits(c.setup.problem, c.plan, l, std::nullopt);
  EXPECT_FALSE(check.passed);
  ASSERT_EQ(check.violations.size(), 1u);
  EXPECT_EQ(check.violations[0].rfind("tick exceeded by ", 0), 0u) << check.violations[0];
  // The first impulse is at t = 0, on every grid: a one-impulse plan meets any tick.
  PlanSummary first = c.plan;
  first.steps.resize(1);
  check = CheckPlanRigLimits(c.setup.problem, first, l, std::nullopt);
  EXPECT_TRUE(check.passed) << (check.violations.empty() ? "" : check.violations[0]);
  EXPECT_EQ(check.margins.at("tick"), 0.0);
}

TEST(PlanRigCheck, SlackLimitsArePassedAndBadSamplingIsRefused) {
  const CirclePlan& c = Circle();
  EXPECT_TRUE(CheckPlanRigLimits(c.setup.problem, c.plan, RigLimits{}, std::nullopt).passed);
  EXPECT_THROW(CheckPlanRigLimits(c.setup.problem, c.plan, RigLimits{}, std::nullopt, {}, 0), std::invalid_argument);
}

}  // namespace
}  // namespace plateball
