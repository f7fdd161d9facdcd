// The installed OMPL component in use: one exact steer between two configurations of the ball
// (include/plateball/ompl/steering.h) and OMPL's propagate to its target, checked against the target.
#include <ompl/base/ScopedState.h>
#include <ompl/control/SpaceInformation.h>

#include <cstdio>

#include "plateball/ompl/steering.h"
#include "plateball/so3.h"

namespace ob = ompl::base;
namespace oc = ompl::control;
namespace ps = plateball::ompl_steering;

int main() {
  // The exact arrival's tolerance is 1e-12 (exact_arrival.h); the steer must land on its target.
  constexpr double kArrivalTolerance = 1e-9;
  const ob::StateSpacePtr space = ps::MakeBallStateSpace({-3.0, -3.0}, {3.0, 3.0});
  const auto si = std::make_shared<oc::SpaceInformation>(space, ps::MakeTargetControlSpace(space));
  si->setStateValidityChecker([](const ob::State*) { return true; });
  const auto steering = ps::UseExactSteering(si, ps::SteeringOptions{});
  si->setup();
  ob::ScopedState<> from(space), to(space), result(space);
  ps::SetConfiguration(from.get(), {0.0, 0.0}, plateball::ExpSO3({0.6, 0.2, 0.0}));
  const Eigen::Vector2d x1(-1.0, 1.5);
  const Eigen::Matrix3d A1 = plateball::ExpSO3({0.2, 0.4, -0.1});
  ps::SetConfiguration(to.get(), x1, A1);
  oc::Control* u = si->allocControl();
  double duration = 0.0;
  if (!steering->steer(from.get(), to.get(), u, duration)) {
    std::printf("ompl consumer: steer failed\n");
    return 1;
  }
  steering->propagate(from.get(), u, duration, result.get());
  si->freeControl(u);
  const double position = (ps::ContactPoint(result.get()) - x1).norm();
  const double orientation = plateball::RotationAngle(ps::Orientation(result.get()), A1);
  const bool ok = position < kArrivalTolerance && orientation < kArrivalTolerance;
  std::printf("ompl consumer: steer %s, arrival errors %.1e %.1e\n", ok ? "exact" : "missed", position, orientation);
  return ok ? 0 : 1;
}
