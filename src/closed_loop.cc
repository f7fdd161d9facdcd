#include "plateball/closed_loop.h"

#include <cmath>

#include "check.h"
#include "execution_noise.h"
#include "plateball/so3.h"
#include "simulated_rig.h"

namespace plateball {

TrialErrors::TrialErrors(const ErrorModel& errors, std::uint64_t seed, std::uint64_t trial)
    : errors_(errors), seed_(seed), trial_(trial) {
  internal::ThrowIfInvalid(errors.Validate());
}

// ExecutionNoise is a pure function of (errors, seed, trial): built per call, it holds no state.
double TrialErrors::TrueLambda(double nominal_lambda) const {
  return internal::ExecutionNoise(errors_, seed_, trial_).TrueLambda(nominal_lambda);
}

Eigen::Vector3d TrialErrors::PerturbImpulse(int k, const Eigen::Vector3d& commanded) const {
  return internal::ExecutionNoise(errors_, seed_, trial_).PerturbImpulse(k, commanded);
}

double TrialErrors::Restitution() const { return internal::ExecutionNoise(errors_, seed_, trial_).Restitution(); }

SimulatedLoopResult RunSimulatedClosedLoop(std::shared_ptr<const NominalPlan> nominal,
                                           const ControllerOptions& options,
                                           const ErrorModel& errors,
                                           std::uint64_t seed,
                                           std::uint64_t trial,
                                           bool contact_point_only) {
  Controller controller(nominal, options);
  internal::SimulatedRig rig(*nominal, errors, seed, trial);
  const long max_ticks = std::lround(2.0 * nominal->plan.total_time / options.tick_period) + 2;
  const internal::ClosedLoopResult r = internal::RunClosedLoop(controller, rig, max_ticks, contact_point_only);
  SimulatedLoopResult out;
  out.status = r.status;
  out.impulses = r.impulses;
  out.ticks = r.ticks;
  out.rejected = r.rejected;
  out.x = r.x;
  out.A = r.A;
  out.position_error = (r.x - nominal->goal).norm();
  out.orientation_error = RotationAngle(nominal->goal_orientation, r.A);
  out.lambda = rig.lambda();
  return out;
}

}  // namespace plateball
