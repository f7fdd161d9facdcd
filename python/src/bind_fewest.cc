// Python binding: the fewest-impulse search (fewest_impulses.h): its problem, options,
// summary with the Pareto table, and the exact-arrival problem that replays a row's impulses.
#include <optional>

#include "bind_common.h"
#include "field_binding.h"
#include "interrupt.h"
#include "plateball/fewest_impulses.h"

namespace plateball::python {

namespace {

void BindFewestInputs(py::module_& m) {
  py::class_<FewestImpulsesOptions> options(m,
                                            "FewestImpulsesOptions",
                                            "Options of fewest_impulses(): the counts searched, the starts per count, "
                                            "the search window and the tolerances of an exact arrival.");
  DefFieldAttributes(WithKeywordInit(options))
      .def("validate",
           &FewestImpulsesOptions::Validate,
           "Empty when the options are valid; else a message naming the field and its value.");
  py::class_<FewestImpulsesProblem, StartState> problem(
      m, "FewestImpulsesProblem", "The fewest impulses that bring the ball to (x1, A1) exactly.");
  WithKeywordInit(problem)
      .def_readwrite("start_at_rest", &FewestImpulsesProblem::start_at_rest)
      .def_readwrite("stop_at_goal", &FewestImpulsesProblem::stop_at_goal)
      .def_readwrite("x1", &FewestImpulsesProblem::x1)
      .def_readwrite("goal_orientation", &FewestImpulsesProblem::A1)
      .def_readwrite("orientation_only", &FewestImpulsesProblem::orientation_only)
      .def_readwrite("limits",
                     &FewestImpulsesProblem::limits,
                     "the rig's limits (RigLimits): only arrivals within them count; empty: none")
      .def_readwrite("physical",
                     &FewestImpulsesProblem::physical,
                     "the masses behind the impulse bounds and the total impulse (PhysicalParameters or None)");
}

void BindFewestCount(py::module_& m) {
  py::class_<FewestImpulsesCount>(
      m, "FewestImpulsesCount", "One impulse count of the search (a Pareto row when reached).")
      .def_readonly("impulses", &FewestImpulsesCount::impulses)
      .def_readonly("starts", &FewestImpulsesCount::starts)
      .def_readonly("arrived", &FewestImpulsesCount::arrived)
      .def_readonly("reached", &FewestImpulsesCount::reached)
      .def_property_readonly(
          "verdict",
          [](const FewestImpulsesCount& c) { return ToString(c.verdict); },
          "reached, generically_impossible (2n below the conditions) or not_found (not proved impossible)")
      .def_readonly("by_continuation", &FewestImpulsesCount::by_continuation)
      .def_readonly("plan", &FewestImpulsesCount::plan)
      .def_readonly("stop", &FewestImpulsesCount::stop)
      .def_readonly("total_time", &FewestImpulsesCount::total_time)
      .def_readonly("path_length", &FewestImpulsesCount::path_length)
      .def_readonly("position_error", &FewestImpulsesCount::position_error)
      .def_readonly("orientation_error", &FewestImpulsesCount::orientation_error)
      .def_readonly("x_final", &FewestImpulsesCount::x_final)
      .def_readonly("orientation_final", &FewestImpulsesCount::A_final)
      .def_readonly("parameters", &FewestImpulsesCount::parameters)
      .def_readonly(
          "total_impulse",
          &FewestImpulsesCount::total_impulse,
          "sum of the norm of J over the impulses with physical parameters, else of the plate velocity changes")
      .def_readonly("deviation",
                    &FewestImpulsesCount::deviation,
                    "the interior impulse points against the straight line x0 -> x1 cut into n equal parts (root of "
                    "the sum of squares)")
      .def_readonly("within_limits", &FewestImpulsesCount::within_limits, "arrivals that met the rig's limits")
      .def_readonly(
          "active", &FewestImpulsesCount::active, "limits active at the row's arrival (with limits, when reached)")
      .def_readonly("blocking",
                    &FewestImpulsesCount::blocking,
                    "not reached under limits: the limits active at the closest feasible arrival")
      .def_readonly(
          "check", &FewestImpulsesCount::check, "with limits, when reached: the independent replay check (RigCheck)");
}

}  // namespace

void BindFewestImpulses(py::module_& m) {
  BindFewestInputs(m);
  BindFewestCount(m);
  py::class_<FewestImpulsesSummary> summary(
      m,
      "FewestImpulsesSummary",
      "The result of fewest_impulses(): the fewest impulse count found, one row per count searched (the Pareto table) "
      "and what was searched; status \"not run\" until solved.");
  AddSummaryShape(summary);
  summary.def_readonly("fewest", &FewestImpulsesSummary::fewest)
      .def_readonly("counts", &FewestImpulsesSummary::counts)
      .def_readonly("minimal_for_generic_goal",
                    &FewestImpulsesSummary::minimal_for_generic_goal,
                    "Every smaller count is impossible for a generic goal (dimension count).")
      .def_readonly("max_total_time", &FewestImpulsesSummary::max_total_time)
      .def_readonly("searched", &FewestImpulsesSummary::searched)
      .def_readonly("rollouts", &FewestImpulsesSummary::rollouts)
      .def_readonly("limited", &FewestImpulsesSummary::limited, "True when the problem had rig limits")
      .def_readonly("constrained_solves",
                    &FewestImpulsesSummary::constrained_solves,
                    "arrivals taken through the constrained solver (SLSQP)")
      .def_readonly("evaluations", &FewestImpulsesSummary::evaluations, "SLSQP evaluations of those solves")
      .def_readonly("blocking",
                    &FewestImpulsesSummary::blocking,
                    "status limits_not_met: the limits that block the counts that arrive without them")
      .def_property_readonly(
          "fewest_count",
          [](const FewestImpulsesSummary& s) -> std::optional<FewestImpulsesCount> {
            const FewestImpulsesCount* f = s.Fewest();
            return f ? std::optional<FewestImpulsesCount>(*f) : std::nullopt;
          },
          "The row of the fewest count (None when not found).");
  m.def(
      "_fewest_impulses",
      [](const FewestImpulsesProblem& problem, FewestImpulsesOptions options) {
        const Interruptible interrupt;  // Ctrl-C abandons the search (KeyboardInterrupt)
        options.progress = [interrupt](int, int) { interrupt.Check(); };
        return interrupt.Run([&] { return SolveFewestImpulses(problem, options); });
      },
      py::arg("problem"),
      py::arg("options"),
      py::call_guard<py::gil_scoped_release>());
  m.def("replay_problem_for",
        &ReplayProblemFor,
        py::arg("problem"),
        py::arg("impulses"),
        "The exact-arrival problem that replays a count's impulses (for replay_exact_arrival).");
}

}  // namespace plateball::python
