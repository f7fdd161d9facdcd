// Python binding: the isoparallel problem (section 2.2), its impulsive approximation and the exact
// arrival (exact_arrival.h).
#include <chrono>
#include <future>

#include "bind_common.h"
#include "field_binding.h"
#include "interrupt.h"
#include "plateball/elastica.h"
#include "plateball/exact_arrival.h"
#include "plateball/impulse.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_certificate.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/so3.h"

namespace plateball::python {

void BindExactArrivalLimits(py::class_<ExactArrivalProblem>& problem,
                            py::class_<ExactArrivalSummary>& summary,
                            py::module_& m);  // bind_rig_limits.cc

namespace {

using Scalar1 = Eigen::Matrix<double, 1, 1>;

// (n + 1, 2) points of a function of arc length s in [0, length].
template <typename F>
Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> SampleArc(double length, int n, F&& position) {
  RequireCount("n", n, 1, 1000000);
  std::vector<int> i(static_cast<std::size_t>(n) + 1);
  for (std::size_t k = 0; k < i.size(); ++k) i[k] = static_cast<int>(k);
  return Stack<2>(i, [&](int k) { return Eigen::RowVector2d(position(length * k / n).transpose()); });
}

void BindElastica(py::module_& m) {
  py::class_<ElasticaParameters>(m,
                                 "ElasticaParameters",
                                 "The three pendulum parameters (G, energy, phase) of section 2.2 in the form the "
                                 "closed forms use, plus the direction g_W of W (the plane's rotation freedom).")
      .def_property_readonly("regime", [](const ElasticaParameters& p) { return ToString(p.regime); })
      .def_readonly("rate", &ElasticaParameters::rate)
      .def_readonly("modulus", &ElasticaParameters::modulus)
      .def_readonly("phase", &ElasticaParameters::phase)
      .def_readonly("heading_w", &ElasticaParameters::heading_w);
  py::class_<Elastica>(
      m, "Elastica", "An optimal path: the heading obeys the pendulum g'' = -G cos(g - g_W) (Figure 6).")
      .def(py::init<const ElasticaParameters&>(), py::arg("parameters"))
      .def_static("from_initial_state",
                  &Elastica::FromInitialState,
                  py::arg("G"),
                  py::arg("heading_w"),
                  py::arg("heading0"),
                  py::arg("curvature0"),
                  "The path with g'' = -G cos(g - g_W), g(0) = heading0, g'(0) = curvature0 (G >= 0). Raises "
                  "ValueError on the separatrix (E = G to 1e-12 relative) or for invalid values.")
      .def_property_readonly("parameters", &Elastica::parameters)
      .def_property_readonly("G", &Elastica::G)
      .def_property_readonly("energy", &Elastica::Energy)
      .def_property_readonly("period", &Elastica::Period)
      .def_property_readonly("drift_per_period", &Elastica::DriftPerPeriod)
      .def("pendulum_angle",
           py::vectorize(&Elastica::PendulumAngle),
           py::arg("s"),
           "The pendulum angle theta(s) = g(s) - g_W + pi/2 at arc length s (a number or an array).")
      .def("heading",
           py::vectorize(&Elastica::Heading),
           py::arg("s"),
           "The heading g(s) of the tangent at arc length s (a number or an array), continuous in s.")
      .def("curvature",
           py::vectorize(&Elastica::Curvature),
           py::arg("s"),
           "The curvature g'(s) at arc length s (a number or an array).")
      .def("tangent", &Elastica::Tangent, py::arg("s"), "Unit tangent x'(s).")
      .def("position", &Elastica::Position, py::arg("s"), "x(s) - x(0), in closed form.");
}

void BindIsoparallelInputs(py::module_& m) {
  py::class_<IsoparallelOptions> options(
      m,
      "IsoparallelOptions",
      "Options of isoparallel(). A problem file's \"isoparallel.solver\" section (plus its seed and integration "
      "section) sets them, with the same ranges as validate().");
  DefFieldAttributes(WithKeywordInit(options))
      .def("validate",
           &IsoparallelOptions::Validate,
           "Empty when valid, else a message naming the field, the value and the bound.");
  py::class_<IsoparallelProblem> problem(
      m, "IsoparallelProblem", "Shortest path from (start, A0) to (goal, A1) (section 2.2).");
  WithKeywordInit(problem)
      .def_readwrite("start", &IsoparallelProblem::start)
      .def_readwrite("goal", &IsoparallelProblem::goal)
      .def_readwrite("start_orientation", &IsoparallelProblem::start_orientation)
      .def_readwrite("goal_orientation", &IsoparallelProblem::goal_orientation);
  py::class_<IsoparallelSolution>(
      m, "IsoparallelSolution", "One optimal path: x(s) = start + elastica.Position(s), s in [0, length].")
      .def_readonly("parameters", &IsoparallelSolution::parameters)
      .def_readonly("start", &IsoparallelSolution::start)
      .def_readonly("length", &IsoparallelSolution::length)
      .def_readonly("crossing", &IsoparallelSolution::crossing)
      .def_readonly("G", &IsoparallelSolution::G)
      .def_readonly("energy", &IsoparallelSolution::energy)
      .def_readonly("periods", &IsoparallelSolution::periods)
      .def_readonly("family", &IsoparallelSolution::family)
      .def_readonly("shooting_residual", &IsoparallelSolution::shooting_residual)
      .def_readonly("orientation_residual", &IsoparallelSolution::orientation_residual)
      .def_readonly("orientation_error", &IsoparallelSolution::orientation_error)
      .def_readonly("endpoint_error", &IsoparallelSolution::endpoint_error)
      .def_readonly("conjugate_time",
                    &IsoparallelSolution::conjugate_time,
                    "First conjugate time along the extremal (inf: none up to 2x the length).")
      .def_readonly("locally_optimal",
                    &IsoparallelSolution::locally_optimal,
                    "No conjugate point strictly before the end (Jacobi's condition); not global optimality.")
      .def("elastica",
           &IsoparallelSolution::Path,
           "The path as an Elastica (from the origin, before the shift to start).")
      .def("position_at",
           &IsoparallelSolution::PositionAt,
           py::arg("s"),
           "The contact point at arc length s along the path.")
      .def(
          "points",
          [](const IsoparallelSolution& s, int n) {
            return SampleArc(s.length, n, [&](double a) { return s.PositionAt(a); });
          },
          py::arg("n") = 400,
          "(n + 1, 2) points at equal arc length");
}

void BindIsoparallelSolve(py::module_& m) {
  py::class_<IsoparallelSummary> summary(
      m,
      "IsoparallelSummary",
      "The result of isoparallel(): the solutions found (shortest first), the Maxwell pairs, the search's counts and "
      "whether the family enumeration is complete; status \"not run\" until solved.");
  AddSummaryShape(summary);
  summary.def_readonly("problem", &IsoparallelSummary::problem)
      .def_readonly("options", &IsoparallelSummary::options)
      .def_property_readonly("method", [](const IsoparallelSummary& s) { return ToString(s.method); })
      .def_readonly("complete", &IsoparallelSummary::complete)
      .def_readonly("periods_searched", &IsoparallelSummary::periods_searched)
      .def_readonly("solutions", &IsoparallelSummary::solutions)
      .def_property_readonly(
          "maxwell_pairs",
          [](const IsoparallelSummary& s) {
            std::vector<std::pair<int, int>> pairs;
            for (const MaxwellPair& m : s.maxwell_pairs) pairs.emplace_back(m.first, m.second);
            return pairs;
          },
          "Index pairs of distinct solutions of equal length (Maxwell points at the goal).")
      .def_readonly("local_solves", &IsoparallelSummary::local_solves)
      .def_readonly("converged_solves", &IsoparallelSummary::converged_solves)
      .def_readonly("evaluations", &IsoparallelSummary::evaluations)
      .def_readonly("searched_length", &IsoparallelSummary::searched_length)
      .def_readonly("time_seconds", &IsoparallelSummary::time_seconds)
      .def("shortest", &IsoparallelSummary::Shortest, "The shortest solution (RuntimeError when there is none).")
      .def_property_readonly("full_report", &IsoparallelSummary::FullReport)
      .def_property_readonly("lengths", [](const IsoparallelSummary& s) {
        return Stack<1>(s.solutions, [](const IsoparallelSolution& q) { return Scalar1(q.length); });
      });
  m.def("_isoparallel",
        &SolveIsoparallel,
        py::arg("problem"),
        py::arg("options"),
        py::call_guard<py::gil_scoped_release>());
  m.def("verify_rolling",
        &VerifyRolling,
        py::arg("solution"),
        py::arg("integration") = IntegrationOptions{},
        py::call_guard<py::gil_scoped_release>(),
        "The reorientation of rolling along the solution (Runge-Kutta-Fehlberg 7(8), independent of the solver).");
  m.def("optimal_path",
        &OptimalPath,
        py::arg("solution"),
        "The smooth curve of an isoparallel solution (for planning it with impulses).");
  m.def("initial_angles_from_orientation",
        &InitialAnglesFromOrientation,
        py::arg("orientation"),
        py::arg("psi"),
        "The angles (theta, phi, psi) of an orientation with the given psi.");
  py::class_<IsoparallelPlanProblem> plan(
      m, "IsoparallelPlanProblem", "The impulsive approximation of an optimal path (Figure 7).");
  WithKeywordInit(plan)
      .def_readwrite("model", &IsoparallelPlanProblem::model)
      .def_readwrite("psi", &IsoparallelPlanProblem::psi)
      .def_readwrite("mu", &IsoparallelPlanProblem::mu)
      .def_readwrite("orientation", &IsoparallelPlanProblem::A0)
      .def_readwrite("solution", &IsoparallelPlanProblem::solution)
      .def_readwrite("impulses", &IsoparallelPlanProblem::impulses);
  m.def("_plan_optimal_path",
        &PlanOptimalPath,
        py::arg("problem"),
        py::arg("options"),
        py::call_guard<py::gil_scoped_release>());
}

// The certificate of a general target (isoparallel_certificate.h): the solver's summary in, every
// solution up to the cap proved (or the piece that did not close) out.
void BindIsoparallelCertificate(py::module_& m) {
  py::class_<IsoparallelCertificateOptions> options(
      m,
      "IsoparallelCertificateOptions",
      "Options of certify_isoparallel(): the length cap, the box budget per piece and the threads.");
  WithKeywordInit(options)
      .def_readwrite("cap_factor", &IsoparallelCertificateOptions::cap_factor)
      .def_readwrite("length_cap", &IsoparallelCertificateOptions::length_cap)
      .def_readwrite("max_boxes", &IsoparallelCertificateOptions::max_boxes)
      .def_readwrite("threads", &IsoparallelCertificateOptions::threads)
      .def("validate",
           &IsoparallelCertificateOptions::Validate,
           "Empty when valid, else a message naming the field, the value and the bound.");
  py::class_<IsoparallelCertificatePiece>(
      m, "IsoparallelCertificatePiece", "One piece of parameter space and what its certificate gave.")
      .def_readonly("name", &IsoparallelCertificatePiece::name)
      .def_readonly("closed", &IsoparallelCertificatePiece::closed)
      .def_readonly("result", &IsoparallelCertificatePiece::result)
      .def_readonly("boxes", &IsoparallelCertificatePiece::boxes)
      .def_readonly("resolved_volume", &IsoparallelCertificatePiece::resolved_volume)
      .def_readonly("proved", &IsoparallelCertificatePiece::proved)
      .def_readonly("cpu_seconds", &IsoparallelCertificatePiece::cpu_seconds);
  py::class_<CertifiedSolution>(
      m,
      "CertifiedSolution",
      "A solution proved the only one of a box, in canonical parameters (k >= 0; the phase of the Jacobi argument in "
      "[0, one period); an oscillating path written with a positive rate).")
      .def_property_readonly("regime", [](const CertifiedSolution& c) { return ToString(c.regime); })
      .def_readonly("rate", &CertifiedSolution::rate)
      .def_readonly("modulus", &CertifiedSolution::modulus)
      .def_readonly("phase", &CertifiedSolution::phase)
      .def_readonly("length", &CertifiedSolution::length)
      .def_readonly("solver_index", &CertifiedSolution::solver_index);
  py::class_<IsoparallelCertificate> certificate(
      m,
      "IsoparallelCertificate",
      "The result of certify_isoparallel(): parameter space cut into pieces of boxes, each excluded by interval bounds "
      "or proved to hold exactly one solution; the proved solutions up to the length cap and the solver's solutions "
      "they confirm or that it missed.");
  AddSummaryShape(certificate);
  certificate.def_property_readonly("complete", &IsoparallelCertificate::IsComplete)
      .def_readonly("length_cap", &IsoparallelCertificate::length_cap)
      .def_readonly("straight_residual", &IsoparallelCertificate::straight_residual)
      .def_readonly("solutions", &IsoparallelCertificate::solutions)
      .def_readonly("solver_unproved", &IsoparallelCertificate::solver_unproved)
      .def_readonly("pieces", &IsoparallelCertificate::pieces)
      .def_readonly("boxes", &IsoparallelCertificate::boxes)
      .def_readonly("cpu_seconds", &IsoparallelCertificate::cpu_seconds)
      .def_readonly("time_seconds", &IsoparallelCertificate::time_seconds)
      .def_property_readonly("missed_by_solver", &IsoparallelCertificate::MissedBySolver)
      .def_property_readonly("full_report", &IsoparallelCertificate::FullReport);
  // Ctrl-C stops every piece within about a thousand boxes (KeyboardInterrupt). The pieces run on
  // their own threads while the calling thread checks the signal handlers every kSignalPoll: a
  // piece left running alone on a worker thread would otherwise never see them.
  m.def(
      "_certify_isoparallel",
      [](const IsoparallelSummary& summary, IsoparallelCertificateOptions options) {
        constexpr std::chrono::milliseconds kSignalPoll{20};
        const Interruptible interrupt;
        options.interrupted = [interrupt] { return interrupt.Requested(); };
        std::future<IsoparallelCertificate> run =
            std::async(std::launch::async, [&] { return CertifyIsoparallel(summary, options); });
        while (run.wait_for(kSignalPoll) != std::future_status::ready) interrupt.Requested();
        IsoparallelCertificate certificate = run.get();
        interrupt.RaiseIfRequested();
        return certificate;
      },
      py::arg("summary"),
      py::arg("options"),
      py::call_guard<py::gil_scoped_release>());
}

void BindExactInputs(py::module_& m) {
  py::class_<ExactArrivalOptions> options(
      m,
      "ExactArrivalOptions",
      "Options of steer(): the tolerances of the exact arrival, the Gauss-Newton iterations, the rollouts' and the "
      "Jacobian's integration and the warm start's plan options.");
  DefFieldAttributes(WithKeywordInit(options))
      .def("validate",
           &ExactArrivalOptions::Validate,
           "Empty when the options are valid; else a message naming the field and its value.");
  py::class_<ExactArrivalProblem, StartState> problem(
      m, "ExactArrivalProblem", "Arrive at (x1, A1) exactly with n impulses near a reference path.");
  WithKeywordInit(problem)
      .def_readwrite("reference", &ExactArrivalProblem::reference)
      .def_readwrite("impulses", &ExactArrivalProblem::impulses)
      .def_readwrite("x1", &ExactArrivalProblem::x1)
      .def_readwrite("goal_orientation", &ExactArrivalProblem::A1)
      .def_readwrite("start_at_rest", &ExactArrivalProblem::start_at_rest)
      .def_readwrite("stop_at_goal", &ExactArrivalProblem::stop_at_goal);
  py::class_<ExactImpulse>(m, "ExactImpulse", "One impulse k at time t_impulse, then the free arc of duration t_k.")
      .def_property_readonly(
          "kind",
          [](const ExactImpulse& q) { return ToString(q.kind); },
          "energy_preserving, start (0 -> mu) or stop (-> 0), as the tool writes it")
      .def_readonly("t_impulse", &ExactImpulse::t_impulse)
      .def_readonly("position", &ExactImpulse::position)
      .def_readonly("delta_psi", &ExactImpulse::delta_psi)
      .def_readonly("duration", &ExactImpulse::duration)
      .def_readonly("delta_omega", &ExactImpulse::delta_omega)
      .def_readonly("plate_velocity_change", &ExactImpulse::plate_velocity_change)
      .def_readonly("angles_before", &ExactImpulse::angles_before)
      .def_readonly("mu_before", &ExactImpulse::mu_before)
      .def_readonly("mu_after", &ExactImpulse::mu_after)
      .def_readonly("planned_position", &ExactImpulse::planned_position)
      .def_readonly("planned_delta_psi", &ExactImpulse::planned_delta_psi)
      .def_readonly("planned_duration", &ExactImpulse::planned_duration)
      .def_readonly("tick",
                    &ExactImpulse::tick,
                    "the index on the rig's tick grid (t_impulse = tick x limits.tick), or -1 without a tick");
  py::class_<ReplayResult>(m,
                           "ReplayResult",
                           "Independent check: re-integrates the reported impulses with FreeMotion (one stored period "
                           "per arc, its own tolerances) from the problem's start and returns the final position and "
                           "orientation. Used by the tests and the tools.")
      .def_readonly("x", &ReplayResult::x)
      .def_readonly("orientation", &ReplayResult::A)
      .def_readonly("position_error", &ReplayResult::position_error)
      .def_readonly("orientation_error", &ReplayResult::orientation_error);
}

// Positions of the exact trajectory: each arc from its impulse (positions only).
Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> ExactTrajectory(const ExactArrivalSummary& s,
                                                                          const ExactArrivalProblem& p,
                                                                          int per_arc) {
  RequireCount("samples_per_arc", per_arc, 1, 100000);
  std::vector<Eigen::Vector2d> points;
  for (const ExactImpulse& k : s.impulses) {
    const Impulse i = EnergyPreservingImpulse(k.angles_before, p.mu, k.delta_psi, p.model);
    const FreeMotion f(
        p.model,
        FreeMotionStart{
            i.state_after, k.position, AlignOrientationToAxis(Eigen::Matrix3d::Identity(), i.state_after.z)});
    for (int j = (points.empty() ? 0 : 1); j <= per_arc; ++j) points.push_back(f.PositionAt(k.duration * j / per_arc));
  }
  return Stack<2>(points, [](const Eigen::Vector2d& q) { return q.transpose(); });
}

}  // namespace

void BindIsoparallel(py::module_& m) {
  BindElastica(m);
  BindIsoparallelInputs(m);
  BindIsoparallelSolve(m);
  BindIsoparallelCertificate(m);
}

void BindExactArrival(py::module_& m) {
  BindExactInputs(m);
  py::class_<ExactArrivalSummary> summary(
      m,
      "ExactArrivalSummary",
      "The result of steer(): the impulses that arrive exactly, the final errors, the deviation from the reference and "
      "the stop impulse; status \"not run\" until solved.");
  auto problem = py::reinterpret_borrow<py::class_<ExactArrivalProblem>>(m.attr("ExactArrivalProblem"));
  BindExactArrivalLimits(problem, summary, m);
  AddSummaryShape(summary);
  summary.def_readonly("impulses", &ExactArrivalSummary::impulses)
      .def_readonly("stop", &ExactArrivalSummary::stop, "the impulse at the goal with stop_at_goal, else None")
      .def_readonly("x_final", &ExactArrivalSummary::x_final)
      .def_readonly("orientation_final", &ExactArrivalSummary::A_final)
      .def_readonly("position_error", &ExactArrivalSummary::position_error)
      .def_readonly("orientation_error", &ExactArrivalSummary::orientation_error)
      .def_readonly("deviation", &ExactArrivalSummary::deviation)
      .def_readonly("max_pass_displacement", &ExactArrivalSummary::max_pass_displacement)
      .def_readonly("total_time", &ExactArrivalSummary::total_time)
      .def_readonly("iterations", &ExactArrivalSummary::iterations)
      .def_readonly("iteration_limit_reached", &ExactArrivalSummary::iteration_limit_reached)
      .def_readonly("rollouts", &ExactArrivalSummary::rollouts)
      .def_readonly("planned_position_error", &ExactArrivalSummary::planned_position_error)
      .def_readonly("planned_orientation_error", &ExactArrivalSummary::planned_orientation_error)
      .def_readonly("planned_total_time", &ExactArrivalSummary::planned_total_time)
      .def_property_readonly("positions",
                             [](const ExactArrivalSummary& s) {
                               return Stack<2>(s.impulses,
                                               [](const ExactImpulse& q) { return q.position.transpose(); });
                             })
      .def_property_readonly("delta_psi",
                             [](const ExactArrivalSummary& s) {
                               return Stack<1>(s.impulses, [](const ExactImpulse& q) { return Scalar1(q.delta_psi); });
                             })
      .def_property_readonly("durations",
                             [](const ExactArrivalSummary& s) {
                               return Stack<1>(s.impulses, [](const ExactImpulse& q) { return Scalar1(q.duration); });
                             })
      .def_property_readonly(
          "plate_velocity_changes",
          [](const ExactArrivalSummary& s) {
            return Stack<3>(s.impulses, [](const ExactImpulse& q) { return q.plate_velocity_change.transpose(); });
          })
      .def("trajectory",
           &ExactTrajectory,
           py::arg("problem"),
           py::arg("samples_per_arc") = 24,
           py::call_guard<py::gil_scoped_release>(),
           "(m, 2) contact points of the exact trajectory");
  m.def("_steer", &SolveExactArrival, py::arg("problem"), py::arg("options"), py::call_guard<py::gil_scoped_release>());
  m.def("replay_exact_arrival",
        &ReplayExactArrival,
        py::arg("problem"),
        py::arg("impulses"),
        py::arg("integration") = IntegrationOptions{1e-14, 1e-14, 2'000'000},
        py::call_guard<py::gil_scoped_release>(),
        "Re-integrates exact-arrival impulses from the problem's start (the independent check).");
}

}  // namespace plateball::python
