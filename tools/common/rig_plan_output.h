// The nominal plan of a problem's path under its rig section (rig_limits.h), as `plateball plan`,
// `montecarlo`, `rig loop` and `view` make it, and its one JSON record ("rig").
#pragma once

#include <string>

#include "common/json_output.h"
#include "plateball/impulse_planner.h"
#include "plateball/problem.h"
#include "plateball/task_adapters.h"

namespace plateball::tools {

/// A plan and what the rig says of it.
struct RigNominal {
  PlanSummary plan;  ///< the plan to execute
  /// null without a rig section or when the plan failed; else {"mode": "honour", "segments_initial",
  /// "points_added", "points_slid", "rounds", "active", "blocking", "check"} (PlanImpulsesOnRig) or
  /// {"mode": "check", "check"} (the plan as given, checked by CheckPlanRigLimits).
  Json rig;
  bool limits_met = true;  ///< false: the plan cannot meet the limits (`message` says why)
  std::string message;     ///< why the limits are not met (empty when met)
  std::string note;        ///< honour: " (active: ...; N partition points added, M slid onto the tick grid)"
};

/// Plans setup.problem. Without a rig section: PlanImpulses. With one: PlanImpulsesOnRig (the partition
/// refined and slid onto the tick grid), or with `check_only` PlanImpulses of the partition as given
/// and CheckPlanRigLimits of it.
RigNominal PlanOnRig(const Problem& p, const PlanSetup& setup, bool check_only);

/// Adds r.rig to *doc as "rig" (nothing when it is null). Limits met: "; rig limits met" and the note
/// appended to "report", true. Not met: status limits_not_met, usable false, message and report say
/// why, false. `doc` must hold "report".
bool AddRigRecord(const RigNominal& r, Json* doc);

}  // namespace plateball::tools
