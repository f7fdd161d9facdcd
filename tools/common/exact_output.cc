#include "common/exact_output.h"

#include <cmath>
#include <optional>
#include <variant>
#include <vector>

#include "common/svg.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"
#include "plateball/impulse_planner.h"

namespace plateball::tools {
namespace {

// The impulse times of an exact-arrival sequence, the stop (at the end) last.
std::vector<double> ImpulseTimes(const std::vector<ExactImpulse>& impulses, const std::optional<ExactImpulse>& stop) {
  std::vector<double> times;
  for (const ExactImpulse& e : impulses) times.push_back(e.t_impulse);
  if (stop) times.push_back(stop->t_impulse);
  return times;
}

// What the limits did to one count of the fewest search.
Json FewestRowRigJson(const FewestImpulsesCount& c) {
  Json j{{"within_limits", c.within_limits}, {"active", c.active}, {"blocking", c.blocking}};
  if (c.check) j["check"] = RigCheckJson(*c.check);
  return j;
}

}  // namespace

Json RigCheckJson(const RigCheck& check) {
  const RigCheckTolerances tol;
  Json margins = Json::object();
  for (const auto& [name, margin] : check.margins) margins[name] = margin;
  return Json{{"passed", check.passed},
              {"samples", check.samples},
              {"tolerances",
               Json{{"position", tol.position},
                    {"impulse_relative", tol.impulse},
                    {"interval_relative", tol.time},
                    {"tick", 0.0}}},
              {"margins", margins},
              {"violations", check.violations}};
}

Json ExactImpulseToJson(const ExactImpulse& e, std::size_t k, bool with_plan, const ActuatorContext* actuator) {
  Json j{{"k", k},
         {"kind", ToString(e.kind)},
         {"t_impulse", e.t_impulse},
         {"x", ToJson(e.position)},
         {"delta_psi", e.delta_psi},
         {"duration", e.duration},
         {"delta_omega", ToJson(e.delta_omega)},
         {"plate_velocity_change", ToJson(e.plate_velocity_change)},
         {"angles_before", ToJson(e.angles_before)},
         {"mu_before", e.mu_before},
         {"mu_after", e.mu_after}};
  if (with_plan) {
    j["p"] = ToJson(e.planned_position);
    j["planned_delta_psi"] = e.planned_delta_psi;
    j["planned_duration"] = e.planned_duration;
  }
  if (e.tick >= 0) j["tick"] = e.tick;
  if (actuator)
    j["actuator"] = ActuatorJsonFromAngles(actuator->problem,
                                           e.angles_before,
                                           e.mu_before,
                                           e.delta_omega,
                                           actuator->request,
                                           actuator->prefix + "impulses[" + std::to_string(k) + "]");
  return j;
}

Json ExactArrivalToJson(const ExactArrivalSummary& s,
                        const ReplayResult& replay,
                        bool with_impulses,
                        const ActuatorContext* actuator) {
  Json j = ResultJson(ToString(s.status), s.IsSolutionUsable(), s.message, s.BriefReport());
  Append(j,
         Json{{"impulse_count", s.impulses.size()},
              {"total_time", s.total_time},
              {"iterations", s.iterations},
              {"iteration_limit_reached", s.iteration_limit_reached},
              {"rollouts", s.rollouts},
              {"arrival",
               Json{{"x", ToJson(s.x_final)},
                    {"rotation", RotationToJson(s.A_final)},
                    {"position_error", s.position_error},
                    {"orientation_error", s.orientation_error}}},
              {"replay",
               Json{{"x", ToJson(replay.x)},
                    {"position_error", replay.position_error},
                    {"orientation_error", replay.orientation_error}}},
              {"deviation",
               Json{{"definition", "sqrt(sum_k |x_k - p(tau_k)|^2) over the interior pass points"},
                    {"value", s.deviation},
                    {"max_pass_displacement", s.max_pass_displacement}}},
              {"stop_at_goal", s.stop.has_value()},
              {"paper_plan",
               Json{{"position_error", s.planned_position_error},
                    {"orientation_error", s.planned_orientation_error},
                    {"total_time", s.planned_total_time}}}});
  if (actuator)
    CheckPulseFlights(ImpulseTimes(s.impulses, s.stop), s.total_time, actuator->request, actuator->prefix + "impulses");
  if (with_impulses) {
    Json list = Json::array();
    for (std::size_t k = 0; k < s.impulses.size(); ++k)
      list.push_back(ExactImpulseToJson(s.impulses[k], k, true, actuator));
    if (s.stop) list.push_back(ExactImpulseToJson(*s.stop, s.impulses.size(), false, actuator));
    j["impulses"] = list;
  }
  return j;
}

Json FewestImpulsesToJson(const FewestImpulsesProblem& problem,
                          const FewestImpulsesSummary& s,
                          bool with_impulses,
                          const ActuatorContext* actuator) {
  Json rows = Json::array();
  for (const FewestImpulsesCount& c : s.counts) {
    Json row{{"impulse_count", c.impulses},
             {"reached", c.reached},
             {"verdict", ToString(c.verdict)},
             {"by_continuation", c.by_continuation},
             {"starts", c.starts},
             {"arrived", c.arrived},
             {"total_time", c.total_time},
             {"path_length", c.path_length},
             {"position_error", c.position_error},
             {"orientation_error", c.orientation_error},
             {"total_impulse", c.total_impulse},
             {"deviation", c.deviation}};
    if (s.limited) row["rig"] = FewestRowRigJson(c);
    if (!c.plan.empty()) {  // the independent re-integration of the row's impulses
      const ReplayResult r = ReplayExactArrival(ReplayProblemFor(problem, c.impulses), c.plan);
      row["replay"] = Json{{"x", ToJson(r.x)},
                           {"position_error", problem.orientation_only ? 0.0 : r.position_error},
                           {"orientation_error", r.orientation_error}};
    }
    rows.push_back(row);
  }
  Json j = ResultJson(ToString(s.status), s.IsSolutionUsable(), s.message, s.BriefReport());
  Append(
      j,
      Json{{"fewest_impulses", s.fewest},
           {"minimal_for_generic_goal", s.minimal_for_generic_goal},
           {"pareto_times", "shortest_found"},
           {"searched", s.searched},
           {"max_total_time", s.max_total_time},
           {"rollouts", s.rollouts},
           {"start_at_rest", problem.start_at_rest},
           {"stop_at_goal", problem.stop_at_goal},
           {"orientation_only", problem.orientation_only},
           {"total_impulse_measure", problem.physical ? "sum_abs_J" : "sum_plate_velocity_change"},
           {"deviation_definition",
            "sqrt(sum_k |x_k - (x0 + k (x1 - x0) / n)|^2) over the interior impulse points: the straight line x0 -> x1 "
            "cut into n equal parts"},
           {"pareto", rows}});
  if (s.limited)
    j["rig"] = Json{{"objective", "fewest"},
                    {"tie_break",
                     "the fewest count reached within the limits; within it the shortest total time found, "
                     "then the first found"},
                    {"method",
                     "each exact arrival found is kept when it meets the limits (no tick), else taken through "
                     "SLSQP under the limits minimising the total time (times on the tick grid); a count is "
                     "reached only when an arrival within the limits passes the independent replay check"},
                    {"constrained_solves", s.constrained_solves},
                    {"evaluations", s.evaluations},
                    {"blocking", s.blocking}};
  const FewestImpulsesCount* f = s.Fewest();
  if (actuator && f)
    CheckPulseFlights(ImpulseTimes(f->plan, f->stop), f->total_time, actuator->request, actuator->prefix + "impulses");
  if (with_impulses && f) {
    Json list = Json::array();
    for (std::size_t k = 0; k < f->plan.size(); ++k) list.push_back(ExactImpulseToJson(f->plan[k], k, false, actuator));
    if (f->stop) list.push_back(ExactImpulseToJson(*f->stop, f->plan.size(), false, actuator));
    j["impulses"] = list;
  }
  return j;
}

bool HasRigSection(const ExactArrivalProblem& problem) {
  return !problem.limits.Empty() || problem.objective != ArrivalObjective::kDeviation;
}

Json RigJson(const ExactArrivalProblem& problem, const ExactArrivalSummary& s, const RigCheck& check) {
  return Json{{"objective", ToString(problem.objective)},
              {"constrained", s.limits.constrained},
              {"active", s.limits.active},
              {"blocking", s.limits.blocking},
              {"evaluations", s.limits.evaluations},
              {"check", RigCheckJson(check)}};
}

namespace {

std::vector<Eigen::Vector2d> Outline(const PlateShape& shape) {
  std::vector<Eigen::Vector2d> pts;
  if (const auto* d = std::get_if<DiskShape>(&shape)) {
    for (int i = 0; i <= 180; ++i)
      pts.push_back(d->center + d->radius * Eigen::Vector2d(std::cos(i * M_PI / 90), std::sin(i * M_PI / 90)));
  } else {
    pts = std::get<PolygonShape>(shape).vertices;
    pts.push_back(pts.front());
  }
  return pts;
}

// The plate region, the obstacles and the box the stroke allows the contact point (around x0).
void DrawLimits(const ExactArrivalProblem& problem, SvgFigure* fig) {
  const RigLimits& l = problem.limits;
  const SvgFigure::Style plate{"#555555", 1.4, "", "none"}, obstacle{"#8e2b2b", 1.0, "", "#e8b4b4"},
      stroke{"#7a5a00", 1.2, "3,3", "none"};
  if (l.plate) {
    fig->Polyline(Outline(*l.plate), plate);
    fig->Legend("plate edge", plate);
  }
  for (const PlateShape& o : l.obstacles) fig->Polyline(Outline(o), obstacle);
  if (!l.obstacles.empty()) fig->Legend("obstacles", obstacle, SvgFigure::Swatch::kPoint);
  if (l.stroke) {
    const Eigen::Vector2d h = 0.5 * *l.stroke, c = problem.x0;
    fig->Polyline({c + Eigen::Vector2d(-h.x(), -h.y()),
                   c + Eigen::Vector2d(h.x(), -h.y()),
                   c + h,
                   c + Eigen::Vector2d(-h.x(), h.y()),
                   c + Eigen::Vector2d(-h.x(), -h.y())},
                  stroke);
    fig->Legend("upper plate's stroke (contact point box)", stroke);
  }
}

}  // namespace

void DrawExactArrival(const ExactArrivalProblem& problem,
                      const ExactArrivalSummary& s,
                      const std::string& title,
                      const std::string& file) {
  DrawExactArrival(problem, s.impulses, title, file, "reference path");
}

void DrawExactArrival(const ExactArrivalProblem& problem,
                      const std::vector<ExactImpulse>& impulses,
                      const std::string& title,
                      const std::string& file,
                      const std::string& reference_label) {
  SvgFigure fig;
  DrawLimits(problem, &fig);
  const SvgFigure::Style reference{"#1f5fbf", 1.6, "7,5", "none"};
  const SvgFigure::Style actual{"#c0392b", 1.4, "", "none"};
  const SvgFigure::Style impulse{"black", 1.0, "", "black"};
  for (const SmoothCurve& c : problem.reference.pieces()) {
    std::vector<Eigen::Vector2d> pts;
    for (int i = 0; i <= 400; ++i) pts.push_back(c.Value(c.Begin() + (c.End() - c.Begin()) * i / 400.0));
    fig.Polyline(pts, reference);
  }
  // Positions do not depend on the orientation: each arc starts from its impulse with the
  // identity turned minimally onto the symmetry axis.
  std::vector<Eigen::Vector2d> traj;
  for (const ExactImpulse& e : impulses) {
    const Impulse imp = EnergyPreservingImpulse(e.angles_before, problem.mu, e.delta_psi, problem.model);
    FreeMotionStart fs;
    fs.state = imp.state_after;
    fs.x0 = e.position;
    fs.A0 = AlignOrientationToAxis(Eigen::Matrix3d::Identity(), fs.state.z);
    std::vector<double> times;
    for (int i = 0; i <= 24; ++i) times.push_back(e.duration * i / 24.0);
    for (const MotionSample& q : IntegrateFreeMotion(problem.model, fs, times)) traj.push_back(q.x);
    fig.Marker(e.position, 2.6, impulse);
  }
  fig.Polyline(traj, actual);
  const SmoothCurve& first = problem.reference.pieces().front();
  const SmoothCurve& last = problem.reference.pieces().back();
  fig.Start(first.StartPoint(), first.Derivative(first.Begin()), "x0");
  fig.Goal(problem.x1, last.Derivative(last.End()), "x1");
  fig.Title(title);
  fig.Legend(reference_label, reference);
  fig.Legend("exact impulsive trajectory", actual);
  fig.Legend("impulse points", impulse);
  fig.Write(file);
}

}  // namespace plateball::tools
