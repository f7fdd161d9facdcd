// Closed loops of the Controller (controller.h) on a rig. A trial's errors (TrialErrors) are the
// seeded draws of an ErrorModel that Execute and Monte Carlo make for (seed, trial): a plant other
// than the library's (a MuJoCo twin, a hardware-in-the-loop bench) injects them to compare with
// the library's closed loop on its own simulated ball (RunSimulatedClosedLoop) for the same seed.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>

#include "plateball/controller.h"
#include "plateball/error_model.h"
#include "plateball/execution.h"
#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

/// The realisation of an ErrorModel in one trial: the draws of Execute's trial (seed, trial).
class TrialErrors {
 public:
  /// Throws std::invalid_argument naming the field for invalid errors.
  TrialErrors(const ErrorModel& errors, std::uint64_t seed, std::uint64_t trial);
  /// The ball's true lambda in this trial: nominal (1 + e), e ~ N(0, errors.lambda^2).
  double TrueLambda(double nominal_lambda) const;
  /// The jump the plate gives for impulse k when `commanded` is asked: turned about e3 by the
  /// impulse_angle draw and scaled by 1 + the impulse_magnitude draw (restitution not included).
  Eigen::Vector3d PerturbImpulse(int k, const Eigen::Vector3d& commanded) const;
  /// The speed factor sqrt(1 - energy_loss) that follows every impulse.
  double Restitution() const;
  /// The error model drawn from.
  const ErrorModel& errors() const { return errors_; }

 private:
  ErrorModel errors_;
  std::uint64_t seed_ = 1;
  std::uint64_t trial_ = 0;
};

/// The end of a closed loop: the controller's last status and the true ball at the last tick.
struct SimulatedLoopResult {
  ControllerStatus status = ControllerStatus::kNotRun;  ///< the controller's last status
  int impulses = 0;                                     ///< impulses the controller gave
  long ticks = 0;                                       ///< Updates called
  int rejected = 0;                                     ///< ticks whose measurement was rejected
  Eigen::Vector2d x = Eigen::Vector2d::Zero();          ///< the true contact point at the last tick
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();      ///< the true orientation then
  double position_error = 0.0;                          ///< |x - goal| (radii)
  double orientation_error = 0.0;                       ///< angle of goal_orientation^T A (rad)
  double lambda = 0.0;                                  ///< the simulated ball's true lambda
};

/// The controller on the library's simulated ball of trial (seed, trial) under `errors` (ideal
/// impulses on ticks, free rolling with the true lambda between them; timing jitter, pulses and
/// observation noise are not modelled: std::invalid_argument names them). Ticks 0, 1, ... until
/// the controller is done, lost or fails, at most 2 total_time / tick_period + 2 ticks. With
/// contact_point_only the measurements carry the contact point alone.
SimulatedLoopResult RunSimulatedClosedLoop(std::shared_ptr<const NominalPlan> nominal,
                                           const ControllerOptions& options,
                                           const ErrorModel& errors,
                                           std::uint64_t seed,
                                           std::uint64_t trial,
                                           bool contact_point_only = false);

}  // namespace PLATEBALL_EXPORT
