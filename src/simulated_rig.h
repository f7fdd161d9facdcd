// Internal: the library's simulated rig for closed-loop runs of the Controller (its tests and
// benchmark): the true ball of one execution trial under an ErrorModel, with the lambda and the
// impulse errors of Execute's trial for the same (seed, trial) (execution_noise.h), rolled freely
// between impulses, and a measurement of it with optional per-tick noise.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "counter_random.h"
#include "execution_noise.h"
#include "plateball/ball_model.h"
#include "plateball/controller.h"
#include "plateball/execution.h"

namespace plateball::internal {

class SimulatedRig {
 public:
  /// The ball at the plan's start. Throws std::invalid_argument naming the field for errors this rig
  /// does not model (timing jitter, finite pulses and Execute's observation noise: the controller's
  /// measurements carry their own noise, `measurement_noise`) or a negative measurement_noise.
  SimulatedRig(const NominalPlan& nominal,
               const ErrorModel& errors,
               std::uint64_t seed,
               std::uint64_t trial,
               double measurement_noise = 0.0);

  /// Free rolling over `duration` >= 0 with the true lambda (throws std::runtime_error when the
  /// integration fails).
  void Roll(double duration);
  /// Impulse k as the plate gives the commanded jump: perturbed, then the restitution.
  void Impulse(int k, const Eigen::Vector3d& commanded_delta_omega);
  /// The measurement at `tick`: the true contact point, orientation and angular velocity plus
  /// normal noise of deviation measurement_noise (per coordinate; for A a rotation vector; omega's
  /// third component stays 0), drawn from (seed, trial, tick).
  ControllerMeasurement Measure(long tick) const;

  const Eigen::Vector2d& x() const { return x_; }
  const Eigen::Matrix3d& A() const { return A_; }
  const BallState& state() const { return state_; }
  double lambda() const { return model_.lambda(); }

 private:
  const NominalPlan& nominal_;
  ExecutionNoise noise_;
  CounterRandom measurement_random_;
  double measurement_noise_;
  double restitution_;
  BallModel model_;
  BallState state_;
  Eigen::Vector2d x_;
  Eigen::Matrix3d A_;
};

/// The outcome of a closed loop: the controller's last status and the true ball at the last tick.
struct ClosedLoopResult {
  ControllerStatus status = ControllerStatus::kNotRun;
  int impulses = 0;
  long ticks = 0;            ///< Updates called
  int rejected = 0;          ///< ticks whose measurement was rejected
  int budget_exhausted = 0;  ///< ticks that flagged it
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
};

/// Ticks 0, 1, ...: measure the rig (contact point only when asked), Update the controller, apply
/// its impulse to the rig, roll one tick; until the controller reports done, lost or an integration
/// failure, or max_ticks.
ClosedLoopResult RunClosedLoop(Controller& controller,
                               SimulatedRig& rig,
                               long max_ticks,
                               bool contact_point_only = false);

}  // namespace plateball::internal
