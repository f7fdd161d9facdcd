// The one JSON layout and the one figure of an exact-arrival result (exact_arrival.h), written by `plateball steer`
// and by `isoparallel_solve --exact`.
#pragma once

#include <string>
#include <vector>

#include "common/actuator_json.h"
#include "common/json_output.h"
#include "plateball/exact_arrival.h"
#include "plateball/fewest_impulses.h"

namespace plateball::tools {

/// {"status", "usable", "message", "report", "impulse_count", "total_time", "iterations",
///  "rollouts", "arrival" ({"x", "rotation", "position_error", "orientation_error"}),
///  "replay" (the independent re-integration: {"x", "position_error", "orientation_error"}),
///  "deviation" ({"definition", "value", "max_pass_displacement"}), "paper_plan" ({"position_error",
///  "orientation_error", "total_time"}) and with `with_impulses` "impulses" (per
///  impulse: k, t_impulse, x, p, delta_psi, duration, delta_omega,
///  plate_velocity_change, angles_before, planned_delta_psi, planned_duration; with `actuator` also
///  "actuator", ActuatorJson of the impulse)}.
Json ExactArrivalToJson(const ExactArrivalSummary& s,
                        const ReplayResult& replay,
                        bool with_impulses = true,
                        const ActuatorContext* actuator = nullptr);

/// The independent check's record (CheckRigLimits, CheckPlanRigLimits): {"passed", "samples",
/// "tolerances", "margins", "violations"}.
Json RigCheckJson(const RigCheck& check);

/// True when the problem has rig limits or an objective other than the deviation: the output then
/// carries RigJson.
bool HasRigSection(const ExactArrivalProblem& problem);
/// {"objective", "constrained", "active", "blocking", "evaluations", "check" (the independent
/// replay, CheckRigLimits: {"passed", "samples_per_arc", "samples", "tolerances", "margins",
/// "violations"})}.
Json RigJson(const ExactArrivalProblem& problem, const ExactArrivalSummary& s, const RigCheck& check);

/// One impulse record (k, kind, t_impulse, position, delta_psi, duration, delta_omega,
/// plate_velocity_change, angles_before, mu_before, mu_after and with `with_plan` the paper's
/// planned_position, planned_delta_psi, planned_duration; with `actuator` "actuator", ActuatorJson of
/// the impulse at its axis before it, named "PREFIXimpulses[K]" in messages).
Json ExactImpulseToJson(const ExactImpulse& e,
                        std::size_t k,
                        bool with_plan,
                        const ActuatorContext* actuator = nullptr);

/// The fewest-impulse search: {"status", "usable", "message", "report", "fewest_impulses", "searched",
/// "max_total_time", "rollouts", "start_at_rest", "stop_at_goal", "orientation_only", "pareto" (per
/// count searched: impulse_count, reached, starts, arrived, total_time, path_length, position_error,
/// orientation_error, total_impulse, deviation, replay (an independent re-integration) and with
/// limits "rig" ({"within_limits", "active", "blocking", "check"})), "total_impulse_measure",
/// "deviation_definition", with limits "rig" ({"objective", "tie_break", "method",
/// "constrained_solves", "evaluations", "blocking"}), with `with_impulses` "impulses" of the
/// fewest count (the stop impulse last), each with `actuator` as ExactImpulseToJson's}.
Json FewestImpulsesToJson(const FewestImpulsesProblem& problem,
                          const FewestImpulsesSummary& s,
                          bool with_impulses,
                          const ActuatorContext* actuator = nullptr);

/// The plate as SVG: the reference dashed, the exact impulsive trajectory solid (each free arc
/// re-integrated from its reported impulse), the impulse points and the goal marked.
void DrawExactArrival(const ExactArrivalProblem& problem,
                      const ExactArrivalSummary& s,
                      const std::string& title,
                      const std::string& file);
/// The same for any impulse sequence from the problem's start (the fewest-impulse answer), the
/// problem's reference dashed under `reference_label`.
void DrawExactArrival(const ExactArrivalProblem& problem,
                      const std::vector<ExactImpulse>& impulses,
                      const std::string& title,
                      const std::string& file,
                      const std::string& reference_label);

}  // namespace plateball::tools
