// Plans the ball from a start to a goal configuration (contact point and orientation) around a disk
// on the plate with OMPL's control-based RRT, whose tree is extended by plateball's exact steering
// (include/plateball/ompl/steering.h). Prints OMPL's status, each connection with its independent
// re-integration (ReplayExactArrival), the whole path's impulse sequence (ChainImpulses) re-integrated
// from the start, and the clearance from the disk along the motion.
// Usage: ompl_plan_around_disk [seed]   (exit 0 when the plan is exact and every check passes, 4 if not)
#include <ompl/base/PlannerStatus.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/SimpleSetup.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "plateball/ompl/steering.h"
#include "plateball/so3.h"

namespace ob = ompl::base;
namespace oc = ompl::control;
namespace ps = plateball::ompl_steering;

namespace {

// An arrival is accepted when the independent re-integration lands within this distance: the
// solver's tolerance is 1e-12, the replay integrates with its own tolerances (1e-14).
constexpr double kArrivalTolerance = 1e-9;
const Eigen::Vector2d kDiskCentre(3.0, 0.0);
constexpr double kDiskRadius = 1.5;

double Clearance(const Eigen::Vector2d& x) { return (x - kDiskCentre).norm() - kDiskRadius; }

}  // namespace

int main(int argc, char** argv) {
  const unsigned long seed = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 7;
  ompl::RNG::setSeed(seed);  // before any OMPL sampler exists: the plan is reproducible
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

  const ob::StateSpacePtr space = ps::MakeBallStateSpace({-3.0, -5.0}, {9.0, 5.0});
  oc::SimpleSetup setup(ps::MakeTargetControlSpace(space));
  const oc::SpaceInformationPtr si = setup.getSpaceInformation();
  ps::SteeringOptions options;  // lambda = 2, mu = 1, 6 impulses per connection
  const auto steering = ps::UseExactSteering(si, options);
  setup.setStateValidityChecker([](const ob::State* s) { return Clearance(ps::ContactPoint(s)) > 0.0; });

  ob::ScopedState<> start(space), goal(space);
  ps::SetConfiguration(start.get(), {0.0, 0.0}, plateball::ExpSO3({0.6, 0.2, 0.0}));
  ps::SetConfiguration(goal.get(), {6.0, 0.0}, plateball::ExpSO3({-0.4, 0.5, 0.3}));
  setup.setStartAndGoalStates(start, goal, 1e-6);
  auto rrt = std::make_shared<oc::RRT>(si);
  rrt->setGoalBias(0.2);
  setup.setPlanner(rrt);

  const ob::PlannerStatus status = setup.solve(120.0);
  std::printf("OMPL status: %s%s\n",
              status.asString().c_str(),
              status == ob::PlannerStatus::EXACT_SOLUTION ? " (EXACT_SOLUTION)" : "");
  if (status != ob::PlannerStatus::EXACT_SOLUTION) return 4;

  const oc::PathControl& path = setup.getSolutionPath();
  std::vector<ps::Connection> connections;
  bool ok = true;
  double min_clearance = INFINITY;
  for (std::size_t i = 0; i < path.getControlCount(); ++i) {
    const oc::Control* target = path.getControl(i);
    ps::Connection c = steering->ConnectTo(path.getState(i), ps::TargetPoint(target), ps::TargetOrientation(target));
    if (!c.IsSolutionUsable()) {
      std::printf("connection %zu: %s\n", i, c.BriefReport().c_str());
      return 4;
    }
    const plateball::ReplayResult replay = plateball::ReplayExactArrival(c.problem, c.summary.impulses);
    const double node_error = (ps::ContactPoint(path.getState(i + 1)) - replay.x).norm();
    for (const plateball::MotionSample& s : c.samples) min_clearance = std::min(min_clearance, Clearance(s.x));
    std::printf(
        "connection %zu: (%.4f, %.4f) -> (%.4f, %.4f), %zu impulses, T = %.6f, replay position error %.3g, "
        "orientation error %.3g, node error %.3g\n",
        i,
        c.problem.x0.x(),
        c.problem.x0.y(),
        c.problem.x1.x(),
        c.problem.x1.y(),
        c.summary.impulses.size(),
        c.summary.total_time,
        replay.position_error,
        replay.orientation_error,
        node_error);
    ok = ok && replay.position_error < kArrivalTolerance && replay.orientation_error < kArrivalTolerance &&
         node_error < kArrivalTolerance;
    connections.push_back(std::move(c));
  }
  // The whole path as one impulse sequence from the start, re-integrated without stopping at the nodes.
  plateball::ExactArrivalProblem whole = connections.front().problem;
  whole.x1 = ps::ContactPoint(goal.get());
  whole.A1 = ps::Orientation(goal.get());
  const std::vector<plateball::ExactImpulse> chained = ps::ChainImpulses(connections);
  const plateball::ReplayResult replay = plateball::ReplayExactArrival(whole, chained);
  // The sequence to execute: each later connection's first delta psi re-based on the ball's psi there.
  std::printf("impulse sequence (time, contact point, delta psi, then flight time):\n");
  for (const plateball::ExactImpulse& e : chained)
    std::printf("  t %.6f at (%.6f, %.6f): delta psi %+.9f, then %.6f\n",
                e.t_impulse,
                e.position.x(),
                e.position.y(),
                e.delta_psi,
                e.duration);
  std::printf("whole path: %zu connections, %zu impulses, goal position error %.3g, orientation error %.3g\n",
              connections.size(),
              chained.size(),
              replay.position_error,
              replay.orientation_error);
  std::printf("smallest clearance from the disk along the motion: %.4f\n", min_clearance);
  ok = ok && replay.position_error < kArrivalTolerance && replay.orientation_error < kArrivalTolerance &&
       min_clearance > 0.0;
  std::printf("%s\n", ok ? "checks passed" : "checks FAILED");
  return ok ? 0 : 4;
}
