// Impulsive path following (section 2.3, "Control strategy", Theorems 2.5 and 2.6): the sequence
// of energy-preserving impulses that makes the ball pass through every partition point of a
// planned path, the orientations the paper compares, and the error bounds.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/error_bounds.h"
#include "plateball/export.h"
#include "plateball/field_list.h"
#include "plateball/impulse.h"
#include "plateball/integration_options.h"
#include "plateball/join.h"
#include "plateball/partition.h"
#include "plateball/path.h"
#include "plateball/reach.h"
#include "plateball/so3.h"  // AlignOrientationToAxis
#include "plateball/start_state.h"

namespace plateball PLATEBALL_EXPORT {

enum class PlanStatus {
  kNotRun,                    ///< default: no plan was run
  kSuccess,                   ///< every partition point reached
  kSegmentBeyondLocalRadius,  ///< a join found no local solution (refine the partition)
  kIntegrationFailure,        ///< an ODE integration failed
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(PlanStatus status);

/// An energy-changing impulse inserted into a plan: at global partition point `index` the speed
/// |omega| is multiplied by `factor` (> 0); the path is unchanged.
struct EnergyChange {
  int index = 0;
  double factor = 1.0;
};

/// What is asked (section 2.3): the ball at p(tau_0) of the first piece and the path to follow.
/// The start (model, initial, mu, A0) is StartMotion's; the start point is the path's start.
struct PlanProblem : StartMotion {
  /// The planned path (default: the unit segment from the origin along x).
  Path path = Path({SmoothCurve::Line(Eigen::Vector2d::Zero(), Eigen::Vector2d::UnitX())});
  /// One rule per smooth piece, or one rule for every piece (partition.h).
  std::vector<PartitionRule> partition{UniformParameter{16}};
  std::vector<EnergyChange> energy_changes;  ///< index: global partition index in [0, n)
};

struct PlanOptions {
  JoinOptions join;  ///< per-segment join (tolerances, local-branch factor)
  /// A segment beyond the join's local radius is connected by Reach (reach.h, earliest solution)
  /// so that coarse partitions still give a plan; false: such a segment ends the plan with
  /// kSegmentBeyondLocalRadius.
  bool reach_fallback = true;
  ReachOptions reach;              ///< options of that fallback (integration: join's)
  IntegrationOptions integration;  ///< arcs with orientation and the rolling reference
  int bound_samples = 5;           ///< samples of p', p'' per segment for the bounds (>= 2)

  /// Empty when the options are valid; else a message naming the field and its value (the ranges
  /// of the field list, then the join's, the reach's and the integration's).
  std::string Validate() const;

  /// The field list (field_list.h): the Python attributes and the ranges Validate() checks.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(PLATEBALL_FIELD(join, "options of each segment's join (tolerances, local-branch factor)"),
             PLATEBALL_FIELD(reach_fallback, "connect a segment beyond the join's local radius by reach"),
             PLATEBALL_FIELD(reach, "options of that fallback (integration: join's)"),
             PLATEBALL_FIELD(integration, "tolerances and step bound of the arcs and the rolling reference"),
             PLATEBALL_FIELD(bound_samples, "samples of p', p'' per segment for the error bounds").Counts(2, 100000));
  }
};

