// The one JSON layout of an impulsive plan (impulse_planner.h's PlanSummary), written by
// `plateball plan` and by `isoparallel_solve --out` (its "plan" section).
#pragma once

#include "common/actuator_json.h"
#include "common/json_output.h"
#include "plateball/impulse_planner.h"

namespace plateball::tools {

/// {"status", "usable", "message", "report", "total_time", "max_pass_miss",
///  "max_join_residual", "measured_error", "polyline_error", "bounds" (a-posteriori, Theorems 2.5,
///  2.6, Corollaries 2, 3 and their constants), "rotation_final" ({"planned", "polyline",
///  "impulsive"}, each RotationToJson), "final" ({"mu", "z", "omega"}), and with
///  `with_steps` "steps" (per impulse: k, piece, tau, p_begin, p_end, t_impulse, duration,
///  delta_psi, delta_omega, plate_velocity_change, mu, states and orientations, pass_miss, join,
///  path_bound, arc_bound, energy_changes)}.
/// With `actuator`, every step and energy change also holds "actuator": ActuatorJson of its impulse
/// (its axis before it, its delta_omega), named "PREFIXsteps[K]" in messages.
Json PlanSummaryToJson(const PlanSummary& plan, bool with_steps = true, const ActuatorContext* actuator = nullptr);

}  // namespace plateball::tools
