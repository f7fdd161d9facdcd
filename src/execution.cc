#include "plateball/execution.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "arc.h"
#include "check.h"
#include "connect.h"
#include "execution_noise.h"
#include "feedback_policy.h"
#include "forced_arc.h"
#include "kinematics.h"
#include "plateball/impulse.h"
#include "plateball/path.h"
#include "plateball/so3.h"

namespace plateball {

std::string ToString(ExecutionStrategy strategy) {
  switch (strategy) {
    case ExecutionStrategy::kOpenLoop:
      return "open_loop";
    case ExecutionStrategy::kFeedback:
      return "feedback";
    case ExecutionStrategy::kFeedbackExact:
      return "feedback_exact";
  }
  return "unknown";
}

ExecutionStrategy ParseExecutionStrategy(const std::string& text, const std::string& field) {
  for (ExecutionStrategy s :
       {ExecutionStrategy::kOpenLoop, ExecutionStrategy::kFeedback, ExecutionStrategy::kFeedbackExact})
    if (text == ToString(s)) return s;
  internal::ThrowInvalid(field, "'" + text + "'", "unknown strategy (open_loop, feedback, feedback_exact)");
}

std::string ToString(ExecutionStatus status) {
  switch (status) {
    case ExecutionStatus::kNotRun:
      return "not_run";
    case ExecutionStatus::kCompleted:
      return "completed";
    case ExecutionStatus::kLost:
      return "lost";
    case ExecutionStatus::kIntegrationFailure:
      return "integration_failure";
  }
  return "unknown";
}

ExactArrivalOptions ExecutionOptions::DefaultExactOptions() {
  ExactArrivalOptions o;
  o.position_tolerance = 1e-10;
  o.orientation_tolerance = 1e-9;
  o.max_iterations = 20;
  o.integration = {1e-12, 1e-12, 2'000'000};
  o.jacobian_integration = {1e-10, 1e-10, 2'000'000};
  return o;
}

std::string ExecutionOptions::Validate() const {
  if (!(miss_tolerance > 0 && miss_tolerance <= 1e6))
    return internal::InvalidValueMessage("miss_tolerance", miss_tolerance, "must be in (0, 1e6]");
  if (exact_window < 3 || exact_window > kMaxExactWindow)
    return internal::InvalidValueMessage(
        "exact_window", exact_window, "must be in [3, " + std::to_string(kMaxExactWindow) + "]");
  const std::string e = exact.Validate();
  return e.empty() ? "" : "exact: " + e;
}

std::string ExecutionSummary::BriefReport() const {
  std::ostringstream os;
  os.precision(4);
  os << "Execution (" << ToString(strategy) << "): " << ToString(status) << ", " << impulses
     << " impulses, position error " << position_error << ", orientation error " << orientation_error
     << " rad, max pass miss " << max_pass_miss << " (" << missed_pass_points << " missed), time " << total_time;
  if (!message.empty()) os << " (" << message << ")";
  return os.str();
}

NominalPlan MakeNominalPlan(const PlanProblem& problem, const PlanOptions& options) {
  return MakeNominalPlan(problem, options, PlanImpulses(problem, options));
}

NominalPlan MakeNominalPlan(const PlanProblem& problem, const PlanOptions& options, PlanSummary plan) {
  NominalPlan n;
  n.model = problem.model;
  n.initial = problem.initial;
  n.mu = problem.mu;
  n.options = options;
  n.plan = std::move(plan);
  if (n.plan.steps.empty()) return n;
  for (const PlanStep& s : n.plan.steps) n.pass_points.push_back(s.p_begin);
  n.pass_points.push_back(n.plan.steps.back().p_end);
  n.goal = n.pass_points.back();
  n.goal_orientation = n.plan.A_planned;
  n.plan_orientation_error = RotationAngle(n.plan.A_planned, n.plan.A_impulsive);
  return n;
}

namespace {

using internal::kObsMu;
using internal::kObsPhi;
using internal::kObsPsi;
using internal::kObsRot;
using internal::kObsTheta;
using internal::kObsX;
using internal::kObsY;
using internal::kTiming;
using Command = internal::FeedbackCommand;
using Observation = internal::FeedbackObservation;

class Trial {
 public:
  Trial(const ExecutionProblem& p, const ExecutionOptions& o)
      : nominal_(*p.nominal),
        strategy_(p.strategy),
        errors_(p.errors),
        options_(o),
        noise_(p.errors, p.seed, p.trial),
        ball_model_(BallModel::FromLambda(noise_.TrueLambda(nominal_.model.lambda()))),
        pulse_before_(errors_.pulse_causal != 0.0 ? 0.0 : 0.5 * errors_.pulse_duration),
        pulse_after_(errors_.pulse_duration - pulse_before_),
        policy_(nominal_, strategy_, options_) {}

