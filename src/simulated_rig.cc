#include "simulated_rig.h"

#include "arc.h"
#include "check.h"
#include "kinematics.h"
#include "plateball/so3.h"

namespace plateball::internal {

namespace {
// Execute's trial draws on stream `trial`; the measurement noise on a stream of its own.
constexpr std::uint64_t kMeasurementStream = 0x6d65617375726531ULL;
}  // namespace

SimulatedRig::SimulatedRig(const NominalPlan& nominal,
                           const ErrorModel& errors,
                           std::uint64_t seed,
                           std::uint64_t trial,
                           double measurement_noise)
    : nominal_(nominal),
      noise_(errors, seed, trial),
      measurement_random_(seed ^ kMeasurementStream, trial),
      measurement_noise_(measurement_noise),
      restitution_(noise_.Restitution()),
      model_(BallModel::FromLambda(noise_.TrueLambda(nominal.model.lambda()))) {
  ThrowIfInvalid(errors.Validate());
  if (errors.timing != 0.0) ThrowInvalid("timing", errors.timing, "the simulated rig fires on ticks: no jitter");
  if (errors.pulse_duration != 0.0)
    ThrowInvalid("pulse_duration", errors.pulse_duration, "the simulated rig gives ideal impulses");
  if (errors.observation != 0.0)
    ThrowInvalid("observation", errors.observation, "use measurement_noise (per tick) instead");
  RequireNonNegative("measurement_noise", measurement_noise);
  state_ = StateFromAngles(ReduceAngles("initial", nominal.initial), nominal.mu, nominal.model);
  x_ = nominal.pass_points.front();
  A_ = nominal.plan.A0;
}

void SimulatedRig::Roll(double duration) {
  if (duration <= 0.0) return;
  const Eigen::Vector2d k = ConservedMomentum(state_, model_);
  const ArcEnd arc = IntegrateArc(model_.lambda(), state_.z, k, duration, nominal_.options.integration);
  x_ += arc.dx;
  A_ = arc.phi * A_;
  state_ = {arc.z, OmegaFromMomentum(arc.z, k, model_)};
}

void SimulatedRig::Impulse(int k, const Eigen::Vector3d& commanded_delta_omega) {
  state_.omega += noise_.PerturbImpulse(k, commanded_delta_omega);
  state_.omega *= restitution_;
}

ControllerMeasurement SimulatedRig::Measure(long tick) const {
  ControllerMeasurement m;
  m.has_orientation = true;
  m.x = x_;
  m.A = A_;
  m.omega = state_.omega;
  const double s = measurement_noise_;
  if (s == 0.0) return m;
  const auto draw = [&](int slot) {
    return s * measurement_random_.Normal(static_cast<std::uint64_t>(tick) * 8 + static_cast<std::uint64_t>(slot));
  };
  m.x += Eigen::Vector2d(draw(0), draw(1));
  m.A = ExpSO3(Eigen::Vector3d(draw(2), draw(3), draw(4))) * m.A;
  m.omega += Eigen::Vector3d(draw(5), draw(6), 0.0);
  return m;
}

ClosedLoopResult RunClosedLoop(Controller& controller, SimulatedRig& rig, long max_ticks, bool contact_point_only) {
  ClosedLoopResult r;
  const double dt = controller.options().tick_period;
  for (long tick = 0; tick < max_ticks; ++tick) {
    ControllerMeasurement m = rig.Measure(tick);
    m.has_orientation = !contact_point_only;
    const ControllerOutput& out = controller.Update(static_cast<double>(tick) * dt, m);
    ++r.ticks;
    r.status = out.status;
    if (out.status == ControllerStatus::kMeasurementRejected) ++r.rejected;
    if (out.budget_exhausted) ++r.budget_exhausted;
    if (out.impulse) {
      rig.Impulse(out.impulse_index, out.delta_omega);
      ++r.impulses;
    }
    if (out.status == ControllerStatus::kDone || out.status == ControllerStatus::kLost ||
        out.status == ControllerStatus::kIntegrationFailure)
      break;
    rig.Roll(dt);
  }
  r.x = rig.x();
  r.A = rig.A();
  return r;
}

}  // namespace plateball::internal
