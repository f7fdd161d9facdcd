#include "common/plan_json.h"

#include <string>
#include <vector>

namespace plateball::tools {
namespace {

Json BoundsToJson(const ErrorBounds& b) {
  const ErrorBoundConstants& c = b.constants;
  return Json{{"a_posteriori", b.a_posteriori},
              {"a_posteriori_path", b.a_posteriori_path},
              {"a_posteriori_arcs", b.a_posteriori_arcs},
              {"theorem_2_5", b.theorem_2_5},
              {"corollary_2", b.corollary_2},
              {"theorem_2_6", b.theorem_2_6},
              {"corollary_3", b.corollary_3},
              {"sum_dtau_cubed", b.sum_dtau_cubed},
              {"parameter_norm", b.parameter_norm},
              {"constants",
               Json{{"K_p", c.K_p},
                    {"M_prime_p", c.M_prime_p},
                    {"K_bar_p", c.K_bar_p},
                    {"C_p", c.C_p},
                    {"M_prime", c.M_prime},
                    {"K_10", c.K_10},
                    {"K_tilde", c.K_tilde},
                    {"K1", c.K1},
                    {"D_p", c.D_p},
                    {"K_tilde_p", c.K_tilde_p}}}};
}

Json StepToJson(const PlanStep& s, const ActuatorContext* actuator) {
  const std::string where = actuator ? actuator->prefix + "steps[" + std::to_string(s.global_index) + "]" : "";
  Json j{{"k", s.global_index},
         {"piece", s.piece},
         {"tau", Json::array({s.tau_begin, s.tau_end})},
         {"p_begin", ToJson(s.p_begin)},
         {"p_end", ToJson(s.p_end)},
         {"t_impulse", s.t_impulse},
         {"duration", s.duration},
         {"delta_psi", s.delta_psi},
         {"delta_omega", ToJson(s.delta_omega)},
         {"plate_velocity_change", ToJson(s.plate_velocity_change)},
         {"mu", s.mu},
         {"angles_before", ToJson(s.angles_before)},
         {"omega_before", ToJson(s.state_before.omega)},
         {"omega_after_impulse", ToJson(s.impulse.state_after.omega)},
         {"angles_after", ToJson(s.angles_after)},
         {"omega_after", ToJson(s.state_after.omega)},
         {"x_end", ToJson(s.x_end)},
         {"pass_miss", s.pass_miss},
         {"join",
          Json{{"status", ToString(s.join_status)}, {"residual", s.join_residual}, {"iterations", s.join_iterations}}},
         {"orientation_planned", ToJson(s.A_planned)},
         {"orientation_polyline", ToJson(s.A_polyline)},
         {"orientation_impulsive", ToJson(s.A_impulsive)},
         {"path_bound", s.path_bound},
         {"arc_bound", s.arc_bound}};
  if (!s.energy_changes.empty()) {
    Json e = Json::array();
    for (const Impulse& i : s.energy_changes) {
      Json c{{"mu_before", i.mu_before},
             {"mu_after", i.mu_after},
             {"delta_omega", ToJson(i.delta_omega)},
             {"plate_velocity_change", ToJson(i.plate_velocity_change)}};
      if (actuator)
        c["actuator"] = ActuatorJson(actuator->problem,
                                     i.state_before.z,
                                     i.delta_omega,
                                     actuator->request,
                                     where + ".energy_changes[" + std::to_string(e.size()) + "]");
      e.push_back(std::move(c));
    }
    j["energy_changes"] = std::move(e);
  }
  if (actuator)
    j["actuator"] = ActuatorJson(actuator->problem, s.impulse.state_before.z, s.delta_omega, actuator->request, where);
  return j;
}

}  // namespace

Json PlanSummaryToJson(const PlanSummary& plan, bool with_steps, const ActuatorContext* actuator) {
  Json doc = ResultJson(ToString(plan.status), plan.IsSolutionUsable(), plan.message, plan.BriefReport());
  doc["total_time"] = plan.total_time;
  doc["max_pass_miss"] = plan.max_pass_miss;
  doc["max_join_residual"] = plan.max_join_residual;
  doc["measured_error"] = plan.measured_error;
  doc["polyline_error"] = plan.polyline_error;
  doc["bounds"] = BoundsToJson(plan.bounds);
  doc["rotation_final"] = Json{{"planned", RotationToJson(plan.A_planned)},
                               {"polyline", RotationToJson(plan.A_polyline)},
                               {"impulsive", RotationToJson(plan.A_impulsive)}};
  doc["final"] =
      Json{{"mu", plan.mu_final}, {"z", ToJson(plan.final_state.z)}, {"omega", ToJson(plan.final_state.omega)}};
  if (actuator) {
    std::vector<double> times;
    for (const PlanStep& s : plan.steps) times.push_back(s.t_impulse);
    CheckPulseFlights(times, plan.total_time, actuator->request, actuator->prefix + "steps");
  }
  if (with_steps) {
    Json steps = Json::array();
    for (const PlanStep& s : plan.steps) steps.push_back(StepToJson(s, actuator));
    doc["steps"] = std::move(steps);
  }
  return doc;
}

}  // namespace plateball::tools