/// One segment k: the impulse at p(tau_k) and the free arc to p(tau_k+1).
struct PlanStep {
  int piece = 0;         ///< smooth piece of the path
  int index = 0;         ///< k within the piece
  int global_index = 0;  ///< k over the whole plan
  double tau_begin = 0.0, tau_end = 0.0;
  Eigen::Vector2d p_begin = Eigen::Vector2d::Zero();  ///< p(tau_k)
  Eigen::Vector2d p_end = Eigen::Vector2d::Zero();    ///< p(tau_k+1)
  double t_impulse = 0.0;  ///< time of the impulse since the start of the plan (sum of earlier t_k)
  double duration = 0.0;   ///< t_k: time of flight to p(tau_k+1)
  double delta_psi = 0.0;
  Eigen::Vector3d delta_omega = Eigen::Vector3d::Zero();
  Eigen::Vector3d plate_velocity_change = Eigen::Vector3d::Zero();  ///< 2 delta_omega x e3
  std::vector<Impulse> energy_changes;  ///< energy-changing impulses applied at p(tau_k) first
  Impulse impulse;                      ///< the energy-preserving impulse at p(tau_k)
  BallState state_before;               ///< on arrival at p(tau_k), before any impulse
  BallState state_after;                ///< on arrival at p(tau_k+1)
  AngleState angles_before, angles_after;
  double mu = 0.0;                                  ///< energy on this arc
  Eigen::Vector2d x_end = Eigen::Vector2d::Zero();  ///< contact point reached (independent arc integration)
  double pass_miss = 0.0;                           ///< |x_end - p(tau_k+1)|
  JoinStatus join_status = JoinStatus::kConverged;
  bool reached_globally = false;  ///< connected by the Reach fallback, not the local join
  double join_residual = 0.0;
  int join_iterations = 0;
  Eigen::Matrix3d A_planned = Eigen::Matrix3d::Identity();    ///< A(tau_k+1) rolling along p
  Eigen::Matrix3d A_polyline = Eigen::Matrix3d::Identity();   ///< Abar_k+1 rolling along the chords
  Eigen::Matrix3d A_impulsive = Eigen::Matrix3d::Identity();  ///< Atilde_k+1 of the impulsive trajectory
  double path_max_speed = 0.0, path_max_acceleration = 0.0;   ///< max |p'|, |p''| on [tau_k, tau_k+1]
  double arc_max_speed = 0.0, arc_max_acceleration = 0.0;     ///< max |x'|, |x''| on the arc
  double path_bound = 0.0;                                    ///< ||R_k - S_k|| <= max|p'| max|p''| h^3 / 12
  double arc_bound = 0.0;                                     ///< ||S_k - Rtilde_k|| <= max|x'| max|x''| t_k^3 / 12
};

/// A default-constructed summary says "not run".
struct PlanSummary {
  // What was asked.
  int pieces = 0;
  int segments = 0;  ///< n over all pieces
  double mu_initial = 0.0;
  Eigen::Matrix3d A0 = Eigen::Matrix3d::Identity();  ///< initial orientation used (A0 e3 = z)

  PlanStatus status = PlanStatus::kNotRun;
  std::string message = "not run";  ///< why, when not kSuccess
  std::vector<PlanStep> steps;
  double total_time = 0.0;     ///< physical time of the whole impulsive trajectory
  double max_pass_miss = 0.0;  ///< max_k |x(t_k) - p(tau_k)|
  double max_join_residual = 0.0;
  Eigen::Matrix3d A_planned = Eigen::Matrix3d::Identity();    ///< A(T)
  Eigen::Matrix3d A_polyline = Eigen::Matrix3d::Identity();   ///< Abar_n
  Eigen::Matrix3d A_impulsive = Eigen::Matrix3d::Identity();  ///< Atilde_n
  double measured_error = 0.0;                                ///< ||A(T) - Atilde_n|| (operator norm)
  double polyline_error = 0.0;                                ///< ||A(T) - Abar_n||
  ErrorBounds bounds;                                         ///< bounds.a_posteriori is the reported bound
  BallState final_state;
  double mu_final = 0.0;

  /// True when the status gives a result that may be used.
  bool IsSolutionUsable() const { return status == PlanStatus::kSuccess; }
  /// One line: the status, the message and the main numbers.
  std::string BriefReport() const;
};

/// Plans the impulses for problem.path with the partition of problem.partition (one per smooth
/// piece, partition.h). The ball starts at p(tau_0) of the first piece with angles `initial`,
/// energy mu and orientation A0 (rotated minimally so that A0 e3 = z, as FreeMotion::FromAngles
/// does). Throws std::invalid_argument naming the field for invalid input (partition, indices,
/// factors, mu, A0, options); a join or an integration that fails is a status.
PlanSummary PlanImpulses(const PlanProblem& problem, const PlanOptions& options = {});

}  // namespace PLATEBALL_EXPORT
