#include "common/exact_output.h"

#include <vector>

#include "common/svg.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"
#include "plateball/impulse_planner.h"

namespace plateball::tools {

Json ExactArrivalToJson(const ExactArrivalSummary& s, const ReplayResult& replay, bool with_impulses) {
  Json j = ResultJson(ToString(s.status), s.IsSolutionUsable(), s.message, s.BriefReport());
  Append(j, Json{{"impulse_count", s.impulses.size()},
         {"total_time", s.total_time},
         {"iterations", s.iterations},
         {"rollouts", s.rollouts},
         {"arrival", Json{{"x", ToJson(s.x_final)},
                          {"rotation", RotationToJson(s.A_final)},
                          {"position_error", s.position_error},
                          {"orientation_error", s.orientation_error}}},
         {"replay", Json{{"x", ToJson(replay.x)},
                         {"position_error", replay.position_error},
                         {"orientation_error", replay.orientation_error}}},
         {"deviation", Json{{"definition", "sqrt(sum_k |x_k - p(tau_k)|^2) over the interior pass points"},
                            {"value", s.deviation},
                            {"max_pass_displacement", s.max_pass_displacement}}},
         {"paper_plan", Json{{"position_error", s.planned_position_error},
                             {"orientation_error", s.planned_orientation_error},
                             {"total_time", s.planned_total_time}}}});
  if (with_impulses) {
    Json list = Json::array();
    for (std::size_t k = 0; k < s.impulses.size(); ++k) {
      const ExactImpulse& e = s.impulses[k];
      list.push_back(Json{{"k", k},
                          {"t_impulse", e.t_impulse},
                          {"x", ToJson(e.position)},
                          {"p", ToJson(e.planned_position)},
                          {"delta_psi", e.delta_psi},
                          {"duration", e.duration},
                          {"delta_omega", ToJson(e.delta_omega)},
                          {"plate_velocity_change", ToJson(e.plate_velocity_change)},
                          {"angles_before", ToJson(e.angles_before)},
                          {"planned_delta_psi", e.planned_delta_psi},
                          {"planned_duration", e.planned_duration}});
    }
    j["impulses"] = list;
  }
  return j;
}

void DrawExactArrival(const ExactArrivalProblem& problem, const ExactArrivalSummary& s, const std::string& title,
                      const std::string& file) {
  SvgFigure fig;
  const SvgFigure::Style reference{"#1f5fbf", 1.6, "7,5", "none"};
  const SvgFigure::Style actual{"#c0392b", 1.4, "", "none"};
  const SvgFigure::Style impulse{"black", 1.0, "", "black"};
  const SvgFigure::Style goal{"#2e8b57", 1.0, "", "#2e8b57"};
  for (const SmoothCurve& c : problem.reference.pieces()) {
    std::vector<Eigen::Vector2d> pts;
    for (int i = 0; i <= 400; ++i) pts.push_back(c.Value(c.Begin() + (c.End() - c.Begin()) * i / 400.0));
    fig.Polyline(pts, reference);
  }
  // Positions do not depend on the orientation: each arc starts from its impulse with the
  // identity turned minimally onto the symmetry axis.
  std::vector<Eigen::Vector2d> traj;
  for (const ExactImpulse& e : s.impulses) {
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
  fig.Marker(problem.x1, 3.2, goal);
  fig.Title(title);
  fig.Legend("reference path", reference);
  fig.Legend("exact impulsive trajectory", actual);
  fig.Legend("impulse points", impulse);
  fig.Legend("goal", goal);
  fig.Write(file);
}

}  // namespace plateball::tools
