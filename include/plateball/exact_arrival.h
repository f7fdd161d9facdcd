// Exact arrival: the energy-preserving impulses (delta psi_k, t_k), k = 0..n-1, of the
// paper's control strategy (section 2.3) corrected so that the ball arrives at the goal position
// x1 *and* the goal orientation A1 exactly, not only to O(1/n^2) (Theorem 2.6).
//
// Unknowns: u = (delta psi_0..n-1, t_0..n-1) (2n values). Conditions (five):
//   x(T) - x1 = 0 (two) and LogSO3(A1^T A(T)) = 0 (three), T = sum t_k,
// where x(t), A(t) are the free motion between impulses (eqs. (12)-(18), the chart-free equations
// of docs/paper_notes.md) and each impulse psi -> psi + delta psi_k keeps theta, phi and mu
// (section 2.1, "Modeling an impulse"). 2n >= 5 is required, so n >= 3.
//
// "Closest to the reference" (the definition reported as `deviation`): among the impulse
// sequences that arrive exactly, the one whose pass points x(t_1 + ... + t_k), k = 1..n-1, are
// moved least from the planned pass points p(tau_k) of the reference, in the sense of
//   D(u) = sqrt( sum_{k=1}^{n-1} |x_k(u) - p(tau_k)|^2 )   subject to the five conditions.
// The solver is a Gauss-Newton method for this equality-constrained least-squares problem (each
// step solves the linearised KKT system: minimise |d + D du|^2 subject to r + J du = 0) with the
// exact Jacobian (variational equations on ceres::Jet, src/exact_chain.h),
// warm-started from the paper's plan (PlanImpulses on the reference, n uniform segments), whose
// pass points are on the reference (D = 0) but whose arrival is only approximate.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/export.h"
#include "plateball/field_list.h"
#include "plateball/impulse_planner.h"
#include "plateball/integration_options.h"
#include "plateball/path.h"
#include "plateball/rig_limits.h"
#include "plateball/start_state.h"

namespace plateball PLATEBALL_EXPORT {

enum class ExactArrivalStatus {
  kNotRun,              ///< default: nothing was solved
  kArrived,             ///< position and orientation within the tolerances
  kNotReached,          ///< the iteration stopped without meeting the tolerances (closest arrival reported)
  kWarmStartFailed,     ///< the paper's plan along the reference failed (its message is kept)
  kIntegrationFailure,  ///< an ODE integration failed
  kLimitsNotMet,        ///< no exact arrival meets the rig's limits (closest feasible arrival reported)
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(ExactArrivalStatus status);

/// What is asked: the ball's start state (StartState: at `x0` with angles `initial`, energy mu
/// and orientation A0), the reference path (it must start at x0), n impulses and the goal (x1, A1).
struct ExactArrivalProblem : StartState {
  Path reference = Path({SmoothCurve::Line(Eigen::Vector2d::Zero(), Eigen::Vector2d::UnitX())});
  int impulses = 12;                                 ///< n in [3, kMaxExactImpulses] (2n unknowns >= 5 conditions)
  Eigen::Vector2d x1 = Eigen::Vector2d::UnitX();     ///< goal position
  Eigen::Matrix3d A1 = Eigen::Matrix3d::Identity();  ///< goal orientation (a rotation)
  /// The ball starts at rest at x0 with the axis of `initial`: the first impulse is then
  /// energy-changing (0 -> mu) and sets the horizontal angular velocity to that of the angles
  /// (theta, phi, psi + delta psi_0); the geometry of the motion is the same as from a rolling start.
  bool start_at_rest = false;
  /// Arrive and stop: after the last arc, one more (energy-changing) impulse brings omega to zero;
  /// it is reported as ExactArrivalSummary::stop.
  bool stop_at_goal = false;
  /// The rig's limits (rig_limits.h); empty: none. When the free optimum meets them (and the
  /// objective is the deviation, without a tick), the result is the free optimum, unchanged.
  RigLimits limits;
  ArrivalObjective objective = ArrivalObjective::kDeviation;
  /// The masses behind the impulse bounds and the impulse objective in the units of J (needed by
  /// limits.max_plate_impulse and limits.max_force).
  std::optional<PhysicalParameters> physical;
};

/// Upper bound of ExactArrivalProblem::impulses: each Jacobian integrates about n^2 arcs, so the
/// worst case (kMaxExactImpulses^2 x kMaxIterations, 2 x 10^6 arcs) takes about 10 s on one core.
inline constexpr int kMaxExactImpulses = 200;

struct ExactArrivalOptions {
  static constexpr int kMaxIterations = 50;  ///< the tools' value: bounds the work with kMaxExactImpulses
  double position_tolerance = 1e-12;         ///< |x(T) - x1| to reach
  double orientation_tolerance = 1e-10;      ///< |LogSO3(A1^T A(T))| (rad) to reach
  int max_iterations = 50;                   ///< Gauss-Newton (KKT) iterations, in [1, kMaxIterations]
  /// Once arrived, the iteration stops when the deviation falls by less than this fraction.
  double deviation_tolerance = 1e-6;
  /// Rollouts of the solver (tighter than the library default so that 1e-12 is meaningful).
  IntegrationOptions integration{1e-14, 1e-14, 2'000'000};
  /// The variational equations of the exact Jacobian (src/exact_chain.h): ceres::Jet through the
  /// kinematics kernel, looser than the rollouts (Newton needs the derivatives to ~1e-8).
  IntegrationOptions jacobian_integration{1e-10, 1e-10, 2'000'000};
  PlanOptions warm_start;  ///< options of the paper's plan (the warm start)

