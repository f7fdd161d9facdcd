// Executing a plan of section 2.3 under the errors of a real rig (error_model.h). The
// paper's strategy is open loop: the planned impulses at the planned times, in a perfect model.
// Three strategies are executed here, with one seeded realisation of the errors per trial:
//   open loop        the planned plate velocity changes at the planned (absolute) times;
//   feedback         before each impulse the (noisy) state is observed and the ball is joined
//                    again to the next pass point p(tau_k+1) (Lemma 2.1, join.h);
//   feedback_exact   feedback while more than `exact_window` impulses remain, then the remaining
//                    impulses are re-planned before each impulse for exact arrival at the goal
//                    (x1, A1) = (p(tau_n), A(T)) (exact_arrival.h); the last two (fewer than the
//                    three that exact arrival needs), and any step whose re-plan does not arrive,
//                    continue the last exact solution.
// The plate acts on the ball's horizontal angular velocity: an impulse adds the commanded
// delta_omega (perturbed, scaled by the restitution) to the true omega; between impulses the
// ball rolls freely with its true lambda.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/error_model.h"
#include "plateball/exact_arrival.h"
#include "plateball/export.h"
#include "plateball/impulse_planner.h"

namespace plateball PLATEBALL_EXPORT {

enum class ExecutionStrategy { kOpenLoop, kFeedback, kFeedbackExact };
/// "open_loop", "feedback", "feedback_exact".
std::string ToString(ExecutionStrategy strategy);
/// The inverse of ToString; throws std::invalid_argument naming `field` and the text otherwise.
ExecutionStrategy ParseExecutionStrategy(const std::string& text, const std::string& field = "strategy");

enum class ExecutionStatus {
  kNotRun,              ///< default: nothing was executed
  kCompleted,           ///< every impulse was applied and the final state measured
  kLost,                ///< feedback: the next pass point could not be joined from the observed state
  kIntegrationFailure,  ///< an ODE integration failed
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(ExecutionStatus status);

/// The deterministic plan every trial executes, computed once (PlanImpulses) with the pass points
/// p(tau_0..n) and the goal (x1, A1) = (p(tau_n), A(T)) of rolling exactly along the path.
struct NominalPlan {
  BallModel model = BallModel::FromLambda(1.0);
  AngleState initial;
  double mu = 1.0;
  PlanOptions options;
  PlanSummary plan;                          ///< plan.A0 is the aligned start orientation
  std::vector<Eigen::Vector2d> pass_points;  ///< p(tau_0), ..., p(tau_n)
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  Eigen::Matrix3d goal_orientation = Eigen::Matrix3d::Identity();
  /// |LogSO3(A1^T Atilde_n)|: the plan's own final orientation error in radians.
  double plan_orientation_error = 0.0;
};
/// Plans problem (throws std::invalid_argument as PlanImpulses); a failed plan is kept in
/// `plan.status` and may not be executed.
NominalPlan MakeNominalPlan(const PlanProblem& problem, const PlanOptions& options = {});
/// The nominal plan of `plan`, already planned for problem with options (e.g. by
/// PlanImpulsesOnRig, rig_planner.h, on a refined partition): its pass points are the plan's.
NominalPlan MakeNominalPlan(const PlanProblem& problem, const PlanOptions& options, PlanSummary plan);

/// What is asked: one trial, i.e. one realisation of `errors` drawn from (seed, trial).
struct ExecutionProblem {
  std::shared_ptr<const NominalPlan> nominal;  ///< required, with a usable plan
  ExecutionStrategy strategy = ExecutionStrategy::kFeedback;
  ErrorModel errors;
  std::uint64_t seed = 1;
  std::uint64_t trial = 0;
};

struct ExecutionOptions {
  static constexpr int kMaxExactWindow = 64;
  /// A pass point is missed when the ball is farther than this from it when the impulse fires
  /// (and at the end), in (0, 1e6].
  double miss_tolerance = 1e-3;
  /// feedback_exact: exact re-planning while 3 ... exact_window impulses remain, in [3, 64].
  int exact_window = 12;
  /// Options of those re-plans (looser than exact_arrival.h's defaults: the errors that follow
  /// are larger than 1e-10).
  ExactArrivalOptions exact = DefaultExactOptions();
  /// Empty when the options are valid; else a message naming the field and its value.
  std::string Validate() const;
  /// The default options of the exact re-plans (the `exact` field).
  static ExactArrivalOptions DefaultExactOptions();
};

/// A default-constructed summary says "not run".
struct ExecutionSummary {
  ExecutionStrategy strategy = ExecutionStrategy::kFeedback;
  ExecutionStatus status = ExecutionStatus::kNotRun;
  std::string message = "not run";
  int impulses = 0;  ///< impulses applied
  /// |x - p(tau_k)| when impulse k fires, k = 1 .. n-1, and at the end (k = n).
  std::vector<double> pass_misses;
  std::vector<double> pass_speeds;  ///< the contact speed |x'| at those moments
  int missed_pass_points = 0;       ///< pass_misses above ExecutionOptions::miss_tolerance
  double max_pass_miss = 0.0;
  double position_error = 0.0;     ///< |x(end) - x1|
  double orientation_error = 0.0;  ///< |LogSO3(A1^T A(end))| in rad
  double total_time = 0.0;         ///< time from the first impulse to the end
  Eigen::Vector2d x_final = Eigen::Vector2d::Zero();
  Eigen::Matrix3d A_final = Eigen::Matrix3d::Identity();
  double mu_final = 0.0;   ///< energy at the end (nominal lambda)
  double lambda = 0.0;     ///< the ball's true lambda in this trial
  int exact_solves = 0;    ///< feedback_exact: exact re-plans that arrived
  int exact_failures = 0;  ///< ... that did not (the last exact plan goes on, else a join)

