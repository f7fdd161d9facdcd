#include "rig/twin_loop.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/number_format.h"
#include "plateball/ball_state.h"
#include "plateball/error_model.h"
#include "plateball/plate_impulse.h"
#include "plateball/so3.h"

namespace plateball::tools::rig {
namespace {

constexpr double kMaxSteps = 1e8;  // as the replay: about 10 minutes of RK4 on one core

std::string Bad(const std::string& field, double value, const std::string& what) {
  return field + ": value " + FormatNumber(value) + ": " + what;
}

// The upper plate's half side in radii: twice the farthest pass point plus the longest flight at a
// speed of 1.5 sqrt(mu / min(1, lambda)) (eq. (9) bounds |x'| by sqrt(mu / min(1, lambda)); the half
// more leaves room for the errors' energy).
double PlateHalfSize(const NominalPlan& nominal, const TwinSettings& settings) {
  double extent = 0.0, flight = 0.0, mu = nominal.mu;
  for (const Eigen::Vector2d& p : nominal.pass_points)
    extent = std::max(extent, (p - nominal.pass_points.front()).norm());
  for (const PlanStep& s : nominal.plan.steps) {
    flight = std::max(flight, s.duration);
    mu = std::max(mu, s.mu);
  }
  const double speed = 1.5 * std::sqrt(mu / std::min(1.0, nominal.model.lambda()));
  return std::max(settings.plate_half_size_radii, 2 * (extent + speed * flight) + 10);
}

// The engine, its step and what it saw; a causal pulse in progress.
class Plant {
 public:
  Plant(const NominalPlan& nominal,
        const PhysicalParameters& ball,
        const TwinSettings& settings,
        double pulse_duration,
        TwinLoopRun* run)
      : twin_(ball, settings), ball_(ball), pulse_duration_(pulse_duration), run_(run) {
    const BallState start = StateFromAngles(nominal.initial, nominal.mu, nominal.model);
    twin_.SetState(0.0, nominal.pass_points.front(), nominal.plan.A0, start.omega);
  }
  // Motion over `duration`: the pulse's force until its end, then none; each part in equal steps of
  // at most the settings' timestep. The restitution follows a pulse at its end.
  void Advance(double duration) {
    const double end = t_ + duration;
    while (pulse_end_ > t_ && pulse_end_ <= end) {
      Steps(pulse_end_ - t_, force_);
      if (restitution_ != 1.0) twin_.SetAngularVelocity(restitution_ * twin_.State().omega);
      pulse_end_ = -1.0;
    }
    Steps(end - t_, pulse_end_ > t_ ? force_ : Eigen::Vector2d::Zero());
  }
  // Impulse k: the jump the plate gives (the errors' draw for k), then the restitution; an ideal
  // jump, or a pulse J/D of the applied jump's plate impulse from now on.
  TwinLoopImpulse Impulse(int k,
                          const Eigen::Vector3d& commanded,
                          const TrialErrors& errors,
                          const PhysicalParameters& physical) {
    const TwinState s = twin_.State();
    TwinLoopImpulse r;
    r.k = k;
    r.t = t_;
    r.x = s.x;
    r.delta_omega = commanded;
    r.applied = errors.PerturbImpulse(k, commanded);
    r.plate_impulse = PlateImpulseFor(physical, s.A.col(2), commanded).plate;
    if (pulse_duration_ == 0.0) {
      twin_.SetAngularVelocity(errors.Restitution() * (s.omega + r.applied));
      return r;
    }
    if (pulse_end_ > t_)
      throw std::runtime_error("impulse " + std::to_string(k) + " at t = " + FormatNumber(t_) +
                               " s fires before the pulse of the previous one ends (pulse_duration too long)");
    r.pulse_impulse = PlateImpulseFor(ball_, s.A.col(2), r.applied).plate;
    force_ = r.pulse_impulse.head<2>() / pulse_duration_;
    pulse_end_ = t_ + pulse_duration_;
    restitution_ = errors.Restitution();
    return r;
  }
  void Finish(const NominalPlan& nominal) {
    const TwinState s = twin_.State();
    run_->t_end = t_;
    run_->x = s.x;
    run_->A = s.A;
    run_->position_error = (s.x - nominal.goal).norm();
    run_->orientation_error = RotationAngle(nominal.goal_orientation, s.A);
  }
  TwinState State() const { return twin_.State(); }
  double time() const { return t_; }

