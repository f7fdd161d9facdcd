// The Controller (controller.h) with the MuJoCo twin as its plant: each tick the twin's ball (contact
// point, orientation, angular velocity) is the measurement, and the commanded jump, perturbed by the
// trial's errors (closed_loop.h: the draws of Execute and Monte Carlo for the same seed), is given to
// the twin as an ideal impulse or as a causal force pulse on the upper plate. The open loop fires the
// planned jumps at the planned times instead.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/closed_loop.h"
#include "plateball/controller.h"
#include "plateball/execution.h"
#include "rig/mujoco_twin.h"

namespace plateball::tools::rig {

struct TwinLoopOptions {
  /// The engine's settings; its timestep is split evenly into the ticks (at most one timestep each).
  TwinSettings settings;
  /// Measurements without the orientation and angular velocity (a camera that sees the contact point).
  bool contact_point_only = false;
  /// s; 0: ideal velocity jumps. > 0: causal pulses, a constant force J/D on the upper plate over
  /// [t_k, t_k + D] (the controller decides at t_k), J the plate impulse of the applied jump; shorter
  /// than every planned flight, and held by the engine's friction (CheckPulseFriction).
  double pulse_duration = 0.0;
  /// Empty when valid, else "FIELD: value V: what is wrong".
  std::string Validate() const;
};

/// The nominal plan as the twin's replay reads a result (impulse times, axes, jumps): for the pulse
/// checks and for ReplayInTwin.
RigPlan RigPlanOf(const NominalPlan& nominal, const PhysicalParameters& physical);

/// One impulse of a run in the twin.
struct TwinLoopImpulse {
  int k = 0;
  long tick = -1;                                           ///< -1 in the open loop (no ticks)
  double t = 0.0;                                           ///< s
  Eigen::Vector2d x = Eigen::Vector2d::Zero();              ///< the twin's contact point then (radii)
  Eigen::Vector3d delta_omega = Eigen::Vector3d::Zero();    ///< commanded jump, rad/s
  Eigen::Vector3d applied = Eigen::Vector3d::Zero();        ///< the jump the plate gave (errors), rad/s
  Eigen::Vector3d plate_impulse = Eigen::Vector3d::Zero();  ///< J for the commanded jump (PlateImpulseFor), N s
  Eigen::Vector3d pulse_impulse =
      Eigen::Vector3d::Zero();  ///< with pulses: J of the applied jump on the twin's ball, N s
  bool exact_replan = false;
  bool late = false;
};

/// How a run in the twin ended.
struct TwinLoopRun {
  ControllerStatus status = ControllerStatus::kNotRun;  ///< the controller's last (kDone for the open loop)
  std::string message;                                  ///< why a closed loop was lost (else empty)
  long ticks = 0;                                       ///< Updates called (0 in the open loop)
  int rejected = 0;                                     ///< rejected measurements
  int exact_solves = 0;
  long steps = 0;                                   ///< engine steps
  double t_end = 0.0;                               ///< s
  Eigen::Vector2d x = Eigen::Vector2d::Zero();      ///< the twin's contact point at t_end (radii)
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();  ///< the twin's orientation at t_end
  double position_error = 0.0;                      ///< |x - goal| (radii)
  double orientation_error = 0.0;                   ///< angle of goal_orientation^T A (rad)
  double max_slip_speed = 0.0;                      ///< m/s
  double max_spin_rate = 0.0;                       ///< rad/s
  std::vector<TwinLoopImpulse> impulses;
};

/// The twin, like the library's simulated rig, gives ideal impulses on ticks and measures exactly:
/// throws std::invalid_argument naming `field`.timing, .pulse_duration or .observation when not 0.
void RequireTwinModelled(const ErrorModel& errors, const std::string& field);

/// The ball with the trial's lambda: the symmetry moment I3 moved so that (alpha + beta) / (1 + beta)
/// = lambda with I1, the masses and the radius kept. Throws std::invalid_argument naming `field`
/// when that I3 is not a rigid ball MuJoCo can build.
PhysicalParameters BallWithLambda(const PhysicalParameters& p, double lambda, const std::string& field);

/// The closed loop: ticks 0, 1, ... of controller.options().tick_period until the controller is
/// done, lost or fails (at most 2 total_time / tick + 2 ticks). Throws std::invalid_argument for
/// invalid options, pulses that overlap a flight or slip, or errors the twin does not model (the
/// error model's timing, pulse_duration and observation: RequireTwinModelled), std::runtime_error
/// when the engine fails or a pulse is still running when the next impulse is due.
TwinLoopRun RunTwinClosedLoop(Controller& controller,
                              const PhysicalParameters& physical,
                              const TrialErrors& errors,
                              const TwinLoopOptions& options);

/// The open loop: the plan's jumps, perturbed by the same errors, at the planned times, to the
/// plan's end (the engine stepping to each impulse time exactly).
TwinLoopRun RunTwinOpenLoop(const NominalPlan& nominal,
                            const PhysicalParameters& physical,
                            const TrialErrors& errors,
                            const TwinLoopOptions& options);

}  // namespace plateball::tools::rig