  ExecutionSummary Run();

 private:
  double Draw(int k, int slot, double sigma) const { return noise_.Draw(k, slot, sigma); }
  Observation Observe(int k) const;
  Command Decide(int k);
  void ApplyImpulse(int k, const Eigen::Vector3d& delta_omega);
  double ArcDuration(int k, const Command& c) const;
  void Fly(double duration);
  void Forced(const Eigen::Vector2d& k_rate, double duration);
  void Pulse(int k, const Eigen::Vector3d& delta_omega);
  BallState Predicted(Eigen::Vector2d* x, Eigen::Matrix3d* A = nullptr) const;
  void Finish();

  const NominalPlan& nominal_;
  ExecutionStrategy strategy_;
  ErrorModel errors_;
  const ExecutionOptions& options_;
  internal::ExecutionNoise noise_;
  BallModel ball_model_;  // the true ball
  double pulse_before_;   // a pulse starts this long before its impulse time
  double pulse_after_;    // and ends this long after it
  BallState state_;
  Eigen::Vector2d x_ = Eigen::Vector2d::Zero();
  Eigen::Matrix3d A_ = Eigen::Matrix3d::Identity();
  double time_ = 0.0;
  internal::FeedbackPolicy policy_;  // the feedback strategies' decisions
  ExecutionSummary out_;
};

// The state at the impulse time: with a centred pulse the controller decides at the pulse's start
// for the state it predicts at the pulse's centre.
Observation Trial::Observe(int k) const {
  Observation o;
  const BallState at = Predicted(&o.x, &o.A);
  o.angles = AnglesFromState(at, nominal_.model);
  o.mu = Energy(at, nominal_.model);
  const double s = errors_.observation;
  if (s == 0.0) return o;
  o.x += Eigen::Vector2d(Draw(k, kObsX, s), Draw(k, kObsY, s));
  o.angles = internal::ReduceAngles(
      "observed",
      {o.angles.theta + Draw(k, kObsTheta, s), o.angles.phi + Draw(k, kObsPhi, s), o.angles.psi + Draw(k, kObsPsi, s)});
  o.mu *= 1.0 + Draw(k, kObsMu, s);
  const Eigen::Vector3d w(Draw(k, kObsRot, s), Draw(k, kObsRot + 1, s), Draw(k, kObsRot + 2, s));
  o.A = ExpSO3(w) * o.A;
  return o;
}

Command Trial::Decide(int k) {
  if (strategy_ == ExecutionStrategy::kOpenLoop) {
    const PlanStep& s = nominal_.plan.steps[static_cast<std::size_t>(k)];
    return {s.delta_omega, s.duration, s.delta_psi};
  }
  Command c;
  if (!policy_.Decide(k, Observe(k), true, &c)) {
    out_.status = policy_.status();
    out_.message = policy_.message();
  }
  out_.exact_solves = policy_.exact_solves();
  out_.exact_failures = policy_.exact_failures();
  return c;
}

// The plate adds the commanded delta_omega, turned and scaled by the impulse errors, to the true
// horizontal angular velocity; the restitution then scales the speed.
void Trial::ApplyImpulse(int k, const Eigen::Vector3d& delta_omega) {
  const Eigen::Vector3d d = noise_.PerturbImpulse(k, delta_omega);
  state_.omega += d;
  if (errors_.energy_loss != 0.0) state_.omega *= noise_.Restitution();
  ++out_.impulses;
}

// Open loop fires at the planned absolute times (plus jitter); feedback after the commanded
// flight time (plus jitter). The end is measured without jitter.
double Trial::ArcDuration(int k, const Command& c) const {
  const int n = static_cast<int>(nominal_.pass_points.size()) - 1;
  const double jitter = k + 1 < n ? Draw(k + 1, kTiming, errors_.timing) : 0.0;
  if (strategy_ != ExecutionStrategy::kOpenLoop) return std::max(0.0, c.duration + jitter);
  const auto& steps = nominal_.plan.steps;
  const double next = k + 1 < n ? steps[static_cast<std::size_t>(k) + 1].t_impulse : nominal_.plan.total_time;
  return std::max(0.0, next + jitter - time_);
}

void Trial::Fly(double duration) {
  const Eigen::Vector2d k_mom = ConservedMomentum(state_, ball_model_);
  const internal::ArcEnd arc =
      internal::IntegrateArc(ball_model_.lambda(), state_.z, k_mom, duration, nominal_.options.integration);
  x_ += arc.dx;
  A_ = arc.phi * A_;
  state_ = {arc.z, OmegaFromMomentum(arc.z, k_mom, ball_model_)};
  time_ += duration;
}

// A segment of constant K rate (zero: free flight; negative duration: back in time).
void Trial::Forced(const Eigen::Vector2d& k_rate, double duration) {
  const internal::ForcedArcEnd arc = internal::IntegrateForcedArc(ball_model_.lambda(),
                                                                  state_.z,
                                                                  ConservedMomentum(state_, ball_model_),
                                                                  k_rate,
                                                                  duration,
                                                                  nominal_.options.integration);
  x_ += arc.dx;
  A_ = arc.phi * A_;
  state_ = {arc.z, OmegaFromMomentum(arc.z, arc.k, ball_model_)};
  time_ += duration;
}

// The state at the impulse time: free flight over the time before the pulse's centre.
BallState Trial::Predicted(Eigen::Vector2d* x, Eigen::Matrix3d* A) const {
  *x = x_;
  if (A != nullptr) *A = A_;
  if (pulse_before_ == 0.0) return state_;
  const Eigen::Vector2d k_mom = ConservedMomentum(state_, ball_model_);
  const internal::ArcEnd arc =
      internal::IntegrateArc(ball_model_.lambda(), state_.z, k_mom, pulse_before_, nominal_.options.integration);
  *x += arc.dx;
  if (A != nullptr) *A = arc.phi * A_;
  return {arc.z, OmegaFromMomentum(arc.z, k_mom, ball_model_)};
}

// A finite pulse: the constant force whose impulse would give the (error-perturbed) jump at the
// impulse time's orientation, i.e. the ideal jump of K spread evenly over the pulse.
void Trial::Pulse(int k, const Eigen::Vector3d& delta_omega) {
  const Eigen::Vector3d d = noise_.PerturbImpulse(k, delta_omega);
  Eigen::Vector2d x;
  const BallState at = Predicted(&x);
  BallState jumped = at;
  jumped.omega += d;
  const Eigen::Vector2d dk = ConservedMomentum(jumped, ball_model_) - ConservedMomentum(at, ball_model_);
  Forced(dk / errors_.pulse_duration, errors_.pulse_duration);
  if (errors_.energy_loss != 0.0) state_.omega *= noise_.Restitution();
  ++out_.impulses;
}

void Trial::Finish() {
  out_.x_final = x_;
  out_.A_final = ProjectToSO3(A_);
  out_.position_error = (x_ - nominal_.goal).norm();
  out_.orientation_error = RotationAngle(nominal_.goal_orientation, out_.A_final);
  out_.total_time = time_;
  out_.mu_final = Energy(state_, nominal_.model);
  if (!std::isfinite(out_.orientation_error)) out_.orientation_error = M_PI;  // never a NaN in a summary
  for (double m : out_.pass_misses) {
    out_.max_pass_miss = std::max(out_.max_pass_miss, m);
    if (m > options_.miss_tolerance) ++out_.missed_pass_points;
  }
}

ExecutionSummary Trial::Run() {
  out_.strategy = strategy_;
  out_.lambda = ball_model_.lambda();
  out_.status = ExecutionStatus::kCompleted;
  out_.message.clear();
  state_ = StateFromAngles(internal::ReduceAngles("initial", nominal_.initial), nominal_.mu, nominal_.model);
  x_ = nominal_.pass_points.front();
  A_ = nominal_.plan.A0;
  const int n = static_cast<int>(nominal_.pass_points.size()) - 1;
  const bool pulsed = errors_.pulse_duration > 0.0;
  try {
    if (pulsed) Forced(Eigen::Vector2d::Zero(), -pulse_before_);  // the ball rolled freely before
    for (int k = 0; k < n && out_.status == ExecutionStatus::kCompleted; ++k) {
      const Command c = Decide(k);
      if (out_.status != ExecutionStatus::kCompleted) break;
      if (!pulsed) {
        ApplyImpulse(k, c.delta_omega);
        Fly(ArcDuration(k, c));
      } else {
        Pulse(k, c.delta_omega);
        const double flight = ArcDuration(k, c) - (k + 1 < n ? pulse_before_ : 0.0) -
                              (strategy_ == ExecutionStrategy::kOpenLoop ? 0.0 : pulse_after_);
        if (flight < 0.0)
          internal::ThrowInvalid("pulse_duration",
                                 errors_.pulse_duration,
                                 "the pulse of impulse " + std::to_string(k) + " overlaps the next one or the end");
        if (flight > 0.0) Fly(flight);
      }
      Eigen::Vector2d x;
      const BallState at = k + 1 < n && pulsed ? Predicted(&x) : BallState{};
      if (!(k + 1 < n && pulsed)) x = x_;
      out_.pass_misses.push_back((x - nominal_.pass_points[static_cast<std::size_t>(k) + 1]).norm());
      out_.pass_speeds.push_back((k + 1 < n && pulsed ? at : state_).omega.head<2>().norm());
    }
  } catch (const std::runtime_error& e) {
    out_.status = ExecutionStatus::kIntegrationFailure;
    out_.message = e.what();
  } catch (const std::invalid_argument& e) {
    // The ball left what the controller can handle (e.g. its energy below the join's 1e-12
    // after many lossy impulses): this trial is lost, the study goes on.
    out_.status = ExecutionStatus::kLost;
    out_.message = "impulse " + std::to_string(out_.impulses) + ": " + e.what();
  }
  Finish();
  return out_;
}

}  // namespace

std::string PulseScheduleError(const NominalPlan& nominal, const ErrorModel& errors) {
  const double d = errors.pulse_duration;
  if (d == 0.0) return {};
  const auto& steps = nominal.plan.steps;
  const double after = errors.pulse_causal != 0.0 ? d : 0.5 * d;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const bool last = k + 1 == steps.size();
    const double flight = (last ? nominal.plan.total_time : steps[k + 1].t_impulse) - steps[k].t_impulse;
    if (flight < (last ? after : d))
      return internal::InvalidValueMessage("pulse_duration",
                                           d,
                                           "longer than the flight " + std::to_string(k) +
                                               (last ? " -> end (" : " -> " + std::to_string(k + 1) + " (") +
                                               internal::FormatNumber(flight) + "): the pulses would overlap");
  }
  return {};
}

