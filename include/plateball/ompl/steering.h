// Exact steering for OMPL (optional component, built when OMPL is found): OMPL's control-based
// planners connect two ball configurations by plateball's exact arrival (exact_arrival.h), so the
// planned path consists of exact, not sampled, connections.
//
// The planning state is the ball's configuration: the contact point x in R^2 and the orientation
// A = R_WB in SO(3) (an ompl::base::CompoundStateSpace of RealVectorStateSpace(2) and
// SO3StateSpace). The kinetic state is fixed per problem, as in exact arrival: the energy mu is kept
// by every energy-preserving impulse, the angles (theta, phi) of the symmetry axis z = A e3
// (eqs. (12)-(14)) follow from A, and psi is set by the first impulse of each connection (its
// delta psi_0), so the value of psi at a node does not matter to the connection from it.
//
// The mapping onto OMPL's control model. OMPL's control-based planners apply one control for a
// number of propagation steps; a plateball connection is a sequence of n impulses (delta psi_k, t_k)
// that exists only as a whole (its impulses are solved together, five conditions on 2n unknowns).
// So here:
//   - a control is the connection's target configuration: six reals (x1, quaternion w x y z of A1);
//   - its duration is one propagation step (step size 1, control duration [1, 1] steps);
//   - propagate(state, target) runs the exact arrival from `state` to the target with a straight
//     reference and n impulses, and returns the arrival configuration (equal to the target within
//     the solver's tolerances); a target that is not reached, or whose motion leaves the valid set,
//     is no move: the result is the start state;
//   - steer(from, to) (canSteer() is true) returns the control "target = to" and duration 1 when the
//     exact arrival reaches `to` and every sampled configuration of the motion between them is valid
//     under the SpaceInformation's StateValidityChecker (contact points spaced at most
//     SteeringOptions::sample_spacing apart along the motion); else false.
// UseExactSteering() installs OMPL's SteeredControlSampler, so ompl::control::RRT extends its tree
// by steer() and reaches the goal state exactly (OMPL's EXACT_SOLUTION). OMPL checks the
// validity of the propagated end state only, so propagate() and steer() check the motion between
// two nodes themselves. Planners that sample random controls (SST, KPIECE, EST, PDST) never call
// steer(): their controls are random targets, and they reach the goal only approximately.
#pragma once

#include <ompl/base/State.h>
#include <ompl/base/StateSpace.h>
#include <ompl/control/Control.h>
#include <ompl/control/SpaceInformation.h>
#include <ompl/control/StatePropagator.h>

#include <Eigen/Core>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/exact_arrival.h"
#include "plateball/free_motion.h"

namespace plateball::ompl_steering {

/// The kinetic data fixed per planning problem and the settings of each exact connection.
struct SteeringOptions {
  BallModel model = BallModel::FromLambda(2.0);  ///< the ball (lambda)
  double mu = 1.0;                               ///< energy, eq. (9), > 0, kept along the whole path
  int impulses = 6;                              ///< n per connection, in [3, kMaxExactImpulses]
  ExactArrivalOptions exact;                     ///< the exact-arrival solver of each connection
  /// Two contact points closer than this cannot be connected: a straight reference of zero length
  /// does not exist, and a ball without spin cannot turn in place.
  double min_distance = 1e-6;
  /// Largest distance between consecutive contact points checked along a connection's motion.
  double sample_spacing = 0.02;