  /// Empty when the options are valid; else a message naming the field and its value (the ranges
  /// of the field list, then the integrations' and the warm start's).
  std::string Validate() const;

  /// The field list (field_list.h): the Python attributes and the ranges Validate() checks.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(PLATEBALL_FIELD(position_tolerance, "|x(T) - x1| to reach").Positive(),
             PLATEBALL_FIELD(orientation_tolerance, "|LogSO3(A1^T A(T))| to reach (rad)").Positive(),
             PLATEBALL_FIELD(max_iterations, "Gauss-Newton (KKT) iterations").Counts(1, kMaxIterations),
             PLATEBALL_FIELD(deviation_tolerance,
                             "once arrived, the iteration stops when the deviation falls by less than this fraction")
                 .NonNegative(),
             PLATEBALL_FIELD(integration, "tolerances and step bound of the solver's rollouts"),
             PLATEBALL_FIELD(jacobian_integration, "tolerances and step bound of the exact Jacobian's integration"),
             PLATEBALL_FIELD(warm_start, "options of the paper's plan (the warm start)"));
  }
};

enum class ExactImpulseKind {
  kEnergyPreserving,  ///< psi -> psi + delta psi at fixed (theta, phi, mu)
  kStart,             ///< from rest: omega 0 -> the angles' omega at mu (energy-changing)
  kStop,              ///< at the goal: omega -> 0 (energy-changing, "arrive and stop")
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(ExactImpulseKind kind);

/// One impulse k at time t_impulse, then the free arc of duration t_k.
struct ExactImpulse {
  ExactImpulseKind kind = ExactImpulseKind::kEnergyPreserving;
  double t_impulse = 0.0;                              ///< since the start
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< contact point at the impulse
  double delta_psi = 0.0;
  double duration = 0.0;  ///< t_k
  Eigen::Vector3d delta_omega = Eigen::Vector3d::Zero();
  Eigen::Vector3d plate_velocity_change = Eigen::Vector3d::Zero();  ///< 2 delta_omega x e3
  AngleState angles_before;                                         ///< (theta, phi, psi) before the impulse
  double mu_before = 0.0, mu_after = 0.0;                           ///< energies (equal unless kStart / kStop)
  Eigen::Vector2d planned_position = Eigen::Vector2d::Zero();       ///< p(tau_k) of the reference
  double planned_delta_psi = 0.0, planned_duration = 0.0;           ///< the paper's plan (warm start)
  /// With a rig tick: the impulse's index on the grid, t_impulse = tick x limits.tick exactly; else -1.
  long long tick = -1;
};

/// A default-constructed summary says "not run".
struct ExactArrivalSummary {
  ExactArrivalStatus status = ExactArrivalStatus::kNotRun;
  std::string message = "not run";
  std::vector<ExactImpulse> impulses;
  /// With ExactArrivalProblem::stop_at_goal: the impulse at the goal that brings omega to zero.
  std::optional<ExactImpulse> stop;
  Eigen::Vector2d x_final = Eigen::Vector2d::Zero();
  Eigen::Matrix3d A_final = Eigen::Matrix3d::Identity();
  double position_error = 0.0;     ///< |x(T) - x1|
  double orientation_error = 0.0;  ///< |LogSO3(A1^T A(T))| in rad
  /// D = sqrt(sum_k |x_k - p(tau_k)|^2) over the interior pass points (see the file comment).
  double deviation = 0.0;
  double max_pass_displacement = 0.0;  ///< max_k |x_k - p(tau_k)|
  double total_time = 0.0;             ///< T = sum t_k
  int iterations = 0;                  ///< Gauss-Newton iterations
  /// The iteration stopped at ExactArrivalOptions::max_iterations before the deviation settled:
  /// with kArrived, the arrival is exact but the pass points may not be the closest (the message says so).
  bool iteration_limit_reached = false;
  int rollouts = 0;  ///< trajectories integrated (with or without their Jacobian)
  // The paper's plan (warm start), for comparison.
  double planned_position_error = 0.0;
  double planned_orientation_error = 0.0;
  double planned_total_time = 0.0;
  /// What the rig's limits did (empty without limits).
  RigLimitsReport limits;