ExecutionSummary Execute(const ExecutionProblem& problem, const ExecutionOptions& options) {
  if (!problem.nominal) internal::ThrowInvalid("nominal", "null", "a nominal plan is required (MakeNominalPlan)");
  if (!problem.nominal->plan.IsSolutionUsable())
    internal::ThrowInvalid("nominal.plan.status",
                           "'" + ToString(problem.nominal->plan.status) + "'",
                           "the nominal plan must be usable: " + problem.nominal->plan.message);
  internal::ThrowIfInvalid(problem.errors.Validate());
  internal::ThrowIfInvalid(PulseScheduleError(*problem.nominal, problem.errors));
  internal::ThrowIfInvalid(options.Validate());
  return Trial(problem, options).Run();
}

namespace {
constexpr double kPulseAim = 0.9;

// Final deviation of an open-loop execution with the given pulses from `ideal`.
double PulsedDeviation(const std::shared_ptr<const NominalPlan>& nominal,
                       const ExecutionSummary& ideal,
                       double duration,
                       bool causal) {
  ExecutionProblem p;
  p.nominal = nominal;
  p.strategy = ExecutionStrategy::kOpenLoop;
  p.errors.pulse_duration = duration;
  p.errors.pulse_causal = causal ? 1.0 : 0.0;
  const ExecutionSummary s = Execute(p);
  if (s.status != ExecutionStatus::kCompleted) return std::numeric_limits<double>::infinity();
  return (s.x_final - ideal.x_final).norm() + RotationAngle(s.A_final, ideal.A_final);
}
}  // namespace

