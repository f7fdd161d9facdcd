// A path-following plan (impulse_planner.h) against a rig's limits (rig_limits.h): the independent
// check that tells whether the rig can execute the plan, as CheckRigLimits (exact_arrival.h) does
// for an exact arrival.
#pragma once

#include <optional>

#include "plateball/ball_model.h"
#include "plateball/export.h"
#include "plateball/impulse_planner.h"
#include "plateball/rig_limits.h"

namespace plateball PLATEBALL_EXPORT {

/// Checks `plan` (of `problem`) against `limits`. Every flight is re-integrated with FreeMotion from
/// its impulse's state, the replayed contact point and orientation carried from flight to flight
/// (from p(tau_0) and plan.A0), and sampled at `samples_per_arc` points: every contact point and
/// plate displacement is checked against the plate, the obstacles and the stroke. The impulses at
/// one partition point (its energy changes, then the energy-preserving impulse) are one actuation:
/// their summed delta omega is checked against max_plate_velocity_change and, with `physical`,
/// against the impulse bound (PlateImpulseFor; without `physical` that bound is not checked); its
/// time against the tick grid (exactly) and the flight before the next against min_interval.
/// Tolerances as CheckRigLimits'. Throws std::invalid_argument for samples_per_arc < 1.
RigCheck CheckPlanRigLimits(const PlanProblem& problem,
                            const PlanSummary& plan,
                            const RigLimits& limits,
                            const std::optional<PhysicalParameters>& physical,
                            const RigCheckTolerances& tolerances = {},
                            int samples_per_arc = 64);

}  // namespace PLATEBALL_EXPORT