  /// Empty when the options are valid; else a message naming the field and its value.
  std::string Validate() const;
};

/// The state space R^2 x SO(3): the contact point within [low, high] (component-wise) and the
/// orientation R_WB. Throws std::invalid_argument naming `low`/`high` unless low < high, finite.
ompl::base::StateSpacePtr MakeBallStateSpace(const Eigen::Vector2d& low, const Eigen::Vector2d& high);
/// The control space of targets: six reals (x1, y1, qw, qx, qy, qz) with the contact point within
/// the state space's bounds and the quaternion components within [-1, 1].
ompl::control::ControlSpacePtr MakeTargetControlSpace(const ompl::base::StateSpacePtr& space);

/// Contact point of a state of MakeBallStateSpace().
Eigen::Vector2d ContactPoint(const ompl::base::State* state);
/// Orientation R_WB of a state of MakeBallStateSpace() (its unit quaternion as a rotation matrix;
/// NaN entries when the quaternion is zero or not finite).
Eigen::Matrix3d Orientation(const ompl::base::State* state);
/// Writes (x, A) into a state of MakeBallStateSpace(); A must be a rotation.
void SetConfiguration(ompl::base::State* state, const Eigen::Vector2d& x, const Eigen::Matrix3d& A);
/// Writes the target (x1, A1) into a control of MakeTargetControlSpace(); A1 must be a rotation.
void SetTarget(ompl::control::Control* control, const Eigen::Vector2d& x1, const Eigen::Matrix3d& A1);
/// The target contact point of a control of MakeTargetControlSpace().
Eigen::Vector2d TargetPoint(const ompl::control::Control* control);
/// The target orientation of a control of MakeTargetControlSpace() (normalised quaternion; NaN
/// entries when the quaternion is zero or not finite).
Eigen::Matrix3d TargetOrientation(const ompl::control::Control* control);

enum class ConnectionStatus {
  kNotRun,         ///< default: nothing was solved
  kConnected,      ///< exact arrival reached the target and the motion is valid
  kInvalidState,   ///< a start or target that is not finite, out of bounds or rejected by the checker
  kTooClose,       ///< contact points closer than SteeringOptions::min_distance
  kNotReached,     ///< the exact arrival did not reach the target (its status in the message)
  kInvalidMotion,  ///< the motion between them passes through a configuration that is not valid
};
/// The value's word for messages.
std::string ToString(ConnectionStatus status);

/// One exact connection between two configurations.
struct Connection {
  ConnectionStatus status = ConnectionStatus::kNotRun;
  std::string message = "not run";
  ExactArrivalProblem problem;  ///< what was solved (start, straight reference, goal)
  ExactArrivalSummary summary;  ///< the impulses and the arrival
  /// The sampled configurations of the motion (start to arrival; filled when the solve arrived).
  std::vector<MotionSample> samples;
  /// The ball's state (z, omega) at the arrival, before any next impulse (filled with `samples`).
  BallState end_state;

  /// True when the connection can be used.
  bool IsSolutionUsable() const { return status == ConnectionStatus::kConnected; }
  /// One line: the status, the message and the arrival errors.
  std::string BriefReport() const;
};

/// The impulses of consecutive connections as one sequence from the first connection's start: the
/// impulse times are shifted by the earlier connections' durations, and the first impulse of each
/// later connection gets the delta psi that takes the psi the ball actually has there (at the end of
/// the previous connection) to the psi its connection planned, reduced to [-pi, pi]. Throws std::invalid_argument when
/// a connection is not usable.
std::vector<ExactImpulse> ChainImpulses(const std::vector<Connection>& connections);

/// The StatePropagator of the mapping described at the top of this file.
class ExactSteeringPropagator : public ompl::control::StatePropagator {
 public:
  /// `si` must use MakeBallStateSpace() and MakeTargetControlSpace(); throws std::invalid_argument
  /// for invalid options.
  ExactSteeringPropagator(const ompl::control::SpaceInformationPtr& si, SteeringOptions options);

  /// The exact connection from `from` to `to`, its motion checked against the validity checker.
  Connection Connect(const ompl::base::State* from, const ompl::base::State* to) const;
  /// The connection from `from` to the target of a control.
  Connection ConnectTo(const ompl::base::State* from, const Eigen::Vector2d& x1, const Eigen::Matrix3d& A1) const;

  /// The arrival configuration of the connection to the control's target (the start state when
  /// the connection is not usable). `duration` is ignored: a control lasts one step.
  void propagate(const ompl::base::State* state,
                 const ompl::control::Control* control,
                 double duration,
                 ompl::base::State* result) const override;
  /// Control = `to` as target, duration = 1 step, when Connect(from, to) is usable; else false.
  bool steer(const ompl::base::State* from,
             const ompl::base::State* to,
             ompl::control::Control* result,
             double& duration) const override;
  /// True: steer() is implemented.
  bool canSteer() const override { return true; }
  /// False: a connection runs forward in time only.
  bool canPropagateBackward() const override { return false; }
  /// The options the connections use.
  const SteeringOptions& options() const { return options_; }

 private:
  const ompl::control::SpaceInformation* si_c_;
  SteeringOptions options_;
  // The last usable connection (start and target values -> arrival), so that propagate() after a
  // successful steer() does not solve the same exact arrival again.
  mutable std::mutex cache_mutex_;
  mutable std::vector<double> cache_key_;
  mutable Eigen::Vector2d cache_x_ = Eigen::Vector2d::Zero();
  mutable Eigen::Matrix3d cache_A_ = Eigen::Matrix3d::Identity();
};

/// Installs exact steering on `si`: the propagator, propagation step 1, control duration [1, 1]
/// steps and OMPL's SteeredControlSampler as the directed control sampler. Returns the propagator.
std::shared_ptr<ExactSteeringPropagator> UseExactSteering(const ompl::control::SpaceInformationPtr& si,
                                                          const SteeringOptions& options);

}  // namespace plateball::ompl_steering
