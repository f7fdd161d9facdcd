// A feedback controller for a rig's real-time loop: built once from a nominal plan (execution.h),
// called once per tick of a fixed loop rate with the measured ball, it answers with the command of
// that tick (nothing, or the impulse due now) and its estimate of the ball now and at the next
// impulse. Its decisions are those of Execute's feedback strategies (the re-join of Lemma 2.1 and
// the exact re-plan of exact_arrival.h, src/feedback_policy.h); the impulse times lie on the tick
// grid (tick 0 is the plan's first impulse). docs/controller.md describes the states it needs and
// how it copes with a contact point only.
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/execution.h"
#include "plateball/export.h"
#include "plateball/plate_impulse.h"

namespace plateball PLATEBALL_EXPORT {

namespace internal {
class FeedbackPolicy;
}

struct ControllerOptions {
  /// The loop's tick period (normalised time = seconds, docs/units.md), in [1e-7, 1]. Impulses
  /// fire on ticks: a commanded flight is rounded to whole ticks (at least one).
  double tick_period = 1e-3;
  /// kFeedback (re-join before each impulse) or kFeedbackExact (exact re-plans near the end).
  ExecutionStrategy strategy = ExecutionStrategy::kFeedback;
  /// exact_window and the exact re-plans' options, as Execute's (miss_tolerance is not used).
  ExecutionOptions execution;
  /// Wall-clock seconds one Update may take, in (0, 10]. Once the re-join is done and more than
  /// this has passed, no exact re-plan is started (the join is used: the best so far) and
  /// ControllerOutput::budget_exhausted is set; it is also set when the tick as a whole overran.
  double time_budget = 1e-3;
  /// A measured contact point farther than this (radii) from the prediction is a jump: rejected.
  double jump_tolerance = 0.05;
  /// A measured orientation turned by more than this (rad) from the prediction is rejected.
  double orientation_jump_tolerance = 0.2;
  /// max |A^T A - I| and |det A - 1| of a measured orientation; |omega_3| / |omega| likewise.
  double rotation_tolerance = 1e-6;
  /// With the ball's physical parameters, each impulse also gives the actuator's plate impulse J.
  std::optional<PhysicalParameters> physical;
  /// Empty when valid; else "FIELD: value V: what is wrong".
  std::string Validate() const;
};

enum class ControllerStatus {
  kNotRun,               ///< default: no update yet
  kOk,                   ///< the measurement was used; a command (or none) is given
  kMeasurementRejected,  ///< the measurement contradicts the model (NaN, not a rotation, spin, a
                         ///< jump): the prediction is used instead and reported
  kTimeOutOfOrder,       ///< the time is not finite or precedes the last tick: nothing changed
  kDone,                 ///< every impulse was given; the estimate keeps rolling freely
  kLost,                 ///< the next pass point cannot be joined from the estimate: no command
  kIntegrationFailure,   ///< an ODE integration failed: no command
};
/// The value's word ("ok", "measurement_rejected", ...).
std::string ToString(ControllerStatus status);

/// What the rig measures at a tick. The contact point is required; the orientation A (R_WB, so
/// the axis is z = A e3) and the spatial angular velocity omega (horizontal, no spin) come
/// together or not at all: without them the controller dead-reckons the axis and the velocity
/// from its own model since the last full measurement (docs/controller.md).
struct ControllerMeasurement {
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  bool has_orientation = false;
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
};

/// The controller's idea of the ball at one instant (nominal lambda).
struct ControllerEstimate {
  long tick = 0;
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  BallState state;
};

/// The answer of one Update. Fixed-size: filling it allocates nothing.
struct ControllerOutput {
  ControllerStatus status = ControllerStatus::kNotRun;
  /// A static text saying why the measurement was rejected or the tick failed ("" when kOk);
  /// Controller::message() has the full text of a lost ball.
  const char* reason = "";
  long tick = 0;           ///< this tick: round(time / tick_period)
  bool impulse = false;    ///< an impulse is due at `tick`
  int impulse_index = -1;  ///< its index k in the plan (0 .. n-1)
  double delta_psi = 0.0;  ///< the impulse psi -> psi + delta psi (exact tail: as planned)
  Eigen::Vector3d delta_omega = Eigen::Vector3d::Zero();            ///< the ball's jump (rad/s)
  Eigen::Vector3d plate_velocity_change = Eigen::Vector3d::Zero();  ///< 2 r delta_omega x e3
  bool has_plate_impulse = false;                                   ///< options.physical given
  PlateImpulse plate_impulse;                                       ///< PlateImpulseFor(physical, z, delta_omega)
  bool exact_replan = false;                                        ///< this impulse comes from a new exact re-plan
  long next_impulse_tick = -1;                                      ///< the next impulse's tick (-1: none left)
  bool late = false;              ///< the impulse's tick was skipped: it fires at this, later, tick
  bool budget_exhausted = false;  ///< see ControllerOptions::time_budget
  bool measurement_used = false;
  ControllerEstimate now;              ///< after this tick's impulse, if any
  ControllerEstimate at_next_impulse;  ///< predicted just before the next impulse (= now when none)
};

class Controller {
 public:
  /// Throws std::invalid_argument naming the field for a null or unusable plan or invalid options.
  /// Allocates everything the ticks need.
  Controller(std::shared_ptr<const NominalPlan> nominal, const ControllerOptions& options = {});
  /// Releases the preallocated state.
  ~Controller();
  /// Not copyable: the feedback policy refers to the controller's own options.
  Controller(const Controller&) = delete;
  /// Not assignable (see the copy constructor).
  Controller& operator=(const Controller&) = delete;

  /// One tick at `time` (normalised time since the plan's first impulse) with the measurement.
  /// Never throws; allocates no heap memory on ticks without an impulse and on impulses decided by
  /// the re-join (the exact re-plan allocates: docs/controller.md).
  const ControllerOutput& Update(double time, const ControllerMeasurement& measurement);

  /// The last output.
  const ControllerOutput& output() const { return out_; }
  /// The last failure's full message (empty when none).
  const std::string& message() const { return message_; }
  /// The plan it follows.
  const NominalPlan& nominal() const { return *nominal_; }
  /// Its options.
  const ControllerOptions& options() const { return options_; }
  /// feedback_exact: exact re-plans that arrived so far.
  int exact_solves() const;
  /// feedback_exact: exact re-plans that did not arrive (the last exact plan or a join went on).
  int exact_failures() const;

 private:
  void Propagate(long tick);
  bool Accept(const ControllerMeasurement& m);
  void Fire(long tick, std::chrono::steady_clock::time_point start);
  void PredictNext();

  std::shared_ptr<const NominalPlan> nominal_;
  ControllerOptions options_;
  std::unique_ptr<internal::FeedbackPolicy> policy_;
  ControllerEstimate estimate_;
  bool started_ = false;
  int next_impulse_ = 0;  // index of the next impulse (n: done)
  long next_impulse_tick_ = 0;
  ControllerOutput out_;
  std::string message_;
};

}  // namespace PLATEBALL_EXPORT
