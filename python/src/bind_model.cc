// Python binding: the ball model, its states, impulses, the free motion and the rolling.
#include <array>

#include "bind_common.h"
#include "field_binding.h"
#include "plateball/angle_form.h"
#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/closed_forms.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"
#include "plateball/integration_options.h"
#include "plateball/join.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"
#include "plateball/start_state.h"

namespace plateball::python {
namespace {

void BindStates(py::module_& m) {
  py::class_<PhysicalParameters> physical(m, "PhysicalParameters", "Physical parameters of the ball (section 2.1).");
  WithKeywordInit(physical)
      .def_readwrite("inertia_1", &PhysicalParameters::inertia_1)
      .def_readwrite("inertia_3", &PhysicalParameters::inertia_3)
      .def_readwrite("ball_mass", &PhysicalParameters::ball_mass)
      .def_readwrite("radius", &PhysicalParameters::radius)
      .def_readwrite("plate_mass", &PhysicalParameters::plate_mass)
      .def("validate",
           &PhysicalParameters::Validate,
           "Empty when valid; otherwise names the first offending field, its value and the bound.");
  py::class_<BallModel>(m, "BallModel", "The ball parameter lambda = (alpha + beta)/(1 + beta), eq. (9).")
      .def(py::init(&BallModel::FromLambda), py::arg("lambda_"))
      .def_static("from_lambda",
                  &BallModel::FromLambda,
                  py::arg("lambda_"),
                  "The model of a given lambda in [1e-3, 1e3]; alpha and beta are then unknown (reported as 0).")
      .def_static("from_alpha_beta",
                  &BallModel::FromAlphaBeta,
                  py::arg("alpha"),
                  py::arg("beta"),
                  "The model of alpha = I3/I1 and beta = M r^2 / I1 (section 2.1): 0 < alpha <= 2 (a rigid body has I3 "
                  "<= 2 I1), beta >= 0.")
      .def_static("from_physical",
                  &BallModel::FromPhysical,
                  py::arg("physical"),
                  "The model of a ball's physical parameters (SI); raises ValueError naming the field when a parameter "
                  "is invalid.")
      .def_property_readonly("lambda_", &BallModel::lambda)
      .def_property_readonly("has_inertia", &BallModel::has_inertia)
      .def_property_readonly("alpha", &BallModel::alpha)
      .def_property_readonly("beta", &BallModel::beta)
      .def_property_readonly("realisable",
                             &BallModel::IsRealisable,
                             "Whether a rigid ball with an upper plate has this model (lambda in (1/2, 4/3]).")
      .def("__repr__", [](const BallModel& b) {
        return "BallModel(lambda_=" + std::string(py::repr(py::float_(b.lambda()))) + ")";
      });
  py::class_<AngleState> angles(m, "AngleState", "The angles (theta, phi, psi) of eqs. (12)-(18).");
  WithKeywordInit(angles)
      .def(py::init([](double theta, double phi, double psi) {
             return AngleState{theta, phi, psi};
           }),
           py::arg("theta"),
           py::arg("phi"),
           py::arg("psi"))
      .def_readwrite("theta", &AngleState::theta)
      .def_readwrite("phi", &AngleState::phi)
      .def_readwrite("psi", &AngleState::psi)
      .def("canonicalize",
           &AngleState::Canonicalize,
           "Same physical state with theta in [0, pi], phi and psi in (-pi, pi].")
      .def("__iter__", [](const AngleState& a) { return py::iter(py::make_tuple(a.theta, a.phi, a.psi)); })
      .def("__repr__", [](const AngleState& a) {
        return "AngleState(theta=" + std::string(py::repr(py::float_(a.theta))) +
               ", phi=" + std::string(py::repr(py::float_(a.phi))) +
               ", psi=" + std::string(py::repr(py::float_(a.psi))) + ")";
      });
  angles.def(py::init([](const std::array<double, 3>& a) { return AngleState{a[0], a[1], a[2]}; }), py::arg("angles"));
  py::implicitly_convertible<py::tuple, AngleState>();
  py::implicitly_convertible<py::list, AngleState>();
  py::class_<BallState> state(m, "BallState", "(z, omega): symmetry axis and spatial angular velocity.");
  WithKeywordInit(state).def_readwrite("z", &BallState::z).def_readwrite("omega", &BallState::omega);
  py::class_<IntegrationOptions> integration(
      m, "IntegrationOptions", "Tolerances and step bound of the ODE integrations.");
  DefFieldAttributes(WithKeywordInit(integration))
      .def("validate",
           &IntegrationOptions::Validate,
           "Empty when valid, else a message naming the field, the value and the bound. Each tolerance must be in "
           "[1e-15, 1) (below, the step size underflows in double precision).");
  m.def("state_from_angles",
        &StateFromAngles,
        py::arg("angles"),
        py::arg("mu"),
        py::arg("model"),
        "The ball state of the angles (theta, phi, psi) and energy mu (section 2.1).");
  m.def("angles_from_state",
        &AnglesFromState,
        py::arg("state"),
        py::arg("model"),
        "The Euler angles (theta, phi, psi) of a ball state (section 2.1).");
  m.def("energy",
        &Energy,
        py::arg("state"),
        py::arg("model"),
        "The energy mu = ``|omega x z|^2 + lambda v0^2``, eq. (9).");
  m.def("conserved_momentum",
        &ConservedMomentum,
        py::arg("state"),
        py::arg("model"),
        "The conserved vector K of the free motion (section 2.1) for a state.");
  m.def("minimum_contact_speed",
        &MinimumContactSpeed,
        py::arg("mu"),
        py::arg("model"),
        "The smallest contact speed of a free motion with energy mu (section 2.1).");
}

void BindImpulses(py::module_& m) {
  py::class_<Impulse>(m, "Impulse", "An impulse at the contact point (section 2.1).")
      .def_readonly("before", &Impulse::before)
      .def_readonly("after", &Impulse::after)
      .def_readonly("mu_before", &Impulse::mu_before)
      .def_readonly("mu_after", &Impulse::mu_after)
      .def_readonly("delta_u", &Impulse::delta_u)
      .def_readonly("delta_v0", &Impulse::delta_v0)
      .def_readonly("delta_omega", &Impulse::delta_omega)
      .def_readonly("plate_velocity_change", &Impulse::plate_velocity_change)
      .def_readonly("state_before", &Impulse::state_before)
      .def_readonly("state_after", &Impulse::state_after);
  m.def("energy_preserving_impulse",
        &EnergyPreservingImpulse,
        py::arg("angles"),
        py::arg("mu"),
        py::arg("delta_psi"),
        py::arg("model"),
        "The energy-preserving impulse psi -> psi + delta_psi at the given angles and mu (section 2.1).");
  m.def("energy_changing_impulse",
        &EnergyChangingImpulse,
        py::arg("angles"),
        py::arg("mu"),
        py::arg("factor"),
        py::arg("model"),
        "An impulse that multiplies the energy mu by `factor` (section 2.1).");
}

void BindTrajectory(py::module_& m) {
  py::class_<Trajectory>(m, "Trajectory", "Samples of a motion as NumPy arrays.")
      .def_property_readonly("t",
                             [](const Trajectory& s) {
                               return Stack<1>(s.samples,
                                               [](const MotionSample& q) { return Eigen::Matrix<double, 1, 1>(q.t); });
                             })
      .def_property_readonly("x",
                             [](const Trajectory& s) {
                               return Stack<2>(s.samples, [](const MotionSample& q) { return q.x.transpose(); });
                             })
      .def_property_readonly("z",
                             [](const Trajectory& s) {
                               return Stack<3>(s.samples, [](const MotionSample& q) { return q.state.z.transpose(); });
                             })
      .def_property_readonly("omega",
                             [](const Trajectory& s) {
                               return Stack<3>(s.samples,
                                               [](const MotionSample& q) { return q.state.omega.transpose(); });
                             })
      .def_property_readonly(
          "angles",
          [](const Trajectory& s) {
            return Stack<3>(s.samples, [](const MotionSample& q) {
              return Eigen::RowVector3d(q.angles.theta, q.angles.phi, q.angles.psi);
            });
          },
          "(n, 3): canonical (theta, phi, psi)")
      .def_property_readonly(
          "energy",
          [](const Trajectory& s) {
            return Stack<1>(s.samples, [](const MotionSample& q) { return Eigen::Matrix<double, 1, 1>(q.energy); });
          })
      .def_property_readonly(
          "orientation",
          [](const Trajectory& s) { return StackMatrices(s.samples, [](const MotionSample& q) { return q.A; }); })
      .def("__len__", [](const Trajectory& s) { return s.samples.size(); });
}

void BindFreeMotion(py::module_& m) {
  py::class_<MotionSample>(m, "MotionSample", "Everything the library reports about the ball at one instant.")
      .def_readonly("t", &MotionSample::t)
      .def_readonly("state", &MotionSample::state)
      .def_readonly("x", &MotionSample::x)
      .def_readonly("orientation", &MotionSample::A)
      .def_readonly("angles", &MotionSample::angles)
      .def_readonly("energy", &MotionSample::energy);
  py::class_<FreeMotion>(m, "FreeMotion", "The free rolling: one period integrated, any time evaluated from it.")
      .def(py::init([](const BallModel& model,
                       const AngleState& angles,
                       double mu,
                       const Eigen::Vector2d& x0,
                       const Eigen::Matrix3d& A0,
                       const IntegrationOptions& integration) {
             return FreeMotion::FromAngles(model, angles, mu, x0, A0, integration);
           }),
           py::arg("model"),
           py::arg("angles"),
           py::arg("mu"),
           py::arg("x0") = Eigen::Vector2d::Zero(),
           py::arg("orientation") = Eigen::Matrix3d::Identity(),
           py::arg("integration") = IntegrationOptions{},
           py::call_guard<py::gil_scoped_release>())
      .def_static(
          "from_state",
          [](const BallModel& model,
             const BallState& state,
             const Eigen::Vector2d& x0,
             const Eigen::Matrix3d& A0,
             const IntegrationOptions& integration) {
            return FreeMotion(model, FreeMotionStart{state, x0, A0}, integration);
          },
          py::arg("model"),
          py::arg("state"),
          py::arg("x0") = Eigen::Vector2d::Zero(),
          py::arg("orientation") = Eigen::Matrix3d::Identity(),
          py::arg("integration") = IntegrationOptions{},
          py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("mu", &FreeMotion::mu)
      .def_property_readonly("period", &FreeMotion::Period)
      .def_property_readonly("drift_per_period", &FreeMotion::DriftPerPeriod)
      .def_property_readonly("mean_velocity", &FreeMotion::MeanVelocity)
      .def_property_readonly("momentum", &FreeMotion::Momentum)
      .def_property_readonly("start_state", [](const FreeMotion& f) { return f.start().state; })
      .def_property_readonly("start_orientation", [](const FreeMotion& f) { return f.start().A0; })
      .def_property_readonly("stored_steps", &FreeMotion::StoredSteps)
      .def("at",
           &FreeMotion::At,
           py::arg("t"),
           "The full sample (a MotionSample) at any real t (negative too) with ``|t| <= 1e12`` periods (beyond, "
           "ValueError: no significant digits would be left), accurate to the integration tolerance.")
      .def("position_at",
           &FreeMotion::PositionAt,
           py::arg("t"),
           "The contact point x(t) only (cheaper than at(): no orientation).")
      .def(
          "sample",
          [](const FreeMotion& f, double t0, double t1, int n) { return Trajectory{f.Sample(t0, t1, n)}; },
          py::arg("t0"),
          py::arg("t1"),
          py::arg("n"),
          py::call_guard<py::gil_scoped_release>(),
          "A Trajectory of n equally spaced samples from t0 to t1 (both included).")
      .def(
          "sample_times",
          [](const FreeMotion& f, const std::vector<double>& times) {
            std::vector<MotionSample> s;
            for (double t : times) s.push_back(f.At(t));
            return Trajectory{s};
          },
          py::arg("times"),
          py::call_guard<py::gil_scoped_release>(),
          "A Trajectory sampled at the given times (any order, any real t).");
}

void BindAngleForm(py::module_& m) {
  py::class_<AngleFormOptions> options(m,
                                       "AngleFormOptions",
                                       "Options of integrate_angle_form(): the integration tolerances and how close to "
                                       "a pole (sin theta) the integration stops.");
  WithKeywordInit(options)
      .def_readwrite("integration", &AngleFormOptions::integration)
      .def_readwrite("pole_threshold", &AngleFormOptions::pole_threshold);
  py::class_<AngleFormResult>(m, "AngleFormResult", "Eqs. (19)-(21) integrated in the angles (not canonicalised).")
      .def_property_readonly("status", [](const AngleFormResult& r) { return ToString(r.status); })
      .def_readonly("message", &AngleFormResult::message)
      .def_readonly("t_reached", &AngleFormResult::t_reached)
      .def_readonly("steps", &AngleFormResult::steps)
      .def_property_readonly(
          "t",
          [](const AngleFormResult& r) {
            return Stack<1>(r.samples, [](const AngleFormSample& q) { return Eigen::Matrix<double, 1, 1>(q.t); });
          })
      .def_property_readonly("angles",
                             [](const AngleFormResult& r) {
                               return Stack<3>(r.samples, [](const AngleFormSample& q) {
                                 return Eigen::RowVector3d(q.angles.theta, q.angles.phi, q.angles.psi);
                               });
                             })
      .def_property_readonly("x", [](const AngleFormResult& r) {
        return Stack<2>(r.samples, [](const AngleFormSample& q) { return q.x.transpose(); });
      });
  m.def("integrate_angle_form",
        &IntegrateAngleForm,
        py::arg("model"),
        py::arg("angles"),
        py::arg("mu"),
        py::arg("x0"),
        py::arg("times"),
        py::arg("options") = AngleFormOptions{},
        py::call_guard<py::gil_scoped_release>(),
        "Eqs. (19)-(21) and x' = (omega_2, -omega_1), sampled at `times` (stops at a pole).");
  py::class_<AppendixSolution>(m, "AppendixSolution", "The closed form of the appendix, eqs. (30)-(34) (corrected).")
      .def(py::init<const BallModel&, const AngleState&, double>(), py::arg("model"), py::arg("angles"), py::arg("mu"))
      .def_property_readonly("period", &AppendixSolution::Period)
      .def_property_readonly("c", [](const AppendixSolution& a) { return a.constants().c; })
      .def("theta", &AppendixSolution::Theta, py::arg("t"), "(30), corrected branch; extended chart for c = 0.")
      .def("w", &AppendixSolution::W, py::arg("t"), "(31) = phi - psi, continuous in t.")
      .def("phi", &AppendixSolution::Phi, py::arg("t"), "from (33), sign corrected.")
      .def("psi", &AppendixSolution::Psi, py::arg("t"), "psi = phi - w at t (from (31) and (33)).");
}

void BindRolling(py::module_& m) {
  m.def("roll_along_segment",
        &RollAlongSegment,
        py::arg("p"),
        py::arg("q"),
        "The reorientation R of rolling along the segment from p to q: the rotation by the length of q - p about e3 x "
        "d.");
  m.def("roll_along_polyline",
        &RollAlongPolyline,
        py::arg("points"),
        "The reorientation R of rolling along the polyline through the points (exact).");
  m.def("roll_along_samples",
        &RollAlongSamples,
        py::arg("points"),
        py::arg("integration") = IntegrationOptions{},
        py::call_guard<py::gil_scoped_release>(),
        "The reorientation R of rolling along the natural cubic spline through the points (integrated).");
  m.def("hat", &Hat, "The skew-symmetric matrix hat(w) with hat(w) v = w x v.");
  m.def("exp_so3", &ExpSO3, "The rotation exp(hat(w)) of a rotation vector w (3x3).");
  m.def("log_so3", &LogSO3, "The rotation vector w with exp(hat(w)) = R and a length of at most pi.");
  m.def("operator_norm_distance",
        &OperatorNormDistance,
        "The operator 2-norm ||A - B|| of two 3x3 matrices (the error the paper compares).");
  m.def("rotation_angle", &RotationAngle, "The angle of a rotation matrix, in [0, pi].");
  m.def("rotation_z", &RotationZ, "The rotation by an angle about e3 (3x3).");
  m.def("align_orientation_to_axis",
        &AlignOrientationToAxis,
        py::arg("orientation"),
        py::arg("z"),
        "The rotation closest to `orientation` whose third column is the unit vector z (minimal rotation).");
}

// The start state, bound once: the problem classes derive from these two (start_state.h).
void BindStartState(py::module_& m) {
  py::class_<StartMotion> motion(
      m, "StartMotion", "The ball at the start without its contact point: model, angles, energy, orientation.");
  WithKeywordInit(motion)
      .def_readwrite("model", &StartMotion::model, "the ball")
      .def_readwrite("initial", &StartMotion::initial, "the angles theta, phi and psi at the start")
      .def_readwrite("mu", &StartMotion::mu, "energy, eq. (9), > 0")
      .def_readwrite(
          "orientation",
          &StartMotion::A0,
          "start orientation R_WB (A0), rotated minimally so that its third column is the axis of `initial`");
  py::class_<StartState, StartMotion> state(m, "StartState", "The ball at the start with its contact point x0.");
  WithKeywordInit(state).def_readwrite("x0", &StartState::x0, "start contact point on the plate");
}

}  // namespace

void BindModel(py::module_& m) {
  BindStates(m);
  BindStartState(m);
  BindImpulses(m);
  BindTrajectory(m);
  BindFreeMotion(m);
  BindAngleForm(m);
  BindRolling(m);
}

}  // namespace plateball::python
