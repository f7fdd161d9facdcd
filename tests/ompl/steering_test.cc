// Exact steering for OMPL: a control-based RRT with plateball's exact steering plans around a disk,
// and every connection is checked independently of the planner: re-integrated by ReplayExactArrival,
// the whole impulse sequence re-integrated from the start, and the motion sampled densely by
// FreeMotion for the clearance from the disk. steer() reports failure for a state and itself, a
// target it cannot reach, a target inside the obstacle, a motion through it and a non-finite target.
#include "plateball/ompl/steering.h"

#include <gtest/gtest.h>
#include <ompl/base/PlannerStatus.h>
#include <ompl/base/ScopedState.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/SimpleSetup.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cmath>
#include <limits>

#include "plateball/impulse.h"
#include "plateball/so3.h"

namespace plateball::ompl_steering {
namespace {

namespace ob = ompl::base;
namespace oc = ompl::control;

// The independent re-integration (tolerance 1e-14) against the solver's 1e-12 arrival.
constexpr double kArrivalTolerance = 1e-9;
// Dense clearance check: this many FreeMotion samples per arc (arcs are < 3 time units long and
// the contact speed is < 1.5, so consecutive samples are < 0.01 apart, half the steering's spacing).
constexpr int kDenseSamplesPerArc = 500;
const Eigen::Vector2d kDiskCentre(3.0, 0.0);
constexpr double kDiskRadius = 1.5;

double Clearance(const Eigen::Vector2d& x) { return (x - kDiskCentre).norm() - kDiskRadius; }

// OMPL takes its seed before the first random number generator exists: set it before main, so that
// the plan is the example's whatever order the tests run in.
const bool kSeeded = [] {
  ompl::RNG::setSeed(7);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  return true;
}();

struct Planned {
  std::shared_ptr<oc::SimpleSetup> setup;
  std::shared_ptr<ExactSteeringPropagator> steering;
  ob::PlannerStatus status;
  Eigen::Vector2d goal_x;
  Eigen::Matrix3d goal_A;
};

// The problem of examples/ompl/plan_around_disk.cc with its seed.
const Planned& PlanAroundDisk() {
  static const Planned planned = [] {
    EXPECT_TRUE(kSeeded);
    Planned p;
    const ob::StateSpacePtr space = MakeBallStateSpace({-3.0, -5.0}, {9.0, 5.0});
    p.setup = std::make_shared<oc::SimpleSetup>(MakeTargetControlSpace(space));
    p.steering = UseExactSteering(p.setup->getSpaceInformation(), SteeringOptions{});
    p.setup->setStateValidityChecker([](const ob::State* s) { return Clearance(ContactPoint(s)) > 0.0; });
    ob::ScopedState<> start(space), goal(space);
    SetConfiguration(start.get(), {0.0, 0.0}, ExpSO3({0.6, 0.2, 0.0}));
    p.goal_x = {6.0, 0.0};
    p.goal_A = ExpSO3({-0.4, 0.5, 0.3});
    SetConfiguration(goal.get(), p.goal_x, p.goal_A);
    p.setup->setStartAndGoalStates(start, goal, 1e-6);
    auto rrt = std::make_shared<oc::RRT>(p.setup->getSpaceInformation());
    rrt->setGoalBias(0.2);
    p.setup->setPlanner(rrt);
    p.status = p.setup->solve(120.0);
    return p;
  }();
  return planned;
}

std::vector<Connection> Connections(const Planned& p) {
  const oc::PathControl& path = p.setup->getSolutionPath();
  std::vector<Connection> out;
  for (std::size_t i = 0; i < path.getControlCount(); ++i) {
    const oc::Control* u = path.getControl(i);
    out.push_back(p.steering->ConnectTo(path.getState(i), TargetPoint(u), TargetOrientation(u)));
  }
  return out;
}

// Smallest clearance over kDenseSamplesPerArc samples per arc, integrated here arc by arc from the
// connection's start (EnergyPreservingImpulse + FreeMotion with the library's default tolerances).
double DenseClearance(const Connection& c) {
  const ExactArrivalProblem& p = c.problem;
  BallState state = StateFromAngles(p.initial, p.mu, p.model);
  Eigen::Vector2d x = p.x0;
  Eigen::Matrix3d A = AlignOrientationToAxis(p.A0, state.z);
  double smallest = INFINITY;
  for (const ExactImpulse& e : c.summary.impulses) {
    const Impulse imp = EnergyPreservingImpulse(AnglesFromState(state, p.model), p.mu, e.delta_psi, p.model);
    const FreeMotion motion(p.model, FreeMotionStart{imp.state_after, x, A});
    for (const MotionSample& s : motion.Sample(0.0, e.duration, kDenseSamplesPerArc))
      smallest = std::min(smallest, Clearance(s.x));
    const MotionSample end = motion.At(e.duration);
    state = end.state;
    x = end.x;
    A = end.A;
  }
  return smallest;
}

TEST(OmplSteering, RrtWithExactSteeringReachesTheGoalExactly) {
  const Planned& p = PlanAroundDisk();
  ASSERT_EQ(p.status, ob::PlannerStatus::EXACT_SOLUTION) << p.status.asString();
  const oc::PathControl& path = p.setup->getSolutionPath();
  ASSERT_GE(path.getControlCount(), 2u) << "the straight connection crosses the disk";
  const std::vector<Connection> connections = Connections(p);
  for (std::size_t i = 0; i < connections.size(); ++i) {
    const Connection& c = connections[i];
    ASSERT_TRUE(c.IsSolutionUsable()) << c.BriefReport();
    const ReplayResult replay = ReplayExactArrival(c.problem, c.summary.impulses);
    EXPECT_LT(replay.position_error, kArrivalTolerance) << "connection " << i;
    EXPECT_LT(replay.orientation_error, kArrivalTolerance) << "connection " << i;
    // The next node of OMPL's path is where the ball arrives.
    EXPECT_LT((ContactPoint(path.getState(i + 1)) - replay.x).norm(), kArrivalTolerance) << "connection " << i;
    EXPECT_LT(RotationAngle(Orientation(path.getState(i + 1)), replay.A), kArrivalTolerance) << "connection " << i;
  }
  // The whole path as one impulse sequence from the start, without re-initialising the ball at the
  // nodes (the first delta psi of each later connection re-based on the psi the ball has there).
  ExactArrivalProblem whole = connections.front().problem;
  whole.x1 = p.goal_x;
  whole.A1 = p.goal_A;
  const std::vector<ExactImpulse> chained = ChainImpulses(connections);
  const ReplayResult replay = ReplayExactArrival(whole, chained);
  EXPECT_LT(replay.position_error, kArrivalTolerance);
  EXPECT_LT(replay.orientation_error, kArrivalTolerance);
  for (const ExactImpulse& e : chained) EXPECT_LE(std::abs(e.delta_psi), M_PI + 1e-12);
  // A path with a connection that is not usable has no sequence.
  std::vector<Connection> broken = connections;
  broken.back().status = ConnectionStatus::kNotReached;
  EXPECT_THROW(ChainImpulses(broken), std::invalid_argument);
}

TEST(OmplSteering, ThePlannedMotionAvoidsTheDiskAtDenseFreeMotionSamples) {
  const Planned& p = PlanAroundDisk();
  ASSERT_EQ(p.status, ob::PlannerStatus::EXACT_SOLUTION) << p.status.asString();
  const double spacing = p.steering->options().sample_spacing;
  for (const Connection& c : Connections(p)) {
    ASSERT_TRUE(c.IsSolutionUsable()) << c.BriefReport();
    EXPECT_GT(DenseClearance(c), 0.0) << c.BriefReport();
    // The steering's own samples are at most sample_spacing apart (its contact-speed bound).
    for (std::size_t k = 1; k < c.samples.size(); ++k)
      EXPECT_LE((c.samples[k].x - c.samples[k - 1].x).norm(), spacing) << "sample " << k;
  }
}

// A fresh problem without the planner: the disk, the same bounds, for steer() alone.
struct Steering {
  oc::SpaceInformationPtr si;
  std::shared_ptr<ExactSteeringPropagator> steering;
  ob::ScopedState<> from, to;
  explicit Steering(const ob::StateSpacePtr& space = MakeBallStateSpace({-3.0, -5.0}, {9.0, 5.0}))
      : si(std::make_shared<oc::SpaceInformation>(space, MakeTargetControlSpace(space))),
        from(si->getStateSpace()),
        to(si->getStateSpace()) {
    si->setStateValidityChecker([](const ob::State* s) { return Clearance(ContactPoint(s)) > 0.0; });
    steering = UseExactSteering(si, SteeringOptions{});
    si->setup();
    SetConfiguration(from.get(), {0.0, 0.0}, ExpSO3({0.6, 0.2, 0.0}));
  }
  bool Steer() {
    oc::Control* u = si->allocControl();
    double duration = -1.0;
    const bool ok = steering->steer(from.get(), to.get(), u, duration);
    si->freeControl(u);
    return ok;
  }
};

TEST(OmplSteering, SteerReachesAFreeTargetWithOneStep) {
  Steering s;
  SetConfiguration(s.to.get(), {-1.0, 1.5}, ExpSO3({0.2, 0.4, -0.1}));
  oc::Control* u = s.si->allocControl();
  double duration = -1.0;
  ASSERT_TRUE(s.steering->steer(s.from.get(), s.to.get(), u, duration));
  EXPECT_EQ(duration, 1.0);
  EXPECT_EQ(TargetPoint(u), Eigen::Vector2d(-1.0, 1.5));
  // propagate() applies the exact connection: the result is the target.
  ob::ScopedState<> result(s.si->getStateSpace());
  s.steering->propagate(s.from.get(), u, duration, result.get());
  EXPECT_LT((ContactPoint(result.get()) - Eigen::Vector2d(-1.0, 1.5)).norm(), kArrivalTolerance);
  EXPECT_LT(RotationAngle(Orientation(result.get()), ExpSO3({0.2, 0.4, -0.1})), kArrivalTolerance);
  s.si->freeControl(u);
}

TEST(OmplSteering, SteerToItselfFailsAsTooClose) {
  Steering s;
  s.to = s.from;
  EXPECT_FALSE(s.Steer());
  EXPECT_EQ(s.steering->Connect(s.from.get(), s.to.get()).status, ConnectionStatus::kTooClose);
}

TEST(OmplSteering, SteerToAnUnreachableTargetFailsAsNotReached) {
  Steering s;
  // 0.05 away, turned half a turn about the vertical: six impulses along a straight reference of
  // that length cannot turn the ball that far.
  SetConfiguration(s.to.get(), {0.05, 0.0}, ExpSO3({0.0, 0.0, 3.0}) * ExpSO3({0.6, 0.2, 0.0}));
  EXPECT_FALSE(s.Steer());
  const Connection c = s.steering->Connect(s.from.get(), s.to.get());
  EXPECT_EQ(c.status, ConnectionStatus::kNotReached) << c.BriefReport();
  // propagate() with that target is no move.
  oc::Control* u = s.si->allocControl();
  SetTarget(u, ContactPoint(s.to.get()), Orientation(s.to.get()));
  ob::ScopedState<> result(s.si->getStateSpace());
  s.steering->propagate(s.from.get(), u, 1.0, result.get());
  EXPECT_EQ(ContactPoint(result.get()), ContactPoint(s.from.get()));
  s.si->freeControl(u);
}

TEST(OmplSteering, SteerToAnInvalidTargetOrThroughTheDiskFails) {
  Steering s;
  SetConfiguration(s.to.get(), kDiskCentre, ExpSO3({0.2, 0.4, -0.1}));
  EXPECT_FALSE(s.Steer());
  EXPECT_EQ(s.steering->Connect(s.from.get(), s.to.get()).status, ConnectionStatus::kInvalidState);
  // Straight across the disk: the exact arrival exists (its pass points stay within 0.8 of the
  // line through the disk's centre), its motion does not avoid the disk.
  SetConfiguration(s.to.get(), {6.0, 0.0}, ExpSO3({0.5, -0.5, 0.5}));
  EXPECT_FALSE(s.Steer());
  const Connection across = s.steering->Connect(s.from.get(), s.to.get());
  EXPECT_EQ(across.status, ConnectionStatus::kInvalidMotion) << across.BriefReport();
  // propagate() with that target (as a planner with random controls would) is no move.
  oc::Control* u = s.si->allocControl();
  SetTarget(u, ContactPoint(s.to.get()), Orientation(s.to.get()));
  ob::ScopedState<> result(s.si->getStateSpace());
  s.steering->propagate(s.from.get(), u, 1.0, result.get());
  EXPECT_EQ(ContactPoint(result.get()), ContactPoint(s.from.get()));
  s.si->freeControl(u);
  // Not finite: a NaN contact point.
  s.to[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(s.Steer());
  EXPECT_EQ(s.steering->Connect(s.from.get(), s.to.get()).status, ConnectionStatus::kInvalidState);
}

TEST(OmplSteering, BadOptionsNameTheField) {
  SteeringOptions o;
  o.impulses = 2;
  EXPECT_NE(o.Validate().find("impulses"), std::string::npos);
  o = SteeringOptions{};
  o.sample_spacing = 0.0;
  EXPECT_NE(o.Validate().find("sample_spacing"), std::string::npos);
  o = SteeringOptions{};
  o.mu = -1.0;
  EXPECT_NE(o.Validate().find("mu"), std::string::npos);
  EXPECT_TRUE(SteeringOptions{}.Validate().empty());
  EXPECT_THROW(MakeBallStateSpace({0.0, 0.0}, {0.0, 1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace plateball::ompl_steering
