// Python binding: every solver (join, reach, plan, converge, isoparallel, its impulsive plan, exact
// arrival) with its problem, options and summary. The solver calls release the GIL. Status enums
// are exposed as their ToString words ("converged", "success", ...), as in the tools' JSON.
#include "bind_common.h"
#include "field_binding.h"
#include "plateball/convergence.h"
#include "plateball/elastica.h"
#include "plateball/error_bounds.h"
#include "plateball/exact_arrival.h"
#include "plateball/impulse_planner.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/join.h"
#include "plateball/reach.h"
#include "plateball/so3.h"

namespace plateball::python {

void BindPlanActuator(py::class_<PlanSummary>& plan);  // bind_actuator.cc

namespace {

using Scalar1 = Eigen::Matrix<double, 1, 1>;

void BindJoin(py::module_& m) {
  py::class_<JoinOptions> options(
      m,
      "JoinOptions",
      "Options of join(): the tolerance, iterations and integration of joining a close target with one impulse.");
  DefFieldAttributes(WithKeywordInit(options))
      .def("validate", &JoinOptions::Validate, "Empty when valid, else names the field, the value and the bound.");
  py::class_<JoinProblem> problem(m, "JoinProblem", "Join x0 to a close target with one impulse (Lemma 2.1).");
  WithKeywordInit(problem)
      .def_readwrite("model", &JoinProblem::model)
      .def_readwrite("start", &JoinProblem::start)
      .def_readwrite("mu", &JoinProblem::mu)
      .def_readwrite("x0", &JoinProblem::x0)
      .def_readwrite("target", &JoinProblem::target);
  py::class_<JoinSummary> summary(
      m, "JoinSummary", "The answer of Join, with what was asked. A default-constructed summary says \"not run\".");
  AddSummaryShape(summary);
  summary.def_readonly("start", &JoinSummary::start)
      .def_readonly("mu", &JoinSummary::mu)
      .def_readonly("x0", &JoinSummary::x0)
      .def_readonly("target", &JoinSummary::target)
      .def_readonly("delta_psi", &JoinSummary::delta_psi)
      .def_readonly("t", &JoinSummary::t)
      .def_readonly("residual", &JoinSummary::residual)
      .def_readonly("iterations", &JoinSummary::iterations)
      .def_readonly("initial_guess_residual", &JoinSummary::initial_guess_residual)
      .def_readonly("time_limit", &JoinSummary::time_limit)
      .def_readonly("jacobian_conditioning", &JoinSummary::jacobian_conditioning)
      .def_readonly("impulse", &JoinSummary::impulse)
      .def_readonly("state_after", &JoinSummary::state_after)
      .def_readonly("angles_after", &JoinSummary::angles_after)
      .def_readonly("x_after", &JoinSummary::x_after);
  m.def("_join", &Join, py::arg("problem"), py::arg("options"), py::call_guard<py::gil_scoped_release>());
}

void BindReachTypes(py::module_& m) {
  py::class_<ReachOptions> options(
      m,
      "ReachOptions",
      "Options of reach(): the horizon, the scan of (delta_psi, t), the global search and the refinement's tolerance.");
  DefFieldAttributes(WithKeywordInit(options))
      .def(
          "validate", &ReachOptions::Validate, "Empty when valid; otherwise names the field, its value and the bound.");
  py::class_<ReachProblem> problem(
      m, "ReachProblem", "Reach a distant target with one impulse (section 2.3, Figure 8).");
  WithKeywordInit(problem)
      .def_readwrite("model", &ReachProblem::model)
      .def_readwrite("start", &ReachProblem::start)
      .def_readwrite("mu", &ReachProblem::mu)
      .def_readwrite("x0", &ReachProblem::x0)
      .def_readwrite("orientation", &ReachProblem::A0)
      .def_readwrite("target", &ReachProblem::target);
  py::class_<ReachSolution>(
      m, "ReachSolution", "One way to reach the target: impulse psi -> psi + delta_psi, then free rolling for time t.")
      .def_readonly("delta_psi", &ReachSolution::delta_psi)
      .def_readonly("t", &ReachSolution::t)
      .def_readonly("periods", &ReachSolution::periods)
      .def_readonly("residual", &ReachSolution::residual)
      .def_readonly("jacobian_determinant", &ReachSolution::jacobian_determinant)
      .def_readonly("impulse", &ReachSolution::impulse)
      .def_readonly("end", &ReachSolution::end);
  py::class_<ClosestApproach>(
      m, "ClosestApproach", "The closest the ball comes to the target over s in [0, 2 pi), t in [0, horizon].")
      .def_readonly("distance", &ClosestApproach::distance)
      .def_readonly("delta_psi", &ClosestApproach::delta_psi)
      .def_readonly("t", &ClosestApproach::t);
}

void BindReach(py::module_& m) {
  BindReachTypes(m);
  py::class_<ReachSummary> summary(
      m,
      "ReachSummary",
      "The result of reach(): every (delta_psi, t) that reaches the target within the horizon, earliest first, or the "
      "closest approach; status \"not run\" until solved.");
  AddSummaryShape(summary);
  summary.def_readonly("problem", &ReachSummary::problem)
      .def_readonly("period", &ReachSummary::period)
      .def_readonly("horizon", &ReachSummary::horizon)
      .def_readonly("solutions", &ReachSummary::solutions)
      .def_readonly("closest_approach", &ReachSummary::closest_approach)
      .def_readonly("drift_guess_delta_psi", &ReachSummary::drift_guess_delta_psi)
      .def_readonly("scan_periods_integrated", &ReachSummary::scan_periods_integrated)
      .def_readonly("candidates", &ReachSummary::candidates)
      .def_readonly("refine_iterations", &ReachSummary::refine_iterations)
      .def_readonly("tight_evaluations", &ReachSummary::tight_evaluations)
      .def_readonly("global_evaluations", &ReachSummary::global_evaluations)
      .def("earliest", &ReachSummary::Earliest, "The earliest solution (RuntimeError when there is none).")
      .def_property_readonly("delta_psi",
                             [](const ReachSummary& s) {
                               return Stack<1>(s.solutions,
                                               [](const ReachSolution& q) { return Scalar1(q.delta_psi); });
                             })
      .def_property_readonly("t", [](const ReachSummary& s) {
        return Stack<1>(s.solutions, [](const ReachSolution& q) { return Scalar1(q.t); });
      });
  m.def("_reach", &Reach, py::arg("problem"), py::arg("options"), py::call_guard<py::gil_scoped_release>());
}

void BindBounds(py::module_& m) {
  py::class_<ErrorBoundConstants>(
      m, "ErrorBoundConstants", "The constants of Lemmas 2.1-2.4 and Theorems 2.5-2.6, estimated over one plan.")
      .def_readonly("K_p", &ErrorBoundConstants::K_p)
      .def_readonly("M_prime_p", &ErrorBoundConstants::M_prime_p)
      .def_readonly("K_bar_p", &ErrorBoundConstants::K_bar_p)
      .def_readonly("C_p", &ErrorBoundConstants::C_p)
      .def_readonly("M_prime", &ErrorBoundConstants::M_prime)
      .def_readonly("K_10", &ErrorBoundConstants::K_10)
      .def_readonly("K_tilde", &ErrorBoundConstants::K_tilde)
      .def_readonly("K1", &ErrorBoundConstants::K1)
      .def_readonly("D_p", &ErrorBoundConstants::D_p)
      .def_readonly("K_tilde_p", &ErrorBoundConstants::K_tilde_p);
  py::class_<ErrorBounds>(m, "ErrorBounds", "Theorems 2.5/2.6, Corollaries 2/3 and the a-posteriori bound.")
      .def_readonly("constants", &ErrorBounds::constants)
      .def_readonly("sum_dtau_cubed", &ErrorBounds::sum_dtau_cubed)
      .def_readonly("parameter_norm", &ErrorBounds::parameter_norm)
      .def_readonly("segments", &ErrorBounds::segments)
      .def_readonly("theorem_2_5", &ErrorBounds::theorem_2_5)
      .def_readonly("corollary_2", &ErrorBounds::corollary_2)
      .def_readonly("theorem_2_6", &ErrorBounds::theorem_2_6)
      .def_readonly("corollary_3", &ErrorBounds::corollary_3)
      .def_readonly("a_posteriori_path", &ErrorBounds::a_posteriori_path)
      .def_readonly("a_posteriori_arcs", &ErrorBounds::a_posteriori_arcs)
      .def_readonly("a_posteriori", &ErrorBounds::a_posteriori)
      .def_property_readonly("report", &ErrorBounds::BriefReport);
}

void BindPlanInputs(py::module_& m) {
  py::class_<EnergyChange> change(m, "EnergyChange", "An energy-changing impulse at partition index `index`.");
  WithKeywordInit(change).def_readwrite("index", &EnergyChange::index).def_readwrite("factor", &EnergyChange::factor);
  py::class_<PlanOptions> options(m,
                                  "PlanOptions",
                                  "Options of plan(): the join and reach options of each segment (reach as a "
                                  "fallback), the integration of the free arcs and the samples of the error bounds.");
  DefFieldAttributes(WithKeywordInit(options))
      .def("validate",
           &PlanOptions::Validate,
           "Empty when the options are valid; else a message naming the field and its value.");
  py::class_<PlanProblem, StartMotion> problem(
      m, "PlanProblem", "Follow a planned path with energy-preserving impulses (section 2.3).");
  WithKeywordInit(problem)
      .def_readwrite("path", &PlanProblem::path)
      .def_readwrite("partition", &PlanProblem::partition)
      .def_readwrite("energy_changes", &PlanProblem::energy_changes);
}

void BindPlanStep(py::module_& m) {
  py::class_<PlanStep>(m, "PlanStep", "One segment k: the impulse at p(tau_k) and the free arc to p(tau_k+1).")
      .def_readonly("piece", &PlanStep::piece)
      .def_readonly("index", &PlanStep::index)
      .def_readonly("global_index", &PlanStep::global_index)
      .def_readonly("tau_begin", &PlanStep::tau_begin)
      .def_readonly("tau_end", &PlanStep::tau_end)
      .def_readonly("p_begin", &PlanStep::p_begin)
      .def_readonly("p_end", &PlanStep::p_end)
      .def_readonly("t_impulse", &PlanStep::t_impulse)
      .def_readonly("duration", &PlanStep::duration)
      .def_readonly("delta_psi", &PlanStep::delta_psi)
      .def_readonly("delta_omega", &PlanStep::delta_omega)
      .def_readonly("plate_velocity_change", &PlanStep::plate_velocity_change)
      .def_readonly("energy_changes", &PlanStep::energy_changes)
      .def_readonly("impulse", &PlanStep::impulse)
      .def_readonly("state_before", &PlanStep::state_before)
      .def_readonly("state_after", &PlanStep::state_after)
      .def_readonly("angles_before", &PlanStep::angles_before)
      .def_readonly("angles_after", &PlanStep::angles_after)
      .def_readonly("mu", &PlanStep::mu)
      .def_readonly("x_end", &PlanStep::x_end)
      .def_readonly("pass_miss", &PlanStep::pass_miss)
      .def_property_readonly("join_status", [](const PlanStep& s) { return ToString(s.join_status); })
      .def_readonly("reached_globally", &PlanStep::reached_globally)
      .def_readonly("join_residual", &PlanStep::join_residual)
      .def_readonly("join_iterations", &PlanStep::join_iterations)
      .def_readonly("orientation_planned", &PlanStep::A_planned)
      .def_readonly("orientation_polyline", &PlanStep::A_polyline)
      .def_readonly("orientation_impulsive", &PlanStep::A_impulsive)
      .def_readonly("path_bound", &PlanStep::path_bound)
      .def_readonly("arc_bound", &PlanStep::arc_bound);
}

// The impulsive trajectory of a plan: each free arc re-integrated from its impulse, chained in
// position and orientation (as `plateball plan --svg` draws it).
Trajectory PlanTrajectory(const PlanSummary& plan,
                          const BallModel& model,
                          int per_arc,
                          const IntegrationOptions& integration) {
  RequireCount("samples_per_arc", per_arc, 1, 100000);
  Trajectory out;
  if (plan.steps.empty()) return out;
  Eigen::Vector2d x = plan.steps.front().p_begin;
  Eigen::Matrix3d a = plan.A0;
  double t0 = 0.0;
  for (const PlanStep& s : plan.steps) {
    if (s.duration <= 0) break;
    std::vector<double> times;
    for (int i = (out.samples.empty() ? 0 : 1); i <= per_arc; ++i) times.push_back(s.duration * i / per_arc);
    for (MotionSample q :
         IntegrateFreeMotion(model, FreeMotionStart{s.impulse.state_after, x, a}, times, integration)) {
      q.t += t0;
      out.samples.push_back(q);
    }
    x = s.x_end;
    a = s.A_impulsive;
    t0 += s.duration;
  }
  return out;
}

void BindPlanSummary(py::module_& m) {
  py::class_<PlanSummary> summary(m,
                                  "PlanSummary",
                                  "The result of plan(): one PlanStep per impulse, the measured error, the error "
                                  "bounds and the final orientations; status \"not run\" until planned.");
  AddSummaryShape(summary);
  summary.def_readonly("pieces", &PlanSummary::pieces)
      .def_readonly("segments", &PlanSummary::segments)
      .def_readonly("mu_initial", &PlanSummary::mu_initial)
      .def_readonly("initial_orientation", &PlanSummary::A0)
      .def_readonly("steps", &PlanSummary::steps)
      .def_readonly("total_time", &PlanSummary::total_time)
      .def_readonly("max_pass_miss", &PlanSummary::max_pass_miss)
      .def_readonly("max_join_residual", &PlanSummary::max_join_residual)
      .def_readonly("orientation_planned", &PlanSummary::A_planned)
      .def_readonly("orientation_polyline", &PlanSummary::A_polyline)
      .def_readonly("orientation_impulsive", &PlanSummary::A_impulsive)
      .def_readonly("measured_error", &PlanSummary::measured_error)
      .def_readonly("polyline_error", &PlanSummary::polyline_error)
      .def_readonly("bounds", &PlanSummary::bounds)
      .def_readonly("final_state", &PlanSummary::final_state)
      .def_readonly("mu_final", &PlanSummary::mu_final)
      .def_property_readonly(
          "pass_points",
          [](const PlanSummary& s) {
            return Stack<2>(s.steps, [](const PlanStep& q) { return q.p_begin.transpose(); });
          },
          "(n, 2): p(tau_k), where the impulses act")
      .def_property_readonly("t_impulse",
                             [](const PlanSummary& s) {
                               return Stack<1>(s.steps, [](const PlanStep& q) { return Scalar1(q.t_impulse); });
                             })
      .def_property_readonly("delta_psi",
                             [](const PlanSummary& s) {
                               return Stack<1>(s.steps, [](const PlanStep& q) { return Scalar1(q.delta_psi); });
                             })
      .def_property_readonly(
          "durations",
          [](const PlanSummary& s) { return Stack<1>(s.steps, [](const PlanStep& q) { return Scalar1(q.duration); }); })
      .def_property_readonly("delta_omega",
                             [](const PlanSummary& s) {
                               return Stack<3>(s.steps, [](const PlanStep& q) { return q.delta_omega.transpose(); });
                             })
      .def_property_readonly("plate_velocity_changes",
                             [](const PlanSummary& s) {
                               return Stack<3>(s.steps,
                                               [](const PlanStep& q) { return q.plate_velocity_change.transpose(); });
                             })
      .def_property_readonly(
          "orientations_impulsive",
          [](const PlanSummary& s) { return StackMatrices(s.steps, [](const PlanStep& q) { return q.A_impulsive; }); })
      .def("trajectory",
           &PlanTrajectory,
           py::arg("model"),
           py::arg("samples_per_arc") = 24,
           py::arg("integration") = IntegrationOptions{},
           py::call_guard<py::gil_scoped_release>(),
           "The impulsive trajectory, every free arc re-integrated from its impulse.");
  BindPlanActuator(summary);
  m.def("_plan", &PlanImpulses, py::arg("problem"), py::arg("options"), py::call_guard<py::gil_scoped_release>());
}

void BindConvergence(py::module_& m) {
  py::class_<ConvergenceProblem> problem(m,
                                         "ConvergenceProblem",
                                         "What is asked: the plan problem (its partition rules must be uniform; each n "
                                         "of `ns` replaces their n) and the distinct partition sizes.");
  WithKeywordInit(problem)
      .def_readwrite("plan", &ConvergenceProblem::plan)
      .def_readwrite("ns", &ConvergenceProblem::ns);
  py::class_<ConvergenceOptions> options(
      m, "ConvergenceOptions", "Options of converge(): the plan options of every row and whether plans are timed.");
  WithKeywordInit(options)
      .def_readwrite("plan", &ConvergenceOptions::plan)
      .def_readwrite("timings", &ConvergenceOptions::timings);
  py::class_<ConvergenceRow>(
      m,
      "ConvergenceRow",
      "One row of a convergence study: the plan of one n, its measured error and the paper's bounds.")
      .def_readonly("n", &ConvergenceRow::n)
      .def_readonly("segments", &ConvergenceRow::segments)
      .def_readonly("plan_seconds", &ConvergenceRow::plan_seconds)
      .def_readonly("measured_error", &ConvergenceRow::measured_error)
      .def_readonly("polyline_error", &ConvergenceRow::polyline_error)
      .def_readonly("bound", &ConvergenceRow::bound)
      .def_readonly("theorem_2_6", &ConvergenceRow::theorem_2_6)
      .def_readonly("corollary_3", &ConvergenceRow::corollary_3)
      .def_readonly("max_pass_miss", &ConvergenceRow::max_pass_miss)
      .def_property_readonly("status", [](const ConvergenceRow& r) { return ToString(r.status); })
      .def_readonly("message", &ConvergenceRow::message);
  py::class_<ConvergenceStudy> study(m,
                                     "ConvergenceStudy",
                                     "The result of converge(): one row per n and the fitted slopes of the error, the "
                                     "bound and the time against n; status \"not run\" (no rows, no slopes) until run, "
                                     "\"completed\" with the slopes, \"no_slope\" with fewer than 2 successful rows.");
  AddSummaryShape(study);
  study.def_readonly("rows", &ConvergenceStudy::rows)
      .def_readonly("error_slope", &ConvergenceStudy::error_slope)
      .def_readonly("bound_slope", &ConvergenceStudy::bound_slope)
      .def_readonly("time_slope", &ConvergenceStudy::time_slope)
      .def_readonly("bound_holds", &ConvergenceStudy::bound_holds)
      .def_readonly("failed_rows", &ConvergenceStudy::failed_rows)
      .def(
          "column",
          [](const ConvergenceStudy& s, const std::string& name) {
            static const std::map<std::string, double ConvergenceRow::*> kColumns{
                {"plan_seconds", &ConvergenceRow::plan_seconds},
                {"measured_error", &ConvergenceRow::measured_error},
                {"polyline_error", &ConvergenceRow::polyline_error},
                {"bound", &ConvergenceRow::bound},
                {"theorem_2_6", &ConvergenceRow::theorem_2_6},
                {"corollary_3", &ConvergenceRow::corollary_3},
                {"max_pass_miss", &ConvergenceRow::max_pass_miss}};
            if (name == "n") return Stack<1>(s.rows, [](const ConvergenceRow& r) { return Scalar1(r.n); });
            const auto it = kColumns.find(name);
            if (it == kColumns.end()) throw std::invalid_argument("column: value '" + name + "': unknown column");
            return Stack<1>(s.rows, [&](const ConvergenceRow& r) { return Scalar1(r.*(it->second)); });
          },
          py::arg("name"),
          "One column of the rows as an array: n, measured_error, polyline_error, bound, ...");
  m.def("log_log_slope",
        &LogLogSlope,
        py::arg("x"),
        py::arg("y"),
        "The least-squares slope of log(y) against log(x) (the convergence rate).");
  m.def("_converge",
        &RunConvergenceStudy,
        py::arg("problem"),
        py::arg("options"),
        py::call_guard<py::gil_scoped_release>());
}

}  // namespace

void BindIsoparallel(py::module_& m);     // bind_isoparallel.cc
void BindExactArrival(py::module_& m);    // bind_isoparallel.cc
void BindRigLimits(py::module_& m);       // bind_rig_limits.cc
void BindFewestImpulses(py::module_& m);  // bind_fewest.cc
void BindIdentify(py::module_& m);        // bind_identify.cc

void BindSolvers(py::module_& m) {
  BindJoin(m);
  BindReach(m);
  BindBounds(m);
  BindPlanInputs(m);
  BindPlanStep(m);
  BindPlanSummary(m);
  BindConvergence(m);
  BindIsoparallel(m);
  BindRigLimits(m);
  BindExactArrival(m);
  BindFewestImpulses(m);
  BindIdentify(m);
}

}  // namespace plateball::python
