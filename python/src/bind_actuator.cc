// Python binding: the actuator's commands of a real rig (docs/rig.md): the plate impulse J of an
// impulse (Newton-Euler of ball and plate), the mean forces of a pulse and the friction they need.
#include "bind_common.h"
#include "plateball/actuator_command.h"
#include "plateball/impulse_planner.h"
#include "plateball/plate_impulse.h"

namespace plateball::python {

void BindActuator(py::module_& m) {
  py::class_<PlateImpulse>(m,
                           "PlateImpulse",
                           "The impulses of one jump delta_omega of the ball's angular velocity, in the units of "
                           "PhysicalParameters (N s and N m s for SI input).")
      .def_readonly("plate",
                    &PlateImpulse::plate,
                    "J: the impulse the actuator gives the upper plate (depends on the ball's orientation)")
      .def_readonly("top_contact", &PlateImpulse::top_contact, "friction impulse of the upper plate on the ball")
      .def_readonly("bottom_contact", &PlateImpulse::bottom_contact, "friction impulse of the lower plate on the ball")
      .def_readonly("torsion", &PlateImpulse::torsion, "vertical angular impulse of the contacts (no spin)")
      .def_readonly("plate_velocity_change",
                    &PlateImpulse::plate_velocity_change,
                    "the plate's velocity change 2 r delta_omega x e3");
  m.def("plate_impulse_for",
        &PlateImpulseFor,
        py::arg("physical"),
        py::arg("z"),
        py::arg("delta_omega"),
        "The PlateImpulse that changes omega by the horizontal delta_omega while the symmetry axis is the unit "
        "vector z (ValueError naming the field for invalid input).");
  py::class_<PulseOptions> options(m,
                                   "PulseOptions",
                                   "A pulse and its contacts: duration (s), preload (N), gravity (m/s^2), "
                                   "static_friction mu_s and torsional_friction ell (m); 0 friction: not given.");
  WithKeywordInit(options)
      .def_readwrite("duration", &PulseOptions::duration, "delta (s) > 0: the mean force is J / delta")
      .def_readwrite("preload", &PulseOptions::preload, "extra normal force (N) on the upper plate")
      .def_readwrite("gravity", &PulseOptions::gravity, "g (m/s^2)")
      .def_readwrite("static_friction", &PulseOptions::static_friction, "mu_s of both contacts; 0: not given")
      .def_readwrite("torsional_friction", &PulseOptions::torsional_friction, "ell (m) of both contacts; 0: not given")
      .def("validate", &PulseOptions::Validate, "Empty when valid; else 'pulse.FIELD: value V: what is wrong'.");
  py::class_<PulseForces>(m, "PulseForces", "The mean forces of one pulse (N, N m) and the friction they need.")
      .def_readonly("mean_force", &PulseForces::mean_force, "J / delta on the upper plate (N)")
      .def_readonly("top_normal_load", &PulseForces::top_normal_load, "M_plate g + preload (N)")
      .def_readonly("bottom_normal_load", &PulseForces::bottom_normal_load, "top load + M_ball g (N)")
      .def_readonly("top_tangential_force", &PulseForces::top_tangential_force, "top friction force (N)")
      .def_readonly("bottom_tangential_force", &PulseForces::bottom_tangential_force, "bottom friction force (N)")
      .def_readonly("torsional_torque", &PulseForces::torsional_torque, "torque about the vertical (N m)")
      .def_readonly("sliding_friction_needed",
                    &PulseForces::sliding_friction_needed,
                    "the least mu_s with which neither contact slides (inf without a normal load)")
      .def_readonly("torsional_friction_needed",
                    &PulseForces::torsional_friction_needed,
                    "the least ell (m) with which the ball does not spin")
      .def_readonly("slides", &PulseForces::slides, "static_friction given and below the need")
      .def_readonly("spins", &PulseForces::spins, "torsional_friction given and below the need");
  m.def("pulse_forces_for",
        &PulseForcesFor,
        py::arg("physical"),
        py::arg("impulse"),
        py::arg("options") = PulseOptions{},
        "The PulseForces of a pulse giving the PlateImpulse `impulse` over options.duration.");
}

// The actuator's commands of a plan's steps (PlanSummary methods).
void BindPlanActuator(py::class_<PlanSummary>& plan) {
  plan.def(
          "plate_impulses",
          [](const PlanSummary& s, const PhysicalParameters& physical) {
            return Stack<3>(s.steps, [&](const PlanStep& q) {
              const Eigen::RowVector3d j = PlateImpulseFor(physical, q.state_before.z, q.delta_omega).plate.transpose();
              return j;
            });
          },
          py::arg("physical"),
          "(n, 3): the plate impulse J of every step (PlateImpulseFor at its axis before the impulse), as the "
          "tools' JSON reports it in steps[].actuator.plate_impulse")
      .def(
          "pulse_forces",
          [](const PlanSummary& s, const PhysicalParameters& physical, const PulseOptions& options) {
            std::vector<PulseForces> out;
            for (const PlanStep& q : s.steps)
              out.push_back(
                  PulseForcesFor(physical, PlateImpulseFor(physical, q.state_before.z, q.delta_omega), options));
            return out;
          },
          py::arg("physical"),
          py::arg("options") = PulseOptions{},
          "The PulseForces of every step's pulse (steps[].actuator.pulse in the tools' JSON).");
}

}  // namespace plateball::python
