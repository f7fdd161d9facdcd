// Python binding: the real-time controller (controller.h) and the nominal plan it follows
// (execution.h's MakeNominalPlan).
#include <memory>
#include <optional>

#include "bind_common.h"
#include "plateball/controller.h"
#include "plateball/execution.h"

namespace plateball::python {
namespace {

void BindNominalPlan(py::module_& m) {
  py::class_<NominalPlan, std::shared_ptr<NominalPlan>>(
      m, "NominalPlan", "A plan with its pass points and goal, as the controller and Execute follow it (execution.h).")
      .def_property_readonly(
          "status",
          [](const NominalPlan& n) { return ToString(n.plan.status); },
          "the plan's status word (only 'success' can be followed)")
      .def_property_readonly(
          "impulses", [](const NominalPlan& n) { return n.plan.steps.size(); }, "the impulses n")
      .def_property_readonly(
          "total_time", [](const NominalPlan& n) { return n.plan.total_time; }, "from the first impulse to the arrival")
      .def_property_readonly(
          "pass_points",
          [](const NominalPlan& n) { return Stack<2>(n.pass_points, [](const Eigen::Vector2d& p) { return p; }); },
          "p(tau_0) ... p(tau_n), shape (n + 1, 2)")
      .def_property_readonly(
          "goal", [](const NominalPlan& n) { return n.goal; }, "the goal contact point p(tau_n)")
      .def_property_readonly(
          "goal_orientation",
          [](const NominalPlan& n) { return n.goal_orientation; },
          "the goal orientation A(T) of rolling along the path")
      .def_property_readonly(
          "plan_orientation_error",
          [](const NominalPlan& n) { return n.plan_orientation_error; },
          "the plan's own final orientation error (rad, Theorem 2.6)");
  m.def(
      "make_nominal_plan",
      [](const PlanProblem& problem, const PlanOptions& options) {
        return std::make_shared<NominalPlan>(MakeNominalPlan(problem, options));
      },
      py::arg("problem"),
      py::arg("options") = PlanOptions{},
      "Plans the problem (ValueError naming the field for invalid input); a failed plan keeps its status.");
}

void BindOptions(py::module_& m) {
  py::class_<ControllerOptions> o(m, "ControllerOptions", "Options of the real-time controller (controller.h).");
  WithKeywordInit(o)
      .def_readwrite("tick_period", &ControllerOptions::tick_period, "the loop's tick (s), in [1e-7, 1]")
      .def_property(
          "strategy",
          [](const ControllerOptions& c) { return ToString(c.strategy); },
          [](ControllerOptions& c, const std::string& w) { c.strategy = ParseExecutionStrategy(w, "strategy"); },
          "'feedback' or 'feedback_exact'")
      .def_readwrite("execution", &ControllerOptions::execution, "exact_window and the exact re-plans' options")
      .def_readwrite("time_budget", &ControllerOptions::time_budget, "wall-clock seconds one update may take")
      .def_readwrite("jump_tolerance",
                     &ControllerOptions::jump_tolerance,
                     "a measured contact point farther than this from the prediction is rejected")
      .def_readwrite("orientation_jump_tolerance",
                     &ControllerOptions::orientation_jump_tolerance,
                     "a measured orientation turned farther than this (rad) is rejected")
      .def_readwrite("rotation_tolerance",
                     &ControllerOptions::rotation_tolerance,
                     "how far a measured orientation may be from a rotation")
      .def_readwrite("physical",
                     &ControllerOptions::physical,
                     "the ball's PhysicalParameters (or None): each impulse also gives the plate impulse J")
      .def("validate", &ControllerOptions::Validate, "'' when valid, else 'FIELD: value V: what is wrong'");
}

void BindOutput(py::module_& m) {
  py::class_<ControllerEstimate>(m, "ControllerEstimate", "The controller's estimate of the ball at one tick.")
      .def_readonly("tick", &ControllerEstimate::tick, "the tick it is for")
      .def_readonly("x", &ControllerEstimate::x, "contact point")
      .def_readonly("orientation", &ControllerEstimate::A, "orientation A (R_WB)")
      .def_readonly("state", &ControllerEstimate::state, "(z, omega) with the nominal lambda");
  py::class_<ControllerOutput>(m, "ControllerOutput", "The answer of one Controller.update.")
      .def_property_readonly(
          "status",
          [](const ControllerOutput& o) { return ToString(o.status); },
          "ok, measurement_rejected, time_out_of_order, done, lost, integration_failure")
      .def_property_readonly(
          "reason",
          [](const ControllerOutput& o) { return std::string(o.reason); },
          "why the measurement was rejected or the tick failed ('' when ok)")
      .def_readonly("tick", &ControllerOutput::tick, "this tick")
      .def_readonly("impulse", &ControllerOutput::impulse, "an impulse is due at this tick")
      .def_readonly("impulse_index", &ControllerOutput::impulse_index, "its index k in the plan")
      .def_readonly("delta_psi", &ControllerOutput::delta_psi, "psi -> psi + delta_psi")
      .def_readonly("delta_omega", &ControllerOutput::delta_omega, "the ball's jump of angular velocity")
      .def_readonly("plate_velocity_change", &ControllerOutput::plate_velocity_change, "2 delta_omega x e3")
      .def_property_readonly(
          "plate_impulse",
          [](const ControllerOutput& o) -> std::optional<Eigen::Vector3d> {
            if (!o.has_plate_impulse) return std::nullopt;
            return o.plate_impulse.plate;
          },
          "the actuator's impulse J (None without physical parameters)")
      .def_readonly("exact_replan", &ControllerOutput::exact_replan, "the impulse comes from a new exact re-plan")
      .def_readonly("next_impulse_tick", &ControllerOutput::next_impulse_tick, "the next impulse's tick (-1: none)")
      .def_readonly("late", &ControllerOutput::late, "the impulse's tick was missed: it fires now")
      .def_readonly("budget_exhausted", &ControllerOutput::budget_exhausted, "the time budget ran out")
      .def_readonly("measurement_used", &ControllerOutput::measurement_used, "the measurement was accepted")
      .def_readonly("now", &ControllerOutput::now, "the estimate after this tick's impulse")
      .def_readonly(
          "at_next_impulse", &ControllerOutput::at_next_impulse, "the estimate predicted just before the next impulse");
}

void BindControllerClass(py::module_& m) {
  py::class_<Controller>(
      m, "Controller", "Feedback for a rig's real-time loop: update(time, x, orientation, omega) once per tick.")
      .def(py::init([](const std::shared_ptr<NominalPlan>& plan, const ControllerOptions& options) {
             return std::make_unique<Controller>(plan, options);
           }),
           py::arg("plan"),
           py::arg("options") = ControllerOptions{},
           "ValueError naming the field for an unusable plan or invalid options.")
      .def(
          "update",
          [](Controller& c,
             double time,
             const Eigen::Vector2d& x,
             const std::optional<Eigen::Matrix3d>& orientation,
             const std::optional<Eigen::Vector3d>& omega) {
            if (orientation.has_value() != omega.has_value())
              throw std::invalid_argument("orientation: value " + std::string(orientation ? "given" : "None") +
                                          ": give the orientation and omega together or neither");
            ControllerMeasurement m;
            m.x = x;
            m.has_orientation = orientation.has_value();
            if (orientation) {
              m.A = *orientation;
              m.omega = *omega;
            }
            return c.Update(time, m);  // a copy: the next update does not change it
          },
          py::arg("time"),
          py::arg("x"),
          py::arg("orientation") = py::none(),
          py::arg("omega") = py::none(),
          "One tick at `time` with the measured contact point (and orientation with omega, or neither).")
      .def_property_readonly("message", &Controller::message, "the last failure's full message")
      .def_property_readonly("exact_solves", &Controller::exact_solves, "exact re-plans that arrived")
      .def_property_readonly("exact_failures", &Controller::exact_failures, "exact re-plans that did not arrive");
}

}  // namespace

void BindController(py::module_& m) {
  BindNominalPlan(m);
  BindOptions(m);
  BindOutput(m);
  BindControllerClass(m);
}

}  // namespace plateball::python
