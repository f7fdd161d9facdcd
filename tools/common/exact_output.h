// The one JSON layout and the one figure of an exact-arrival result (exact_arrival.h), written by `plateball steer`
// and by `isoparallel_solve --exact`.
#pragma once

#include <string>

#include "common/json_output.h"
#include "plateball/exact_arrival.h"

namespace plateball::tools {

/// {"status", "usable", "message", "report", "impulse_count", "total_time", "iterations",
///  "rollouts", "arrival" ({"x", "rotation", "position_error", "orientation_error"}),
///  "replay" (the independent re-integration: {"x", "position_error", "orientation_error"}),
///  "deviation" ({"definition", "value", "max_pass_displacement"}), "paper_plan" ({"position_error",
///  "orientation_error", "total_time"}) and with `with_impulses` "impulses" (per
///  impulse: k, t_impulse, x, p, delta_psi, duration, delta_omega,
///  plate_velocity_change, angles_before, planned_delta_psi, planned_duration)}.
Json ExactArrivalToJson(const ExactArrivalSummary& s, const ReplayResult& replay, bool with_impulses = true);

/// The plate as SVG: the reference dashed, the exact impulsive trajectory solid (each free arc
/// re-integrated from its reported impulse), the impulse points and the goal marked.
void DrawExactArrival(const ExactArrivalProblem& problem, const ExactArrivalSummary& s, const std::string& title,
                      const std::string& file);

}  // namespace plateball::tools