 private:
  void Steps(double duration, const Eigen::Vector2d& force) {
    if (!(duration > 0)) return;
    const int n = std::max(1, static_cast<int>(std::ceil(duration / twin_.settings().timestep - 1e-9)));
    for (int i = 0; i < n; ++i) {
      twin_.Step(duration / n, force);
      const TwinState s = twin_.State();
      if (s.contacts < 2)
        throw std::runtime_error("the ball left the plates in the engine at t = " + FormatNumber(s.t) + " s (" +
                                 std::to_string(s.contacts) + " contacts)");
      run_->max_slip_speed = std::max(run_->max_slip_speed, s.slip_speed);
      run_->max_spin_rate = std::max(run_->max_spin_rate, s.spin_rate);
    }
    run_->steps += n;
    t_ += duration;
  }

  MujocoTwin twin_;
  PhysicalParameters ball_;
  double pulse_duration_;
  TwinLoopRun* run_;
  double t_ = 0.0;           // the run's time: the sum of the steps (the engine's clock rounds)
  double pulse_end_ = -1.0;  // the running pulse's end (none when <= t_)
  Eigen::Vector2d force_ = Eigen::Vector2d::Zero();
  double restitution_ = 1.0;
};

// The twin's settings for a run, the ball with the trial's lambda, and the step count's bound.
struct Setup {
  TwinSettings settings;
  PhysicalParameters ball;
};

Setup SetupFor(const NominalPlan& nominal,
               const PhysicalParameters& physical,
               const TrialErrors& errors,
               const TwinLoopOptions& options,
               double span) {
  if (const std::string m = options.Validate(); !m.empty()) throw std::invalid_argument(m);
  RequireTwinModelled(errors.errors(), "errors");
  if (span / options.settings.timestep > kMaxSteps)
    throw std::invalid_argument(Bad("timestep",
                                    options.settings.timestep,
                                    "the run would take more than 1e8 engine steps over " + FormatNumber(span) + " s"));
  if (!(std::isfinite(options.pulse_duration) && options.pulse_duration >= 0))
    throw std::invalid_argument(
        Bad("pulse_duration", options.pulse_duration, "must be finite and >= 0 s (0: ideal jumps)"));
  if (options.pulse_duration > 0) {
    const RigPlan plan = RigPlanOf(nominal, physical);
    CheckPulseWindows(plan, options.pulse_duration, "pulse_duration");
    CheckPulseFriction(plan, options.pulse_duration, options.settings, "pulse_duration");
  }
  Setup s;
  s.settings = options.settings;
  s.settings.plate_half_size_radii = PlateHalfSize(nominal, options.settings);
  s.ball = errors.errors().lambda == 0.0
               ? physical
               : BallWithLambda(physical, errors.TrueLambda(nominal.model.lambda()), "errors.lambda");
  return s;
}

}  // namespace

std::string TwinLoopOptions::Validate() const { return settings.Validate(); }

void RequireTwinModelled(const ErrorModel& e, const std::string& field) {
  const auto no = [&](const char* key, double v, const char* what) {
    if (v != 0.0) throw std::invalid_argument(Bad(ErrorModelKeyField(field, key), v, what));
  };
  no("timing", e.timing, "the twin's loop fires on ticks: no jitter");
  no("pulse_duration", e.pulse_duration, "the twin's loop gives ideal impulses");
  no("observation", e.observation, "the twin's loop measures the engine's ball exactly");
}

PhysicalParameters BallWithLambda(const PhysicalParameters& p, double lambda, const std::string& field) {
  // lambda = (alpha + beta) / (1 + beta), alpha = I3 / I1, beta = M r^2 / I1 (ball_model.h).
  const double beta = p.EffectiveMass() * p.radius * p.radius / p.inertia_1;
  PhysicalParameters out = p;
  out.inertia_3 = (lambda * (1 + beta) - beta) * p.inertia_1;
  std::string why = out.inertia_3 > 0 ? out.Validate() : "I3 would not be positive";
  if (why.empty()) why = TwinBuildableMessage(out);
  if (!why.empty())
    throw std::invalid_argument(Bad(field,
                                    lambda,
                                    "the twin realises the trial's lambda by I3 = " + FormatNumber(out.inertia_3) +
                                        ", not a ball it can build: " + why));
  return out;
}

RigPlan RigPlanOf(const NominalPlan& nominal, const PhysicalParameters& physical) {
  RigPlan plan;
  plan.physical = physical;
  plan.model = nominal.model;
  plan.integration = nominal.options.integration;
  plan.start = StateFromAngles(nominal.initial, nominal.mu, nominal.model);
  plan.x0 = nominal.pass_points.front();
  plan.A0 = nominal.plan.A0;
  plan.t_end = nominal.plan.total_time;
  for (const PlanStep& step : nominal.plan.steps) {
    RigImpulse k;
    k.t = step.t_impulse;
    k.z = step.state_before.z;
    k.delta_omega = step.delta_omega;
    k.omega_after = step.state_before.omega + step.delta_omega;
    plan.impulses.push_back(k);
  }
  return plan;
}

TwinLoopRun RunTwinClosedLoop(Controller& controller,
                              const PhysicalParameters& physical,
                              const TrialErrors& errors,
                              const TwinLoopOptions& options) {
  const NominalPlan& nominal = controller.nominal();
  const double tick = controller.options().tick_period;
  const long max_ticks = std::lround(2.0 * nominal.plan.total_time / tick) + 2;
  const Setup setup = SetupFor(nominal, physical, errors, options, static_cast<double>(max_ticks) * tick);
  TwinLoopRun run;
  Plant plant(nominal, setup.ball, setup.settings, options.pulse_duration, &run);
  for (long i = 0; i < max_ticks; ++i) {
    const TwinState s = plant.State();
    ControllerMeasurement m;
    m.x = s.x;
    m.has_orientation = !options.contact_point_only;
    m.A = s.A;
    m.omega = Eigen::Vector3d(s.omega.x(), s.omega.y(), 0.0);  // the twin's spin is reported, not measured
    const ControllerOutput& out = controller.Update(static_cast<double>(i) * tick, m);
    ++run.ticks;
    run.status = out.status;
    if (out.status == ControllerStatus::kMeasurementRejected) ++run.rejected;
    if (out.impulse) {
      TwinLoopImpulse r = plant.Impulse(out.impulse_index, out.delta_omega, errors, physical);
      r.tick = i;
      r.exact_replan = out.exact_replan;
      r.late = out.late;
      run.impulses.push_back(r);
    }
    if (out.status == ControllerStatus::kDone || out.status == ControllerStatus::kLost ||
        out.status == ControllerStatus::kIntegrationFailure) {
      if (out.status != ControllerStatus::kDone) run.message = controller.message();
      break;
    }
    plant.Advance(tick);
  }
  run.exact_solves = controller.exact_solves();
  plant.Finish(nominal);
  return run;
}

TwinLoopRun RunTwinOpenLoop(const NominalPlan& nominal,
                            const PhysicalParameters& physical,
                            const TrialErrors& errors,
                            const TwinLoopOptions& options) {
  const Setup setup = SetupFor(nominal, physical, errors, options, nominal.plan.total_time);
  TwinLoopRun run;
  Plant plant(nominal, setup.ball, setup.settings, options.pulse_duration, &run);
  const std::vector<PlanStep>& steps = nominal.plan.steps;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    plant.Advance(steps[k].t_impulse - plant.time());
    run.impulses.push_back(plant.Impulse(static_cast<int>(k), steps[k].delta_omega, errors, physical));
  }
  plant.Advance(nominal.plan.total_time - plant.time());
  run.status = ControllerStatus::kDone;
  plant.Finish(nominal);
  return run;
}

}  // namespace plateball::tools::rig