PulseDurationChoice ChoosePulseDuration(const std::shared_ptr<const NominalPlan>& nominal,
                                        double tolerance,
                                        bool causal) {
  internal::RequirePositive("tolerance", tolerance);
  if (!nominal) internal::ThrowInvalid("nominal", "null", "a nominal plan is required (MakeNominalPlan)");
  ExecutionProblem ideal_problem;
  ideal_problem.nominal = nominal;
  const ExecutionSummary ideal = Execute(ideal_problem);
  const auto& steps = nominal->plan.steps;
  double shortest = nominal->plan.total_time - (steps.empty() ? 0.0 : steps.back().t_impulse);
  for (std::size_t k = 0; k + 1 < steps.size(); ++k)
    shortest = std::min(shortest, steps[k + 1].t_impulse - steps[k].t_impulse);
  PulseDurationChoice c;
  const double d0 = 0.1 * shortest;
  const double e0 = PulsedDeviation(nominal, ideal, d0, causal);
  ++c.executions;
  // Aim at 0.9 tolerance: the fitted order holds to a few per cent, not exactly.
  const double scale = e0 > 0 ? kPulseAim * tolerance / e0 : 1.0;
  c.duration = std::min(shortest, d0 * (causal ? scale : std::sqrt(scale)));
  c.measured_error = PulsedDeviation(nominal, ideal, c.duration, causal);
  ++c.executions;
  for (int halvings = 0; c.measured_error > tolerance && halvings < 8; ++halvings) {
    c.duration *= 0.5;
    c.measured_error = PulsedDeviation(nominal, ideal, c.duration, causal);
    ++c.executions;
  }
  c.within = c.measured_error <= tolerance;
  return c;
}

}  // namespace plateball