  /// True when the status gives a result that may be used.
  bool IsSolutionUsable() const { return status == ExactArrivalStatus::kArrived; }
  /// One line: the status, the message and the main numbers.
  std::string BriefReport() const;
};

/// Solves the exact-arrival problem in the time scale of mu = 1 (mu only rescales time by
/// 1/sqrt(mu)): every mu gives the same pass points, with times scaled by 1/sqrt(mu). Throws std::invalid_argument
/// naming the field for invalid input (impulses < 3, mu, angles, A0 or A1 not rotations, x0 not the reference start,
/// options); a goal that is not reached is the status kNotReached with the closest arrival found.
ExactArrivalSummary SolveExactArrival(const ExactArrivalProblem& problem, const ExactArrivalOptions& options = {});

/// Independent check: re-integrates the reported impulses with FreeMotion (one stored period per
/// arc, its own tolerances) from the problem's start and returns the final position and
/// orientation. Used by the tests and the tools.
struct ReplayResult {
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  double position_error = 0.0;
  double orientation_error = 0.0;
};
/// Re-integrates `impulses` from the problem's start with `integration` (the independent check above).
ReplayResult ReplayExactArrival(const ExactArrivalProblem& problem,
                                const std::vector<ExactImpulse>& impulses,
                                const IntegrationOptions& integration = {1e-14, 1e-14, 2000000});

/// The independent check of a result against the problem's limits: re-integrates the impulses with
/// FreeMotion, samples every arc at `samples_per_arc` points and checks every contact point, plate
/// displacement, impulse (its delta omega from the replayed states, J by PlateImpulseFor), interval
/// and grid time (exactly) against the limits with `tolerances`.
RigCheck CheckRigLimits(const ExactArrivalProblem& problem,
                        const ExactArrivalSummary& summary,
                        const RigCheckTolerances& tolerances = {},
                        int samples_per_arc = 64);

}  // namespace PLATEBALL_EXPORT
