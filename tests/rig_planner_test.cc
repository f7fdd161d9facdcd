// PlanImpulsesOnRig (rig_planner.h): a path-following plan that honours a rig's limits. The judge
// is the independent check (CheckPlanRigLimits) at a denser sampling than the planner's own, a
// dense integration of the flights (IntegrateFreeMotion, another integrator than the planner's
// arcs), the tick grid compared with == and the plan without limits compared bit for bit.
#include "plateball/rig_planner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "plateball/free_motion.h"
#include "plateball/plan_rig_check.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"

namespace plateball {
namespace {

// tests/data/plan_rig_blocked.json: problems/circle.json's circle (radius 2 about (-2, 0), 64
// impulses) on a rig whose obstacle of radius 1.998 at the centre lies inside the flights' bow
// (they bow inwards to 1.9952 between the pass points).
struct BlockedCircle {
  Problem file;
  PlanSetup setup;
};

const BlockedCircle& Blocked() {
  static const BlockedCircle c = [] {
    BlockedCircle r;
    r.file = ReadProblemFile(std::string(PLATEBALL_SOURCE_DIR) + "/tests/data/plan_rig_blocked.json");
    r.setup = PlanSetupFor(r.file);
    return r;
  }();
  return c;
}

const Eigen::Vector2d kCentre(-2.0, 0.0);
constexpr int kDenseCheckSamples = 512;  // 8 x the planner's default check, 16 x its own sampling
constexpr int kDensePoints = 300;        // per flight for the other integrator: 10 x the planner's sampling
// A pass point is met to the join's tolerance (1e-12 in the problem file) plus the arc's rounding.
constexpr double kPassMiss = 1e-11;
// The replay carries its own contact point over 64 flights: their integration errors add up.
constexpr double kReplayMiss = 1e-9;

bool Contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// The smallest distance from the circle's centre over every flight, densely integrated from each
// impulse's state at the planner's arrival (kDensePoints per flight).
double LeastDistance(const PlanProblem& problem, const PlanSummary& plan) {
  double least = INFINITY;
  Eigen::Vector2d x = problem.path.StartPoint();
  Eigen::Matrix3d a = plan.A0;
  for (const PlanStep& s : plan.steps) {
    std::vector<double> times;
    for (int i = 0; i <= kDensePoints; ++i) times.push_back(s.duration * i / kDensePoints);
    for (const MotionSample& q : IntegrateFreeMotion(problem.model,
                                                     FreeMotionStart{s.impulse.state_after, x, a},
                                                     times,
                                                     IntegrationOptions{1e-12, 1e-12, 2000000}))
      least = std::min(least, (q.x - kCentre).norm());
    x = s.x_end;
    a = s.A_impulsive;
  }
  return least;
}

TEST(RigPlanner, TheObstacleInTheBowIsAvoidedByRefiningThePartition) {
  const BlockedCircle& c = Blocked();
  const PlanSummary unrefined = PlanImpulses(c.setup.problem, c.setup.options);
  ASSERT_FALSE(CheckPlanRigLimits(c.setup.problem, unrefined, c.file.rig, std::nullopt).passed);
  const RigPlanSummary r = PlanImpulsesOnRig(c.setup.problem, c.file.rig, std::nullopt, c.setup.options);
  ASSERT_TRUE(r.IsSolutionUsable()) << r.BriefReport();
  EXPECT_TRUE(r.check.passed);
  EXPECT_TRUE(Contains(r.active, "obstacles[0]"));
  EXPECT_TRUE(r.blocking.empty());
  EXPECT_GE(r.rounds, 1);
  EXPECT_EQ(r.plan.segments, r.segments_initial + r.points_added);
  EXPECT_GT(r.points_added, 0);
  EXPECT_LE(r.plan.max_pass_miss, kPassMiss);
  // Independent of the planner's sampling: the check at 512 samples per flight and a dense
  // integration by another integrator both keep out of the obstacle.
  const RigCheck dense = CheckPlanRigLimits(c.setup.problem, r.plan, c.file.rig, std::nullopt, {}, kDenseCheckSamples);
  EXPECT_TRUE(dense.passed) << (dense.violations.empty() ? "" : dense.violations[0]);
  EXPECT_GT(LeastDistance(c.setup.problem, r.plan), 1.998);
  EXPECT_LT(LeastDistance(c.setup.problem, unrefined), 1.998);
}

TEST(RigPlanner, AFlightOutOfTheStrokeBoxIsRefinedWhereItLeavesIt) {
  // The segment from the origin to (2, 0) with 8 impulses: the flights leave the line sideways; on
  // flight 7 the upper plate's displacement 2 y reaches 0.0045, against a stroke of 1e-3.
  const BlockedCircle& c = Blocked();
  PlanProblem p = c.setup.problem;
  p.path = Path({SmoothCurve::Line(Eigen::Vector2d::Zero(), Eigen::Vector2d(2.0, 0.0))});
  p.partition = {UniformParameter{8}};
  RigLimits l;
  l.stroke = Eigen::Vector2d(100.0, 1e-3);
  ASSERT_FALSE(CheckPlanRigLimits(p, PlanImpulses(p, c.setup.options), l, std::nullopt).passed);
  const RigPlanSummary r = PlanImpulsesOnRig(p, l, std::nullopt, c.setup.options);
  ASSERT_TRUE(r.IsSolutionUsable()) << r.BriefReport();
  EXPECT_EQ(r.active, std::vector<std::string>{"stroke.y"});
  EXPECT_GT(r.points_added, 0);
  EXPECT_LT(r.points_added, 8) << "only the flights that leave the box are bisected";
  const RigCheck dense = CheckPlanRigLimits(p, r.plan, l, std::nullopt, {}, kDenseCheckSamples);
  EXPECT_TRUE(dense.passed) << (dense.violations.empty() ? "" : dense.violations[0]);
}

TEST(RigPlanner, APathThroughAnObstacleIsBlockedNamingTheObstacleAndThePoint) {
  const BlockedCircle& c = Blocked();
  RigLimits l;
  l.obstacles = {DiskShape{Eigen::Vector2d(-2.0, 2.0), 0.25}};  // on the circle's top point p(pi/2)
  const RigPlanSummary r = PlanImpulsesOnRig(c.setup.problem, l, std::nullopt, c.setup.options);
  EXPECT_EQ(r.status, RigPlanStatus::kLimitsNotMet);
  EXPECT_EQ(r.blocking, std::vector<std::string>{"obstacles[0]"});
  EXPECT_NE(r.message.find("the path itself enters obstacles[0] by 0.2499999999999"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("at p(tau = 1.5707963267948966) = (-1.9999999999999998, 2) (piece 0)"), std::string::npos)
      << r.message;
  EXPECT_EQ(r.points_added, 0) << "refinement cannot help a path through an obstacle";
  // A coarse partition (4 segments) and a wall 0.01 thick across the ring at angle 0.3 about the
  // centre, from radius 1.3 to 2.5: every flight round the circle crosses it, and so does the path,
  // which is sampled at least 2000 times (0.0063 apart), not only at the planner's 32 per segment.
  PlanProblem coarse = c.setup.problem;
  coarse.partition = {UniformParameter{4}};
  const Eigen::Vector2d u(std::cos(0.3), std::sin(0.3)), v(-u.y(), u.x());
  l.obstacles = {PolygonShape{{kCentre + 1.3 * u - 0.005 * v,
                               kCentre + 2.5 * u - 0.005 * v,
                               kCentre + 2.5 * u + 0.005 * v,
                               kCentre + 1.3 * u + 0.005 * v}}};
  const RigPlanSummary wall = PlanImpulsesOnRig(coarse, l, std::nullopt, c.setup.options);
  EXPECT_EQ(wall.blocking, std::vector<std::string>{"obstacles[0]"});
  EXPECT_NE(wall.message.find("the path itself enters obstacles[0] by 0.00"), std::string::npos) << wall.message;
  EXPECT_EQ(wall.points_added, 0) << "found on the given partition, before any refinement";
}

TEST(RigPlanner, ThePlanIsJudgedByItsFlightsNotByThePath) {
  // An obstacle of radius 0.01 on the path at p(0.3), with 4 segments: the path crosses it, but the
  // flights, bowing inwards by up to 0.59, pass it: the plan meets the limits and nothing is refined.
  const BlockedCircle& c = Blocked();
  PlanProblem coarse = c.setup.problem;
  coarse.partition = {UniformParameter{4}};
  RigLimits l;
  l.obstacles = {DiskShape{c.setup.problem.path.pieces()[0].Value(0.3), 0.01}};
  const RigPlanSummary r = PlanImpulsesOnRig(coarse, l, std::nullopt, c.setup.options);
  ASSERT_TRUE(r.IsSolutionUsable()) << r.BriefReport();
  EXPECT_EQ(r.points_added, 0);
  EXPECT_TRUE(CheckPlanRigLimits(coarse, r.plan, l, std::nullopt, {}, kDenseCheckSamples).passed);
}

TEST(RigPlanner, ImpulseTimesSlideOntoTheTickAndStillMeetThePartitionPoints) {
  const BlockedCircle& c = Blocked();
  RigLimits l;
  l.tick = 1e-3;  // the control loop at 1 kHz (flights last about 0.26)
  const RigPlanSummary r = PlanImpulsesOnRig(c.setup.problem, l, std::nullopt, c.setup.options);
  ASSERT_TRUE(r.IsSolutionUsable()) << r.BriefReport();
  EXPECT_EQ(r.points_slid, 63) << "every interior point; the ends of the circle stay fixed";
  EXPECT_TRUE(Contains(r.active, "tick"));
  for (const PlanStep& s : r.plan.steps) {
    EXPECT_EQ(s.t_impulse, static_cast<double>(std::llround(s.t_impulse / l.tick)) * l.tick)
        << "impulse " << s.global_index;
    EXPECT_LE(s.pass_miss, kPassMiss) << "impulse " << s.global_index;
    EXPECT_NEAR((s.p_end - kCentre).norm(), 2.0, 1e-12) << "the slid point stays on the path";
  }
  // An independent replay (FreeMotion from each impulse's state, carried from flight to flight)
  // arrives at each slid partition point.
  Eigen::Vector2d x = c.setup.problem.path.StartPoint();
  Eigen::Matrix3d a = r.plan.A0;
  for (const PlanStep& s : r.plan.steps) {
    const MotionSample end =
        FreeMotion(c.setup.problem.model, FreeMotionStart{s.impulse.state_after, x, a}, c.setup.options.integration)
            .At(s.duration);
    x = end.x, a = end.A;
    EXPECT_LE((x - s.p_end).norm(), kReplayMiss) << "impulse " << s.global_index;
  }
  EXPECT_NEAR(r.plan.steps.back().p_end.x(), 0.0, 1e-12) << "the path's end is fixed";
}

// The shortest time between two impulses of `plan` (but the last flight, the check's rule), from
// the impulse times replayed: t_0 + the sum of the flights before, independent of t_impulse.
double ShortestInterval(const PlanSummary& plan) {
  double t = plan.steps.front().t_impulse, least = INFINITY;
  for (std::size_t k = 0; k + 1 < plan.steps.size(); ++k) {
    const double next = t + plan.steps[k].duration;
    least = std::min(least, next - t);
    EXPECT_NEAR(plan.steps[k + 1].t_impulse, next, 1e-12) << "impulse " << k + 1;
    t = next;
  }
  return least;
}

TEST(RigPlanner, ATickCoarserThanTheFlightsIsBlockingWithoutCoarsening) {
  // Flights of about 0.257 on a grid of 0.3: the drift of the arrivals grows until a multiple lies
  // beyond the next partition point's arrival, where the point cannot slide (max_rounds = 0: the
  // partition is neither refined nor coarsened).
  const BlockedCircle& c = Blocked();
  RigLimits l;
  l.tick = 0.3;
  RigPlanOptions fixed;
  fixed.max_rounds = 0;
  const RigPlanSummary r = PlanImpulsesOnRig(c.setup.problem, l, std::nullopt, c.setup.options, fixed);
  EXPECT_EQ(r.status, RigPlanStatus::kLimitsNotMet);
  EXPECT_EQ(r.blocking, std::vector<std::string>{"tick"});
  EXPECT_NE(r.message.find("lies beyond the arrival at the next partition point"), std::string::npos) << r.message;
  EXPECT_LT(r.points_slid, 63);
  EXPECT_EQ(r.points_removed, 0);
  EXPECT_LT(r.check.margins.at("tick"), 0.0);
}

TEST(RigPlanner, ATickCoarserThanTheFlightsMergesThem) {
  // The same grid of 0.3 with coarsening: the points the grid cannot place are removed (their
  // flights merge with the next) until every impulse lands on the grid.
  const BlockedCircle& c = Blocked();
  RigLimits l;
  l.tick = 0.3;
  const RigPlanSummary r = PlanImpulsesOnRig(c.setup.problem, l, std::nullopt, c.setup.options);
  ASSERT_TRUE(r.IsSolutionUsable()) << r.BriefReport();
  EXPECT_GT(r.points_removed, 0);
  EXPECT_EQ(r.plan.segments, 64 - r.points_removed);
  EXPECT_TRUE(Contains(r.active, "tick"));
  const RigCheck dense =
      CheckPlanRigLimits(c.setup.problem, r.plan, l, std::nullopt, RigCheckTolerances{}, kDenseCheckSamples);
  EXPECT_TRUE(dense.passed) << dense.violations.front();
  for (const PlanStep& s : r.plan.steps) {
    EXPECT_EQ(s.t_impulse, static_cast<double>(std::llround(s.t_impulse / l.tick)) * l.tick) << s.global_index;
    EXPECT_LE(s.pass_miss, kPassMiss) << "impulse " << s.global_index;
  }
  EXPECT_GE(ShortestInterval(r.plan), l.tick * (1 - 1e-9)) << "two impulses on one tick";
}

TEST(RigPlanner, AShortestIntervalLongerThanTheFlightsMergesThem) {
  // Flights of about 0.257 and a shortest interval of 0.3: every other interior point is removed
  // (32 flights of about 0.515). The merged flights bow to about 1.981 from the centre: the plate
  // of radius 3 and the obstacle of radius 1.5 stay clear (a dense integration measures it).
  const BlockedCircle& c = Blocked();
  RigLimits l;
  l.plate = DiskShape{kCentre, 3.0};
  l.obstacles = {DiskShape{kCentre, 1.5}};
  l.min_interval = 0.3;
  ASSERT_FALSE(
      CheckPlanRigLimits(c.setup.problem, PlanImpulses(c.setup.problem, c.setup.options), l, std::nullopt).passed);
  const RigPlanSummary r = PlanImpulsesOnRig(c.setup.problem, l, std::nullopt, c.setup.options);
  ASSERT_TRUE(r.IsSolutionUsable()) << r.BriefReport();
  EXPECT_EQ(r.points_removed, 32);
  EXPECT_EQ(r.plan.segments, 32);
  EXPECT_EQ(r.active, std::vector<std::string>{"min_interval"});
  const RigCheck dense =
      CheckPlanRigLimits(c.setup.problem, r.plan, l, std::nullopt, RigCheckTolerances{}, kDenseCheckSamples);
  EXPECT_TRUE(dense.passed) << dense.violations.front();
  EXPECT_GE(ShortestInterval(r.plan), l.min_interval);
  const double least = LeastDistance(c.setup.problem, r.plan);
  EXPECT_GT(least, 1.5);
  EXPECT_LT(least, 1.99) << "the merged flights bow deeper than the 64 flights' 1.9952";
  for (const PlanStep& s : r.plan.steps) EXPECT_LE(s.pass_miss, kPassMiss) << "impulse " << s.global_index;
}

TEST(RigPlanner, AMergeWhoseFlightWouldEnterAnObstacleKeepsItsPoint) {
  // An obstacle of radius 1.99: the 64 flights (bow 1.9952) pass it, the merged 32 (bow 1.981)
  // would enter it, so no flight may merge and the shortest interval blocks.
  const BlockedCircle& c = Blocked();
  RigLimits l;
  l.obstacles = {DiskShape{kCentre, 1.99}};
  l.min_interval = 0.3;
  const RigPlanSummary r = PlanImpulsesOnRig(c.setup.problem, l, std::nullopt, c.setup.options);
  EXPECT_EQ(r.status, RigPlanStatus::kLimitsNotMet);
  EXPECT_EQ(r.points_removed, 0);
  EXPECT_EQ(r.plan.segments, 64);
  EXPECT_EQ(r.blocking, std::vector<std::string>{"min_interval"}) << r.message;
  EXPECT_NE(r.message.find("the merged flight enters obstacles[0]"), std::string::npos) << r.message;
  EXPECT_GE(r.check.margins.at("obstacles[0]"), 0.0) << "the obstacle is still avoided";
}

TEST(RigPlanner, PassPointsOnThePlatesEdgeAreMetWithoutRefinement) {
  // The flights bow inwards, so a plate of the circle's own radius is touched at the pass points
  // only (to the joins' 1e-13), within the check's tolerance.
  const BlockedCircle& c = Blocked();
  RigLimits l;
  l.plate = DiskShape{kCentre, 2.0};
  const RigPlanSummary r = PlanImpulsesOnRig(c.setup.problem, l, std::nullopt, c.setup.options);
  ASSERT_TRUE(r.IsSolutionUsable()) << r.BriefReport();
  EXPECT_EQ(r.points_added, 0);
  EXPECT_LE(std::abs(r.check.margins.at("plate")), RigCheckTolerances{}.position);
}

TEST(RigPlanner, AnImpulseAtAJunctionOfPiecesCannotSlideOntoTheTick) {
  // problems/piecewise.json: a line, a half circle and a sine wave, 16 impulses each. The interior
  // points slide; the two junctions are fixed points of the path and are named.
  const PlanSetup setup = PlanSetupFor(ReadProblemFile(std::string(PLATEBALL_SOURCE_DIR) + "/problems/piecewise.json"));
  RigLimits l;
  l.tick = 1e-3;
  const RigPlanSummary r = PlanImpulsesOnRig(setup.problem, l, std::nullopt, setup.options);
  EXPECT_EQ(r.status, RigPlanStatus::kLimitsNotMet);
  EXPECT_EQ(r.blocking, std::vector<std::string>{"tick"});
  EXPECT_EQ(r.points_slid, 3 * 15);
  EXPECT_NE(r.message.find("the impulse at the junction of pieces 0 and 1"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("the impulse at the junction of pieces 1 and 2"), std::string::npos) << r.message;
  for (const PlanStep& s : r.plan.steps)
    if (s.index > 0) {
      EXPECT_EQ(s.t_impulse, static_cast<double>(std::llround(s.t_impulse / l.tick)) * l.tick) << s.global_index;
    }
}

TEST(RigPlanner, SlackLimitsLeaveThePlanBitForBit) {
  const BlockedCircle& c = Blocked();
  RigLimits l;
  l.plate = DiskShape{kCentre, 3.0};
  l.obstacles = {DiskShape{kCentre, 1.5}};
  l.max_plate_velocity_change = 4.0;
  l.min_interval = 0.01;
  const PlanSummary free = PlanImpulses(c.setup.problem, c.setup.options);
  const RigPlanSummary r = PlanImpulsesOnRig(c.setup.problem, l, std::nullopt, c.setup.options);
  ASSERT_TRUE(r.IsSolutionUsable()) << r.BriefReport();
  EXPECT_TRUE(r.active.empty());
  EXPECT_EQ(r.points_added, 0);
  ASSERT_EQ(r.plan.steps.size(), free.steps.size());
  for (std::size_t k = 0; k < free.steps.size(); ++k) {
    const PlanStep &a = r.plan.steps[k], &b = free.steps[k];
    EXPECT_EQ(a.tau_end, b.tau_end);
    EXPECT_EQ(a.t_impulse, b.t_impulse);
    EXPECT_EQ(a.duration, b.duration);
    EXPECT_EQ(a.delta_psi, b.delta_psi);
    EXPECT_EQ(a.delta_omega, b.delta_omega);
    EXPECT_EQ(a.x_end, b.x_end);
    EXPECT_EQ(a.A_impulsive, b.A_impulsive);
  }
  EXPECT_EQ(r.plan.measured_error, free.measured_error);
  EXPECT_EQ(r.plan.bounds.a_posteriori, free.bounds.a_posteriori);
}

TEST(RigPlanner, LimitsThePartitionCannotChangeAreReportedByName) {
  const BlockedCircle& c = Blocked();
  // Bisecting the flights of about 0.26 would make them shorter than the shortest interval.
  RigLimits l = c.file.rig;
  l.min_interval = 0.2;
  RigPlanSummary r = PlanImpulsesOnRig(c.setup.problem, l, std::nullopt, c.setup.options);
  EXPECT_EQ(r.status, RigPlanStatus::kLimitsNotMet);
  EXPECT_TRUE(Contains(r.blocking, "min_interval")) << r.message;
  EXPECT_NE(r.message.find("shorter than min_interval 0.2"), std::string::npos) << r.message;
  // The first impulse turns the initial motion onto the circle with a plate velocity change of 3.1.
  l = c.file.rig;
  l.max_plate_velocity_change = 2.0;
  r = PlanImpulsesOnRig(c.setup.problem, l, std::nullopt, c.setup.options);
  EXPECT_EQ(r.status, RigPlanStatus::kLimitsNotMet);
  EXPECT_EQ(r.blocking, std::vector<std::string>{"max_plate_velocity_change"}) << r.message;
  EXPECT_TRUE(r.check.margins.at("obstacles[0]") >= 0) << "the obstacle is still avoided";
  // A refinement budget too small for the bow.
  RigPlanOptions tight;
  tight.max_added_points = 3;
  r = PlanImpulsesOnRig(c.setup.problem, c.file.rig, std::nullopt, c.setup.options, tight);
  EXPECT_EQ(r.status, RigPlanStatus::kLimitsNotMet);
  EXPECT_TRUE(Contains(r.blocking, "obstacles[0]")) << r.message;
  EXPECT_NE(r.message.find("max_added_points 3"), std::string::npos) << r.message;
}

TEST(RigPlanner, EnergyChangesKeepTheirPartitionPointsThroughTheRefinement) {
  const BlockedCircle& c = Blocked();
  PlanProblem p = c.setup.problem;
  p.energy_changes = {{32, 1.1}};  // at p(pi), the circle's far point
  const RigPlanSummary r = PlanImpulsesOnRig(p, c.file.rig, std::nullopt, c.setup.options);
  ASSERT_TRUE(r.IsSolutionUsable()) << r.BriefReport();
  int at = -1;
  for (const PlanStep& s : r.plan.steps)
    if (!s.energy_changes.empty()) at = s.global_index;
  ASSERT_GE(at, 0);
  EXPECT_NEAR(r.plan.steps[static_cast<std::size_t>(at)].tau_begin, M_PI, 1e-15);
  EXPECT_NEAR(r.plan.mu_final, 1.1 * 1.1 * c.setup.problem.mu, 1e-12);
}

TEST(RigPlanner, InvalidOptionsAreRefusedNamingTheField) {
  const BlockedCircle& c = Blocked();
  RigPlanOptions o;
  o.samples_per_flight = 1;
  try {
    PlanImpulsesOnRig(c.setup.problem, c.file.rig, std::nullopt, c.setup.options, o);
    FAIL() << "accepted samples_per_flight = 1";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("samples_per_flight: value 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plateball
