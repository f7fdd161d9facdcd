#include "plateball/exact_arrival.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "check.h"
#include "constrained_arrival.h"
#include "dense_solve.h"
#include "exact_chain.h"
#include "field_check.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"
#include "plateball/so3.h"

namespace plateball {

std::string ToString(ExactArrivalStatus status) {
  switch (status) {
    case ExactArrivalStatus::kNotRun:
      return "not_run";
    case ExactArrivalStatus::kArrived:
      return "arrived";
    case ExactArrivalStatus::kNotReached:
      return "not_reached";
    case ExactArrivalStatus::kWarmStartFailed:
      return "warm_start_failed";
    case ExactArrivalStatus::kIntegrationFailure:
      return "integration_failure";
    case ExactArrivalStatus::kLimitsNotMet:
      return "limits_not_met";
  }
  return "unknown";
}

std::string ToString(ExactImpulseKind kind) {
  switch (kind) {
    case ExactImpulseKind::kEnergyPreserving:
      return "energy_preserving";
    case ExactImpulseKind::kStart:
      return "start";
    case ExactImpulseKind::kStop:
      return "stop";
  }
  return "unknown";
}

std::string ExactArrivalOptions::Validate() const {
  std::string e = internal::CheckRanges(*this);  // tolerances and iterations (the field list)
  if (!e.empty()) return e;
  e = integration.Validate();
  if (!e.empty()) return "integration." + e;
  e = jacobian_integration.Validate();
  if (!e.empty()) return "jacobian_integration." + e;
  return warm_start.Validate();
}

std::string ExactArrivalSummary::BriefReport() const {
  std::ostringstream os;
  os.precision(3);
  os << "ExactArrival: " << ToString(status) << ", n = " << impulses.size() << ", position error = " << position_error
     << ", orientation error = " << orientation_error << " rad, deviation = " << deviation << ", T = " << total_time
     << ", iterations = " << iterations;
  if (!message.empty()) os << " (" << message << ")";
  return os.str();
}

namespace {

using internal::ChainNode;

// The fixed data of one solve: the start, the goal, the reference pass points.
struct Setup {
  const BallModel* model = nullptr;
  double mu = 1.0;
  ChainNode start;
  Eigen::Vector2d x1;
  Eigen::Matrix3d A1;
  std::vector<Eigen::Vector2d> planned;  // p(tau_k), k = 0..n
  IntegrationOptions integration;
  int n = 0;
};

void RollOut(const Setup& s, const Eigen::VectorXd& u, std::vector<ChainNode>& nodes) {
  nodes.resize(static_cast<std::size_t>(s.n) + 1);
  nodes[0] = s.start;
  internal::RollChain(s.model->lambda(), u, s.integration, &nodes);
}

// The five arrival conditions followed by the 2(n-1) pass-point displacements.
Eigen::VectorXd Residuals(const Setup& s, const std::vector<ChainNode>& nodes) {
  Eigen::VectorXd r(5 + 2 * (s.n - 1));
  r.head<5>() = internal::ArrivalResidual(nodes.back(), s.x1, s.A1);
  for (int k = 1; k < s.n; ++k)
    r.segment<2>(5 + 2 * (k - 1)) = nodes[static_cast<std::size_t>(k)].x - s.planned[static_cast<std::size_t>(k)];
  return r;
}

// The exact Jacobian of Residuals (variational equations, src/exact_chain.h).
Eigen::MatrixXd Jacobian(const Setup& s,
                         const Eigen::VectorXd& u,
                         const IntegrationOptions& integration,
                         int* rollouts) {
  std::vector<ChainNode> nodes(static_cast<std::size_t>(s.n) + 1);
  nodes[0] = s.start;
  internal::ChainJacobian cj;
  internal::RollChain(s.model->lambda(), u, integration, &nodes, &cj);
  ++*rollouts;
  Eigen::MatrixXd jac(5 + 2 * (s.n - 1), 2 * s.n);
  jac.topRows<5>() = internal::ArrivalJacobian(cj, nodes.back(), s.A1);
  for (int k = 1; k < s.n; ++k) jac.middleRows<2>(5 + 2 * (k - 1)) = cj.dx[static_cast<std::size_t>(k)];
  return jac;
}

// One Gauss-Newton step of min |d|^2 subject to r = 0: the linearised KKT system
// [D^T D + eps I, J^T; J, 0] [du; nu] = [-D^T d; -r].
Eigen::VectorXd KktStep(const Eigen::MatrixXd& jac, const Eigen::VectorXd& res) {
  const int p = static_cast<int>(jac.cols());
  const Eigen::MatrixXd J = jac.topRows(5);
  const Eigen::MatrixXd D = jac.bottomRows(jac.rows() - 5);
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(p + 5, p + 5);
  const Eigen::MatrixXd dtd = D.transpose() * D;
  kkt.topLeftCorner(p, p) = dtd + 1e-10 * (1.0 + dtd.diagonal().maxCoeff()) * Eigen::MatrixXd::Identity(p, p);
  kkt.topRightCorner(p, 5) = J.transpose();
  kkt.bottomLeftCorner(5, p) = J;
  Eigen::VectorXd rhs(p + 5);
  rhs.head(p) = -D.transpose() * res.tail(res.size() - 5);
  rhs.tail<5>() = -res.head<5>();
  return internal::FullPivLuSolve(kkt, rhs).head(p);
}

bool Arrived(const Eigen::VectorXd& r, const ExactArrivalOptions& o) {
  return r.head<2>().norm() <= o.position_tolerance && r.segment<3>(2).norm() <= o.orientation_tolerance;
}

// Merit of a trial point: the arrival conditions dominate (scaled to their tolerances' ratio),
// the deviation counts once they are met.
double Merit(const Eigen::VectorXd& r) { return r.head<5>().norm(); }

void ValidateLimits(const ExactArrivalProblem& p) {
  internal::ValidateRigProblem(p.limits, p.physical, p.x0, p.x1);
  if (p.objective == ArrivalObjective::kFewest)
    internal::ThrowInvalid("objective",
                           ToString(p.objective),
                           "asks for the fewest impulses: that is the fewest-impulse search (SolveFewestImpulses), "
                           "not an exact arrival along a reference");
}

void ValidateProblem(const ExactArrivalProblem& p) {
  if (p.impulses < 3 || p.impulses > kMaxExactImpulses)
    internal::ThrowInvalid("impulses",
                           p.impulses,
                           "must be in [3, " + std::to_string(kMaxExactImpulses) +
                               "] (2n unknowns for the 5 arrival conditions; the Jacobian costs n^2 arcs)");
  internal::ValidateStartAndGoal(p.mu, p.x0, p.x1, p.A0, p.A1);
  const double miss = (p.reference.StartPoint() - p.x0).norm();
  if (!(miss <= 1e-9 * std::max(1.0, p.reference.Length())))
    internal::ThrowInvalid("x0",
                           "(" + internal::FormatNumber(p.x0.x()) + ", " + internal::FormatNumber(p.x0.y()) + ")",
                           "must equal the reference's start point (to 1e-9 of its length)");
  ValidateLimits(p);
}

// The summary's per-impulse report and errors from the final parameters.
void Report(const Setup& s,
            const ExactArrivalProblem& p,
            const Eigen::VectorXd& u,
            const std::vector<ChainNode>& nodes,
            const PlanSummary& plan,
            ExactArrivalSummary& out) {
  out.impulses = internal::ReportImpulses(*s.model, s.mu, nodes, u, p.start_at_rest);
  for (int k = 0; k < s.n; ++k) {
    ExactImpulse& e = out.impulses[static_cast<std::size_t>(k)];
    e.planned_position = s.planned[static_cast<std::size_t>(k)];
    e.planned_delta_psi = plan.steps[static_cast<std::size_t>(k)].delta_psi;
    e.planned_duration = plan.steps[static_cast<std::size_t>(k)].duration;
  }
  const Eigen::VectorXd r = Residuals(s, nodes);
  out.total_time = u.tail(s.n).sum();
  out.x_final = nodes.back().x;
  out.A_final = nodes.back().A;
  out.position_error = r.head<2>().norm();
  out.orientation_error = r.segment<3>(2).norm();
  out.deviation = r.tail(r.size() - 5).norm();
  out.max_pass_displacement = 0.0;
  for (int k = 1; k < s.n; ++k)
    out.max_pass_displacement = std::max(out.max_pass_displacement, r.segment<2>(5 + 2 * (k - 1)).norm());
  if (p.stop_at_goal) out.stop = internal::StopImpulse(*s.model, s.mu, nodes.back(), out.total_time);
}

// The paper's plan along the reference with n uniform segments: the warm start.
PlanSummary WarmStart(const ExactArrivalProblem& p, const ExactArrivalOptions& o) {
  PlanProblem plan;
  plan.model = p.model;
  plan.initial = p.initial;
  plan.mu = p.mu;
  plan.A0 = p.A0;
  plan.path = p.reference;
  plan.partition = {UniformParameter{p.impulses}};
  return PlanImpulses(plan, o.warm_start);
}

Setup MakeSetup(const ExactArrivalProblem& p, const ExactArrivalOptions& o, const PlanSummary& plan) {
  Setup s;
  s.model = &p.model;
  s.mu = p.mu;
  s.n = p.impulses;
  s.start = internal::StartNode(p.model, p.initial, p.mu, p.x0, p.A0);
  s.x1 = p.x1;
  s.A1 = p.A1;
  s.integration = o.integration;
  for (const PlanStep& st : plan.steps) s.planned.push_back(st.p_begin);
  s.planned.push_back(plan.steps.back().p_end);
  return s;
}

// Backtracking from the longest admissible step: at most kMaxStep long (a trust region for goals
// far from the warm start) and keeping every flight time above half its value; shortened while
// it worsens the arrival.
bool TryStep(const Setup& s,
             const Eigen::VectorXd& u,
             const Eigen::VectorXd& du,
             double merit,
             Eigen::VectorXd* u_new,
             std::vector<ChainNode>* nodes,
             Eigen::VectorXd* r_new,
             int* rollouts) {
  constexpr double kMaxStep = 1.0;
  double alpha = std::min(1.0, kMaxStep / std::max(du.norm(), 1e-300));
  for (int k = 0; k < s.n; ++k)
    if (du[s.n + k] < 0) alpha = std::min(alpha, 0.5 * u[s.n + k] / -du[s.n + k]);
  for (int tries = 0; tries < 12; ++tries, alpha *= 0.5) {
    *u_new = u + alpha * du;
    if ((u_new->tail(s.n).array() <= 0).any()) continue;
    RollOut(s, *u_new, *nodes);
    ++*rollouts;
    *r_new = Residuals(s, *nodes);
    if (Merit(*r_new) <= std::max(merit, 1e-9) || Merit(*r_new) < 0.9 * merit) return true;
  }
  return false;
}

// Polish with the last Jacobian (chord steps): the minimum-norm correction of the five arrival
// conditions only, J^T (J J^T)^-1 r, while it reduces them; it moves the pass points by O(|r|).
void Polish(const Setup& s,
            const Eigen::MatrixXd& jac,
            Eigen::VectorXd* u,
            std::vector<ChainNode>* nodes,
            Eigen::VectorXd* r,
            int* rollouts) {
  const Eigen::MatrixXd J = jac.topRows(5);
  const Eigen::MatrixXd jjt = J * J.transpose();
  for (int i = 0; i < 8 && Merit(*r) > 0.0; ++i) {
    const Eigen::VectorXd u_new = *u - J.transpose() * internal::FullPivLuSolve(jjt, r->head<5>());
    if ((u_new.tail(s.n).array() <= 0).any()) return;
    std::vector<ChainNode> trial;
    RollOut(s, u_new, trial);
    ++*rollouts;
    const Eigen::VectorXd r_new = Residuals(s, trial);
    if (!(Merit(r_new) < Merit(*r))) return;
    *u = u_new;
    *nodes = trial;
    *r = r_new;
  }
}

// The rig's limits at mu = 1: the free optimum u when it meets them, else the constrained solve's
// result (constrained_arrival.h). Returns false when no exact arrival meets them.
bool ApplyLimits(const ExactArrivalProblem& p,
                 const ExactArrivalOptions& o,
                 const Setup& s,
                 Eigen::VectorXd* u,
                 std::vector<ChainNode>* nodes,
                 ExactArrivalSummary* out,
                 std::vector<long long>* ticks) {
  internal::ConstrainedSetup cs;
  cs.lambda = p.model.lambda();
  cs.n = s.n;
  cs.start = s.start;
  cs.x1 = s.x1;
  cs.A1 = s.A1;
  cs.planned = s.planned;
  cs.limits = p.limits;
  cs.physical = p.physical;
  cs.objective = p.objective;
  cs.start_at_rest = p.start_at_rest;
  cs.stop_at_goal = p.stop_at_goal;
  cs.integration = o.integration;
  cs.jacobian_integration = o.jacobian_integration;
  cs.position_tolerance = o.position_tolerance;
  cs.orientation_tolerance = o.orientation_tolerance;
  if (internal::LimitsAreSlack(cs, *u)) return true;
  const internal::ConstrainedOutcome c = internal::SolveConstrainedArrival(cs, *u);
  *u = c.u;
  RollOut(s, *u, *nodes);
  out->rollouts += c.rollouts + 1;
  out->limits.constrained = true;
  out->limits.active = c.active;
  out->limits.blocking = c.blocking;
  out->limits.evaluations = c.evaluations;
  *ticks = c.ticks;
  return c.arrived;
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

// The solve at mu = 1 (the caller normalises the time scale, see SolveExactArrival).
ExactArrivalSummary SolveNormalised(const ExactArrivalProblem& problem, const ExactArrivalOptions& options) {
  ExactArrivalSummary out;
  const PlanSummary plan = WarmStart(problem, options);
  if (!plan.IsSolutionUsable()) {
    out.status = ExactArrivalStatus::kWarmStartFailed;
    out.message = "warm start: " + plan.BriefReport();
    return out;
  }
  const Setup s = MakeSetup(problem, options, plan);
  Eigen::VectorXd u(2 * s.n);
  for (int k = 0; k < s.n; ++k) {
    u[k] = plan.steps[static_cast<std::size_t>(k)].delta_psi;
    u[s.n + k] = plan.steps[static_cast<std::size_t>(k)].duration;
  }
  std::vector<ChainNode> nodes;
  try {
    RollOut(s, u, nodes);
    out.rollouts = 1;
    Eigen::VectorXd r = Residuals(s, nodes);
    out.planned_position_error = r.head<2>().norm();
    out.planned_orientation_error = r.segment<3>(2).norm();
    out.planned_total_time = u.tail(s.n).sum();
    bool stalled = false;
    double deviation = 0.0;
    Eigen::MatrixXd jac;
    while (out.iterations < options.max_iterations) {
      jac = Jacobian(s, u, options.jacobian_integration, &out.rollouts);
      const Eigen::VectorXd du = KktStep(jac, r);
      ++out.iterations;
      Eigen::VectorXd u_new, r_new;
      std::vector<ChainNode> trial;
      if (!TryStep(s, u, du, Merit(r), &u_new, &trial, &r_new, &out.rollouts)) {
        stalled = true;
        break;
      }
      u = u_new;
      nodes = trial;
      r = r_new;
      // Stop when the deviation has settled (the arrival is then finished by Polish's chord steps,
      // which move the pass points by O(|r|)) or when the step vanished at arrival.
      const double deviation_before = deviation;
      deviation = r.tail(r.size() - 5).norm();
      const bool settled = out.iterations > 1 && Merit(r) < 1e-6 &&
                           std::abs(deviation_before - deviation) <= options.deviation_tolerance * deviation_before;
      if (settled || (Arrived(r, options) && du.norm() <= 1e-8 * (1.0 + u.norm()))) break;
      out.iteration_limit_reached = out.iterations == options.max_iterations;
    }
    if (jac.size() > 0) Polish(s, jac, &u, &nodes, &r, &out.rollouts);
    std::vector<long long> ticks;
    const bool limits_met = problem.limits.Empty() && problem.objective == ArrivalObjective::kDeviation
                                ? true
                                : ApplyLimits(problem, options, s, &u, &nodes, &out, &ticks);
    r = Residuals(s, nodes);
    Report(s, problem, u, nodes, plan, out);
    for (std::size_t k = 0; k < ticks.size(); ++k)
      (k < out.impulses.size() ? out.impulses[k] : *out.stop).tick = ticks[k];
    if (!limits_met) {
      out.status = ExactArrivalStatus::kLimitsNotMet;
      out.message = "no exact arrival found that meets the rig's limits; blocked by " + JoinNames(out.limits.blocking) +
                    " (closest feasible arrival reported)";
    } else if (Arrived(r, options)) {
      out.status = ExactArrivalStatus::kArrived;
      out.message.clear();
      if (out.iteration_limit_reached)
        out.message = "arrived, but the minimisation of the deviation stopped at the iteration limit (" +
                      std::to_string(options.max_iterations) + "): the pass points are not the closest ones found";
    } else {
      out.status = ExactArrivalStatus::kNotReached;
      out.message = stalled ? "no step reduced the arrival error (closest arrival reported)"
                            : "iteration limit reached (closest arrival reported)";
    }
  } catch (const std::runtime_error& e) {
    out.status = ExactArrivalStatus::kIntegrationFailure;
    out.message = e.what();
  }
  return out;
}

// A solution at energy 1 as the solution at energy mu: the motion at energy mu is the motion at
// energy 1 with time scaled by 1/sqrt(mu) (eq. (9): omega scales with sqrt(mu)); positions,
// orientations, angles and the delta psi are the same.
void ScaleEnergy(double mu, ExactImpulse* e) {
  const double time = 1.0 / std::sqrt(mu), rate = std::sqrt(mu);
  e->t_impulse *= time;
  e->duration *= time;
  e->planned_duration *= time;
  e->delta_omega *= rate;
  e->plate_velocity_change *= rate;
  e->mu_before *= mu;  // 1 -> mu, 0 (at rest) stays 0
  e->mu_after *= mu;
}

// The limits in the time scale of mu = 1 (times x sqrt(mu), velocities and impulses / sqrt(mu)).
RigLimits NormalisedLimits(RigLimits l, double mu) {
  const double rate = std::sqrt(mu);
  l.tick *= rate;
  l.min_interval *= rate;
  l.max_plate_velocity_change /= rate;
  l.max_plate_impulse /= rate;
  l.max_force /= rate;
  return l;
}

// Impulse times on the grid exactly (t_impulse = index x tick), the flights their differences.
void PlaceOnGrid(double tick, ExactArrivalSummary* out) {
  out->total_time = internal::PlaceOnGrid(tick, &out->impulses, &out->stop, out->total_time);
}

}  // namespace

ExactArrivalSummary SolveExactArrival(const ExactArrivalProblem& problem, const ExactArrivalOptions& options) {
  const std::string err = options.Validate();
  if (!err.empty()) throw std::invalid_argument(err);
  ValidateProblem(problem);
  // Solved in the time scale of mu = 1, so that every mu gives the same pass points (the iteration,
  // its step bound and its tolerances then see the same numbers for every mu).
  if (problem.mu == 1.0) {
    ExactArrivalSummary out = SolveNormalised(problem, options);
    PlaceOnGrid(problem.limits.tick, &out);
    return out;
  }
  ExactArrivalProblem unit = problem;
  unit.mu = 1.0;
  unit.limits = NormalisedLimits(problem.limits, problem.mu);
  ExactArrivalSummary out = SolveNormalised(unit, options);
  for (ExactImpulse& e : out.impulses) ScaleEnergy(problem.mu, &e);
  if (out.stop) ScaleEnergy(problem.mu, &*out.stop);
  out.total_time /= std::sqrt(problem.mu);
  out.planned_total_time /= std::sqrt(problem.mu);
  PlaceOnGrid(problem.limits.tick, &out);
  return out;
}

ReplayResult ReplayExactArrival(const ExactArrivalProblem& problem,
                                const std::vector<ExactImpulse>& impulses,
                                const IntegrationOptions& integration) {
  BallState state = StateFromAngles(problem.initial, problem.mu, problem.model);
  ReplayResult out;
  out.x = problem.x0;
  out.A = AlignOrientationToAxis(problem.A0, state.z);
  for (std::size_t k = 0; k < impulses.size(); ++k) {
    const AngleState angles = AnglesFromState(state, problem.model);
    const plateball::Impulse imp = EnergyPreservingImpulse(angles, problem.mu, impulses[k].delta_psi, problem.model);
    const FreeMotion motion(problem.model, FreeMotionStart{imp.state_after, out.x, out.A}, integration);
    const MotionSample end = motion.At(impulses[k].duration);
    state = end.state;
    out.x = end.x;
    out.A = end.A;
  }
  out.position_error = (out.x - problem.x1).norm();
  out.orientation_error = LogSO3(problem.A1.transpose() * out.A).norm();
  return out;
}

namespace internal {

void ValidateStartAndGoal(double mu,
                          const Eigen::Vector2d& x0,
                          const Eigen::Vector2d& x1,
                          const Eigen::Matrix3d& A0,
                          const Eigen::Matrix3d& A1) {
  RequireEnergy("mu", mu);
  RequireCoordinates("x0", x0);
  RequireCoordinates("x1", x1);
  RequireFinite("A0", A0);
  RequireFinite("A1", A1);
  if (!IsRotation(A0, 1e-9)) ThrowInvalid("A0", "(matrix)", "not a rotation matrix (to 1e-9)");
  if (!IsRotation(A1, 1e-9)) ThrowInvalid("A1", "(matrix)", "not a rotation matrix (to 1e-9)");
}

ChainNode StartNode(const BallModel& model,
                    const AngleState& initial,
                    double mu,
                    const Eigen::Vector2d& x0,
                    const Eigen::Matrix3d& A0) {
  const BallState state = StateFromAngles(initial, mu, model);
  ChainNode start;
  start.z = state.z;
  start.k = ConservedMomentum(state, model);
  start.x = x0;
  start.A = AlignOrientationToAxis(A0, state.z);
  return start;
}

std::vector<ExactImpulse> ReportImpulses(const BallModel& model,
                                         double mu,
                                         const std::vector<ChainNode>& nodes,
                                         const Eigen::VectorXd& u,
                                         bool start_at_rest) {
  const int n = static_cast<int>(u.size() / 2);
  std::vector<ExactImpulse> out;
  double t = 0.0;
  for (int k = 0; k < n; ++k) {
    const ChainNode& a = nodes[static_cast<std::size_t>(k)];
    ExactImpulse e;
    e.t_impulse = t;
    e.position = a.x;
    e.delta_psi = u[k];
    e.duration = u[n + k];
    e.angles_before = AnglesFromState({a.z, OmegaFromMomentum(a.z, a.k, model)}, model);
    const plateball::Impulse imp = EnergyPreservingImpulse(e.angles_before, mu, e.delta_psi, model);
    e.delta_omega = imp.delta_omega;
    e.plate_velocity_change = imp.plate_velocity_change;
    e.mu_before = e.mu_after = mu;
    if (k == 0 && start_at_rest) {  // from rest: the whole angular velocity is the change
      e.kind = ExactImpulseKind::kStart;
      e.mu_before = 0.0;
      e.delta_omega = imp.state_after.omega;
      e.plate_velocity_change = 2.0 * e.delta_omega.cross(Eigen::Vector3d::UnitZ());
    }
    out.push_back(e);
    t += e.duration;
  }
  return out;
}

ExactImpulse StopImpulse(const BallModel& model, double mu, const ChainNode& end, double total_time) {
  ExactImpulse e;
  e.kind = ExactImpulseKind::kStop;
  e.t_impulse = total_time;
  e.position = end.x;
  const BallState state{end.z, OmegaFromMomentum(end.z, end.k, model)};
  e.angles_before = AnglesFromState(state, model);
  e.delta_omega = -state.omega;
  e.plate_velocity_change = 2.0 * e.delta_omega.cross(Eigen::Vector3d::UnitZ());
  e.mu_before = mu;
  e.mu_after = 0.0;
  return e;
}

}  // namespace internal

}  // namespace plateball
