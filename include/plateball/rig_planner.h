// A path-following plan (impulse_planner.h) that honours a rig's limits (rig_limits.h) where the
// planner can: the partition is refined where a flight leaves the plate, enters an obstacle or
// leaves the stroke box, and its points slide along the path onto the tick grid. The limits the
// partition cannot change (the path itself outside, the shortest interval, the impulse bounds)
// are reported by name. The independent check (CheckPlanRigLimits, plan_rig_check.h) is the judge.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/export.h"
#include "plateball/field_list.h"
#include "plateball/impulse_planner.h"
#include "plateball/limits.h"
#include "plateball/rig_limits.h"

namespace plateball PLATEBALL_EXPORT {

struct RigPlanOptions {
  /// Rounds of refinement: each bisects, in tau, every segment whose flight exceeds a geometric
  /// limit, and plans again (a flight deviates from its chord by O(h^2), so a round cuts the bow
  /// by about 4).
  int max_rounds = 8;
  /// Partition points the refinement may add over all rounds (the plan stays within the
  /// partition's step limit as well).
  int max_added_points = 4096;
  /// Samples per flight at which the planner looks for the flight's smallest geometric margin (the
  /// smallest is then located between its neighbours by golden-section search); the path itself
  /// is sampled as densely per segment of the given partition, and at least 2000 times per piece.
  int samples_per_flight = 32;
  /// Samples per flight of the final independent check (CheckPlanRigLimits).
  int check_samples_per_flight = 64;
  RigCheckTolerances tolerances;  ///< of the final check and of the path's own margins

  /// Empty when the options are valid; else a message naming the field and its value (the ranges
  /// of the field list, the tolerances' as tolerances.FIELD).
  std::string Validate() const;

  /// The field list (field_list.h): the Python attributes and the ranges Validate() checks.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(
        PLATEBALL_FIELD(max_rounds,
                        "refinement rounds, each bisecting the segments whose flights exceed a geometric limit")
            .Counts(0, 64),
        PLATEBALL_FIELD(max_added_points, "partition points the refinement may add over all rounds")
            .Counts(0, limits::kMaxPartitionSteps),
        PLATEBALL_FIELD(samples_per_flight, "samples per flight at which the planner looks for its smallest margin")
            .Counts(2, 100000),
        PLATEBALL_FIELD(check_samples_per_flight, "samples per flight of the final independent check")
            .Counts(1, 100000),
        PLATEBALL_FIELD(tolerances, "tolerances of the final check and of the path's own margins"));
  }
};

enum class RigPlanStatus {
  kNotRun,        ///< default: nothing planned
  kSuccess,       ///< the plan meets every limit (the independent check passed)
  kPlanFailed,    ///< the planner failed (plan.status and plan.message say why)
  kLimitsNotMet,  ///< a limit cannot be met: `blocking` names it, `message` says why
};
/// "not_run", "success", "plan_failed", "limits_not_met".
std::string ToString(RigPlanStatus status);

struct RigPlanSummary {
  RigPlanStatus status = RigPlanStatus::kNotRun;
  std::string message = "not run";
  PlanSummary plan;          ///< the plan of the final partition (its steps carry their taus)
  RigCheck check;            ///< the independent check of `plan` (CheckPlanRigLimits)
  int segments_initial = 0;  ///< partition segments asked for
  int points_added = 0;      ///< partition points the refinement added
  int points_slid = 0;       ///< partition points slid onto the tick grid (final plan)
  /// Partition points removed to merge flights shorter than min_interval, or that the tick grid
  /// could not place, with a neighbour (coarsening)
  int points_removed = 0;
  int rounds = 0;  ///< refinement rounds run (0: the given partition was enough)
  /// Limits that shaped the plan: the geometric limits refined against ("plate", "obstacles[0]",
  /// "stroke.x", ...), "tick" when points slid onto the grid or were removed for it, and
  /// "min_interval" when points were removed for it.
  std::vector<std::string> active;
  /// Limits that cannot be met, each once; the message says where and why.
  std::vector<std::string> blocking;

  /// True when the plan meets every limit (status kSuccess).
  bool IsSolutionUsable() const { return status == RigPlanStatus::kSuccess; }
  /// One line: the status, the refinement and the plan's report.
  std::string BriefReport() const;
};

/// Plans problem.path under `limits`, round by round: every flight is replayed (IntegrateFreeMotion)
/// and its smallest margin to the plate, the obstacles and the stroke located; the segments of the
/// flights below -tolerances.position (the check's tolerance: a pass point on the edge is met) are
/// bisected in tau and the path planned again, until none is. The flights are the judge, not the
/// path: a path that crosses an obstacle its flights pass is planned as it is. Refinement stops
/// with limits_not_met when the path itself (sampled) exceeds a limit the flights exceed (the pass
/// points converge to the path: blocked at the path's worst point), when the rounds or points run
/// out, or when a bisected flight would be shorter than min_interval (blocked by min_interval).
/// With a tick every interior point of a piece slides along the path onto the grid (the flight's
/// duration is the grid's difference; the ends of a piece stay fixed, and an impulse at a junction
/// of pieces that falls off the grid is blocked by "tick"). Energy changes keep their partition points.
/// Then the partition is coarsened where flights are too short: a flight shorter than min_interval
/// (but the last) or one whose end the grid could not place merges with a neighbour (an interior
/// point without energy changes is removed, no two neighbours in one round) and the path is planned
/// again, keeping a round's merges only while every flight stays within the geometric limits (a
/// merge whose flight would leave them keeps its point), for at most max_rounds rounds.
/// The final plan is checked by CheckPlanRigLimits; a limit it reports exceeded (the impulse
/// bounds, min_interval, ...) is blocking. Slack limits leave the plan bit for bit as
/// PlanImpulses(problem, options) gives it. Throws std::invalid_argument for invalid input
/// (as PlanImpulses, limits.Validate(), options.Validate()).
RigPlanSummary PlanImpulsesOnRig(const PlanProblem& problem,
                                 const RigLimits& limits,
                                 const std::optional<PhysicalParameters>& physical,
                                 const PlanOptions& options = {},
                                 const RigPlanOptions& rig_options = {});

}  // namespace PLATEBALL_EXPORT