  /// True when the status gives a result that may be used.
  bool IsSolutionUsable() const { return status == ExecutionStatus::kCompleted; }
  /// One line: the status, the message and the main numbers.
  std::string BriefReport() const;
};

/// Empty when the pulses of `errors.pulse_duration` fit the nominal plan's flights (each no longer
/// than the flight to the next impulse; the last one's end before the plan's end); otherwise
/// "pulse_duration: value D: longer than the flight K -> K+1 (F)". The first pulse may start
/// before time 0 (the ball rolled freely before).
std::string PulseScheduleError(const NominalPlan& nominal, const ErrorModel& errors);

/// A pulse duration for executing a nominal plan open loop within a stated error.
struct PulseDurationChoice {
  double duration = 0.0;        ///< the chosen pulse duration (s, normalised time)
  double measured_error = 0.0;  ///< final |x - x_ideal| + rotation angle to A_ideal, executed with it
  int executions = 0;           ///< pulsed executions run (the ideal one not counted)
  bool within = false;          ///< measured_error <= the tolerance
};

/// Chooses the pulse duration from the measured order: executes with d0 = 0.1 x the shortest flight,
/// scales by (0.9 tolerance / error)^(1/2) (centred; causal: ^1, docs/rig.md), caps at the shortest flight,
/// and verifies by executing, halving (at most 8 times) while the error exceeds the tolerance.
/// Throws std::invalid_argument naming `tolerance` when it is not finite and > 0.
PulseDurationChoice ChoosePulseDuration(const std::shared_ptr<const NominalPlan>& nominal,
                                        double tolerance,
                                        bool causal = false);

/// Executes one trial. Throws std::invalid_argument naming the field for a missing nominal plan,
/// a plan that is not usable, invalid errors or options, pulses that do not fit the plan's flights; a lost ball or a
/// failed integration is a status. The result depends only on (nominal, strategy, errors, seed, trial, options).
ExecutionSummary Execute(const ExecutionProblem& problem, const ExecutionOptions& options = {});

}  // namespace PLATEBALL_EXPORT
